// Compiled into every target that links the installed package's vbsim::vbsim
// (vbsimConfig.cmake adds it, and VBSIM_INSTALLED_DATA_DIR, the package's
// <prefix>/share/vbsim): the library then finds the installed presets and
// technology files wherever the package was installed (io/data_dir.h).
#include "io/data_dir.h"

namespace {
const bool vbsim_data_dir_set = vbsim::set_data_dir(VBSIM_INSTALLED_DATA_DIR);
}  // namespace
