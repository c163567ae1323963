// The standard streams as outputs like any other (README "Conventions"): data
// written to stdout that does not arrive (a full device, a closed pipe, a
// closed descriptor) is an error, never an exit 0.
#pragma once
#include <string>

namespace vbsim::cli {

/// At start: SIGPIPE ignored (a closed pipe becomes a write error, EPIPE), and
/// descriptors 0, 1 and 2 occupied when closed, so that no file opened later
/// takes their number; a closed stdout is reopened so that every write to it
/// fails (EBADF), as writes to a closed descriptor do.
void guard_standard_streams();

/// Flushes stdout; an empty string when everything written reached it, else
/// the reason ("Broken pipe", "No space left on device"). Always empty after
/// ignore_standard_output_errors().
std::string standard_output_error();

/// For --help and --version: text for a reader that may stop early (`| head`),
/// so a stdout that did not take all of it is no error.
void ignore_standard_output_errors();

}  // namespace vbsim::cli
