// The exec functions the shim interposes. No exit handler runs when a process
// replaces its image, so before each exec the image's capture is written out
// (prepare_for_exec: every thread's buffered records and the summary); the new
// image, which loads the shim again when LD_PRELOAD is in its environment,
// claims files of its own (capture_output.h). glibc's exec functions do not
// call one another through the dynamic linker, so each one is interposed; each
// then calls the C library's own with the same arguments.
#include <unistd.h>

#include <cstdarg>
#include <vector>

#include "capture_output.h"
#include "real_embree.h"

using namespace vbsim::shim;

namespace {

void before_exec() {
  if (capture_enabled()) prepare_for_exec();
}

/// The arguments of execl, execlp and execle after `first`, up to and with the
/// terminating null pointer; `ap` is left after it (at execle's environment).
std::vector<char*> collect_arguments(const char* first, va_list& ap) {
  std::vector<char*> argv{const_cast<char*>(first)};
  while (argv.back() != nullptr) argv.push_back(va_arg(ap, char*));
  return argv;
}

}  // namespace

extern "C" {

int execve(const char* path, char* const argv[], char* const envp[]) noexcept {
  VBSIM_REAL_LIBC(execve);
  before_exec();
  return real(path, argv, envp);
}

int execv(const char* path, char* const argv[]) noexcept {
  VBSIM_REAL_LIBC(execv);
  before_exec();
  return real(path, argv);
}

int execvp(const char* file, char* const argv[]) noexcept {
  VBSIM_REAL_LIBC(execvp);
  before_exec();
  return real(file, argv);
}

int execvpe(const char* file, char* const argv[], char* const envp[]) noexcept {
  VBSIM_REAL_LIBC(execvpe);
  before_exec();
  return real(file, argv, envp);
}

int fexecve(int fd, char* const argv[], char* const envp[]) noexcept {
  VBSIM_REAL_LIBC(fexecve);
  before_exec();
  return real(fd, argv, envp);
}

int execl(const char* path, const char* arg, ...) noexcept {
  VBSIM_REAL_LIBC(execv);
  va_list ap;
  va_start(ap, arg);
  const std::vector<char*> argv = collect_arguments(arg, ap);
  va_end(ap);
  before_exec();
  return real(path, argv.data());
}

int execlp(const char* file, const char* arg, ...) noexcept {
  VBSIM_REAL_LIBC(execvp);
  va_list ap;
  va_start(ap, arg);
  const std::vector<char*> argv = collect_arguments(arg, ap);
  va_end(ap);
  before_exec();
  return real(file, argv.data());
}

int execle(const char* path, const char* arg, ...) noexcept {
  VBSIM_REAL_LIBC(execve);
  va_list ap;
  va_start(ap, arg);
  const std::vector<char*> argv = collect_arguments(arg, ap);
  char* const* envp = va_arg(ap, char* const*);
  va_end(ap);
  before_exec();
  return real(path, argv.data(), envp);
}

}  // extern "C"
