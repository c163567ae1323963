// Where vbsim's data files are found at run time: the hardware presets
// (presets/NAME.json) and the energy technology files (tech/NAME.json).
//
// Contract, first match wins:
//   1. the environment variable VBSIM_DATA_DIR (the installed layout:
//      $VBSIM_DATA_DIR/presets, $VBSIM_DATA_DIR/tech), an override for a moved
//      install or one's own presets;
//   2. the directory given to set_data_dir(); a program linked against the
//      installed CMake package (find_package(vbsim), target vbsim::vbsim) calls
//      it before main with the package's <prefix>/share/vbsim, wherever the
//      package was installed or moved to (docs/hw-model.md, "Embedding");
//   3. the source tree the library was built from (model/hw/presets,
//      model/energy/tech): the vbsim program and the tests of a build tree.
#pragma once
#include <string>

namespace vbsim {

/// Makes `dir` (a directory holding presets/ and tech/) the data directory,
/// unless VBSIM_DATA_DIR is set. Returns true (so that a static initializer can
/// call it). Not thread-safe: call it before any simulation starts.
bool set_data_dir(const std::string& dir);

/// The directory holding the hardware presets (NAME.json), per the order above.
std::string presets_dir();

/// The directory holding the technology files (NAME.json), per the order above.
std::string tech_dir();

}  // namespace vbsim
