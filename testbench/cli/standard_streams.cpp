#include "standard_streams.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>

namespace vbsim::cli {

namespace {

bool is_open(int fd) { return ::fcntl(fd, F_GETFD) != -1 || errno != EBADF; }

/// Opens /dev/null onto `fd` (the lowest free number, which is `fd` when the
/// ones below it are open).
void occupy(int fd, int flags) {
  const int got = ::open("/dev/null", flags);
  if (got >= 0 && got != fd) {
    ::dup2(got, fd);
    ::close(got);
  }
}

}  // namespace

void guard_standard_streams() {
  std::signal(SIGPIPE, SIG_IGN);
  // In order, so that each open takes the number wanted. stdout is opened for
  // reading only: a write to it fails with EBADF, as on the closed descriptor.
  if (!is_open(0)) occupy(0, O_RDONLY);
  if (!is_open(1)) occupy(1, O_RDONLY);
  if (!is_open(2)) occupy(2, O_WRONLY);
}

namespace {
bool g_ignore_output_errors = false;
}  // namespace

void ignore_standard_output_errors() { g_ignore_output_errors = true; }

std::string standard_output_error() {
  std::cout.flush();
  if (g_ignore_output_errors) {
    std::fflush(stdout);
    return "";
  }
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  const int flush_errno = errno;
  if (flushed && !std::ferror(stdout) && std::cout.good()) return "";
  if (!flushed && flush_errno != 0) return std::strerror(flush_errno);
  // An earlier write failed and its errno is gone: one more byte, written
  // directly, meets the same fault and names it (ENOSPC, EPIPE, EBADF). The
  // stream has already lost data, so the byte cannot spoil a good output.
  errno = 0;
  if (::write(1, "\n", 1) < 0 && errno != 0) return std::strerror(errno);
  return "write error";
}

}  // namespace vbsim::cli
