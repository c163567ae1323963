# `cmake --install`: the model library (lib/libvbsim.a), its public headers
# (include/vbsim/<part>/*.h, include/vbsim/trace_writer.hpp), the presets and
# technology files (share/vbsim/presets, share/vbsim/tech), the examples with
# their own CMakeLists.txt (share/vbsim/examples: testbench/examples), the CMake package
# (lib/cmake/vbsim: find_package(vbsim) -> vbsim::vbsim) and a pkg-config file
# (lib/pkgconfig/vbsim.pc). Every path is relative to the prefix given at
# install time (cmake --install BUILD --prefix DIR), so the package can be
# installed anywhere and moved. Included from model/CMakeLists.txt.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(VBSIM_INSTALL_DATA_DIR ${CMAKE_INSTALL_DATADIR}/vbsim)
set(VBSIM_INSTALL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/vbsim)

set_target_properties(vbsim_model PROPERTIES EXPORT_NAME vbsim OUTPUT_NAME vbsim)
install(TARGETS vbsim_model EXPORT vbsimTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# The headers keep the source tree's layout ("hw/accelerator.h"); the capture
# shim is a preloaded library of its own, not part of the embedding API.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/model/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vbsim
        FILES_MATCHING PATTERN "*.h"
        PATTERN "capture_shim" EXCLUDE PATTERN "include" EXCLUDE PATTERN "presets" EXCLUDE PATTERN "tech" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/model/include/vbsim/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vbsim)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/model/hw/presets/ DESTINATION ${VBSIM_INSTALL_DATA_DIR}/presets)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/model/energy/tech/ DESTINATION ${VBSIM_INSTALL_DATA_DIR}/tech)
# The examples as a user builds them on their own (their CMakeLists.txt finds the
# package); the test driver that builds them stays behind.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/testbench/examples/ DESTINATION ${VBSIM_INSTALL_DATA_DIR}/examples
        PATTERN "installed_package_test.cmake" EXCLUDE)

install(EXPORT vbsimTargets NAMESPACE vbsim:: DESTINATION ${VBSIM_INSTALL_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/scripts/cmake/vbsimConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/package/vbsimConfig.cmake
                              INSTALL_DESTINATION ${VBSIM_INSTALL_CMAKE_DIR}
                              PATH_VARS VBSIM_INSTALL_DATA_DIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/vbsimConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/vbsimConfig.cmake ${PROJECT_BINARY_DIR}/package/vbsimConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/scripts/cmake/vbsim_installed_data_dir.cpp
        DESTINATION ${VBSIM_INSTALL_CMAKE_DIR})

# pkg-config: the prefix found from the .pc file's own place (${pcfiledir}).
file(RELATIVE_PATH VBSIM_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" VBSIM_PC_TO_PREFIX "${VBSIM_PC_TO_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/scripts/cmake/vbsim.pc.in ${PROJECT_BINARY_DIR}/package/vbsim.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/vbsim.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
