# The installed package as a user meets it (ctest: package.installed_examples):
# installs vbsim's build to a fresh prefix, copies the examples the package
# installs (PREFIX/share/vbsim/examples) to a folder of their own and builds
# that copy against the package alone (find_package(vbsim), vbsim::vbsim; no
# header of the source tree on any include path), runs the four examples and
# checks that they print what the examples built with the project print (the
# same library, headers and presets), and that the installed library reads
# the installed presets.
# Then one example again, built with the flags of the installed vbsim.pc.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DIN_TREE_EMBED=... -DIN_TREE_CLOCKED=...
#         -DIN_TREE_CLOSED_LOOP=... -DIN_TREE_PRECISION=... -DCXX_COMPILER=... -P installed_package_test.cmake
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR IN_TREE_EMBED IN_TREE_CLOCKED IN_TREE_CLOSED_LOOP IN_TREE_PRECISION
            CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "installed_package_test: -D${var}= is required")
  endif()
endforeach()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "installed_package_test: ${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

function(expect_line text line what)
  string(FIND "${text}" "${line}\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "installed_package_test: expected '${line}' (${what}) in\n${text}")
  endif()
endfunction()

set(prefix ${WORK_DIR}/prefix)
set(examples ${WORK_DIR}/examples)
set(build ${WORK_DIR}/examples-build)
file(REMOVE_RECURSE ${WORK_DIR})
run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f lib/libvbsim.a lib/cmake/vbsim/vbsimConfig.cmake lib/pkgconfig/vbsim.pc include/vbsim/hw/accelerator.h
          include/vbsim/trace_writer.hpp share/vbsim/presets/small.json share/vbsim/tech/45nm.json
          share/vbsim/examples/CMakeLists.txt share/vbsim/examples/example_main.h
          share/vbsim/examples/reduced_precision/reduced_precision_units.h)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "installed_package_test: ${prefix}/${f} was not installed")
  endif()
endforeach()
if(EXISTS ${prefix}/include/vbsim/capture_shim)
  message(FATAL_ERROR "installed_package_test: the capture shim's headers were installed")
endif()

if(EXISTS ${prefix}/share/vbsim/examples/installed_package_test.cmake)
  message(FATAL_ERROR "installed_package_test: the test driver was installed with the examples")
endif()
if(EXISTS ${prefix}/include/vbsim/reduced_precision OR EXISTS ${prefix}/include/vbsim/hw/examples)
  message(FATAL_ERROR "installed_package_test: example code was installed as part of the library's headers")
endif()

