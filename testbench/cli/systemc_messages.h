// SystemC's report messages ("Info: (I703) tracing timescale unit set", warnings)
// go to stderr, never into a command's data on stdout, and info and warning
// messages are dropped when the command runs with -q. Errors and fatal reports
// keep SystemC's default handling (shown on stderr, then thrown or aborted).
#pragma once

namespace vbsim::cli {

/// Installs the handler; main() calls it before any command runs.
void route_systemc_messages_to_stderr();

/// With `quiet`, info and warning reports are not shown.
void set_systemc_quiet(bool quiet);

}  // namespace vbsim::cli
