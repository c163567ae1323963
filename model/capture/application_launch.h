// Running the application under the capture shim: a child process with
// LD_PRELOAD naming the shim (ahead of any preload the user set) and
// VBSIM_CAPTURE_DIR naming the raw directory; its standard streams are the
// caller's. The application's own arguments and environment are otherwise
// untouched.
#pragma once
#include <string>
#include <vector>

namespace vbsim::capture {

struct LaunchResult {
  int exit_code = -1;  ///< the exit status when it exited, else -1
  int signal = 0;      ///< the signal that ended it, else 0
  /// SIGINT or SIGTERM that reached this process while the application ran
  /// (Ctrl-C or a SIGTERM to the process group, or to this process alone), else 0.
  int interrupted = 0;
  bool exited_normally() const { return signal == 0 && exit_code == 0; }
  std::string describe() const;  ///< "exited with status 3", "was killed by signal 11 (...)"
};

/// Runs `command` (looked up on PATH like a shell would) and waits for it.
/// While this process waits, SIGINT and SIGTERM are the application's to
/// handle: Ctrl-C reaches it through the process group, a SIGTERM sent to this
/// process is passed on; either is noted in `interrupted`. Throws
/// std::runtime_error when it cannot be started.
LaunchResult run_under_shim(const std::vector<std::string>& command, const std::string& shim_path,
                            const std::string& raw_dir);

/// The shim's path: $VBSIM_CAPTURE_SHIM when set, else libvbsim_capture_shim.so
/// next to the running executable. Throws naming the path when it is missing.
std::string capture_shim_path();

}  // namespace vbsim::capture