# The installed examples, copied out of the prefix as a user would copy them.
file(COPY ${prefix}/share/vbsim/examples/ DESTINATION ${examples})
# -j2 and ccache (when found, testbench/examples/CMakeLists.txt): one file per example.
run("configure" ${CMAKE_COMMAND} -S ${examples} -B ${build} -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
run("build" ${CMAKE_COMMAND} --build ${build} -j 2)

set(trace ${SOURCE_DIR}/traces/bunny/paths.jsonl)
set(ENV{SYSTEMC_DISABLE_COPYRIGHT_MESSAGE} 1)
unset(ENV{VBSIM_DATA_DIR})
foreach(example embed clocked closed_loop precision)
  if(example STREQUAL "embed")
    set(installed ${build}/embed_accelerator)
    set(in_tree ${IN_TREE_EMBED})
    set(args ${trace} 80)
  elseif(example STREQUAL "closed_loop")
    set(installed ${build}/closed_loop_shader)
    set(in_tree ${IN_TREE_CLOSED_LOOP})
    set(args ${trace} 4)
  elseif(example STREQUAL "precision")
    set(installed ${build}/precision_study)
    set(in_tree ${IN_TREE_PRECISION})
    set(args ${trace} validity-bit small)
  else()
    set(installed ${build}/clocked_design)
    set(in_tree ${IN_TREE_CLOCKED})
    set(args ${trace} small)
  endif()
  run("${installed}" ${installed} ${args})
  set(out_installed "${output}")
  run("${in_tree}" ${in_tree} ${args})
  set(out_in_tree "${output}")
  if(example STREQUAL "embed")
    # The one line that differs: where the presets were read.
    expect_line("${out_installed}" "presets_dir ${prefix}/share/vbsim/presets" "the installed library's presets")
    expect_line("${out_in_tree}" "presets_dir ${SOURCE_DIR}/model/hw/presets" "the source tree's presets")
    string(REGEX REPLACE "presets_dir [^\n]*\n" "" out_installed "${out_installed}")
    string(REGEX REPLACE "presets_dir [^\n]*\n" "" out_in_tree "${out_in_tree}")
  endif()
  if(example STREQUAL "closed_loop")
    if(NOT out_installed MATCHES "\nlater [1-9][0-9]*\n")
      message(FATAL_ERROR "installed_package_test: no closed loop that waited for answers in\n${out_installed}")
    endif()
  elseif(example STREQUAL "precision")
    expect_line("${out_installed}" "${trace}, method validity-bit, preset small, 1008 rays" "every ray of the trace")
    if(NOT out_installed MATCHES "\ntriangle 8 bits ")
      message(FATAL_ERROR "installed_package_test: no reduced-precision run in\n${out_installed}")
    endif()
  else()
    expect_line("${out_installed}" "rays 1008" "every ray of the trace")
  endif()
  if(NOT out_installed STREQUAL out_in_tree)
    message(FATAL_ERROR "installed_package_test: ${installed} printed\n${out_installed}\n"
                        "the example built with the project printed\n${out_in_tree}")
  endif()
  message(STATUS "${installed}:\n${out_installed}")
  set(${example}_in_tree "${out_in_tree}")
endforeach()

# VBSIM_DATA_DIR overrides the package's data directory (io/data_dir.h).
file(COPY ${prefix}/share/vbsim/ DESTINATION ${WORK_DIR}/moved-data)
set(ENV{VBSIM_DATA_DIR} ${WORK_DIR}/moved-data)
run("${build}/embed_accelerator with VBSIM_DATA_DIR" ${build}/embed_accelerator ${trace} 80)
expect_line("${output}" "presets_dir ${WORK_DIR}/moved-data/presets" "the presets of VBSIM_DATA_DIR")

# pkg-config: vbsim.pc finds the prefix from its own place; one example built
# with its flags (the data directory given by its `datadir` variable).
find_program(PKG_CONFIG pkg-config REQUIRED)
find_program(CCACHE ccache)
set(compile ${CXX_COMPILER})
if(CCACHE)
  set(compile ${CCACHE} ${CXX_COMPILER})
endif()
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
run("pkg-config" ${PKG_CONFIG} --cflags --libs vbsim)
separate_arguments(pc_flags UNIX_COMMAND "${output}")
run("pkg-config datadir" ${PKG_CONFIG} --variable=datadir vbsim)
string(STRIP "${output}" pc_datadir)
file(REAL_PATH "${pc_datadir}" pc_datadir)
file(REAL_PATH "${prefix}/share/vbsim" installed_datadir)
if(NOT pc_datadir STREQUAL installed_datadir)
  message(FATAL_ERROR "installed_package_test: vbsim.pc's datadir is ${pc_datadir}, not ${installed_datadir}")
endif()
run("build with pkg-config" ${compile} -std=c++17 -O2 ${SOURCE_DIR}/testbench/examples/clocked_design.cpp
    -o ${WORK_DIR}/clocked_design_pkg_config ${pc_flags})
set(ENV{VBSIM_DATA_DIR} ${pc_datadir})
run("clocked_design built with pkg-config" ${WORK_DIR}/clocked_design_pkg_config ${trace} small)
if(NOT output STREQUAL clocked_in_tree)
  message(FATAL_ERROR "installed_package_test: clocked_design built with pkg-config printed\n${output}\n"
                      "the example built with the project printed\n${clocked_in_tree}")
endif()
