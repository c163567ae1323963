// Temporaries a killed run left behind. An output is written as
// "NAME.partial-PID-N" beside NAME (io/atomic_output_file.h); a run killed
// with SIGKILL, or a machine that lost power, leaves that file. Before writing
// NAME again, the temporaries of NAME whose process no longer runs are
// removed: a process that still runs (or a pid now taken by another process)
// keeps its own. The pid is looked up on this machine, so an output directory
// shared with another machine's runs should be one per machine.
#pragma once
#include <string>

namespace vbsim {

/// True when `name` is "BASE.partial-PID-N" (decimal PID and N); PID into `pid`.
bool parse_temporary_name(const std::string& name, const std::string& base, long& pid);

/// True when a process `pid` runs on this machine (or exists but is not ours).
bool process_running(long pid);

/// Removes the temporaries of `path` ("PATH.partial-PID-N", files or
/// directories) whose PID no longer runs; returns how many. Errors (an
/// unreadable directory, a file another user owns) leave what they touch.
int remove_stale_temporaries(const std::string& path) noexcept;

}  // namespace vbsim
