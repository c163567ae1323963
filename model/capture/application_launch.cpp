#include "capture/application_launch.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "capture/raw_capture_format.h"

namespace vbsim::capture {

namespace {

volatile sig_atomic_t g_child = 0;
volatile sig_atomic_t g_interrupted = 0;
/// SIGINT: noted (Ctrl-C reaches the application through the process group).
extern "C" void note_interrupt(int sig) { g_interrupted = sig; }
/// SIGTERM: noted and passed on to the application (sent to this process alone, it would not reach it).
extern "C" void forward_signal(int sig) {
  g_interrupted = sig;
  if (g_child > 0) ::kill(static_cast<pid_t>(g_child), sig);
}

}  // namespace

std::string LaunchResult::describe() const {
  if (signal != 0) return fmt::format("was killed by signal {} ({})", signal, strsignal(signal));
  return fmt::format("exited with status {}", exit_code);
}

std::string capture_shim_path() {
  if (const char* env = std::getenv("VBSIM_CAPTURE_SHIM"); env && *env) {
    if (!std::filesystem::exists(env))
      throw std::runtime_error(fmt::format("VBSIM_CAPTURE_SHIM names {}, which does not exist", env));
    return std::filesystem::absolute(env).string();
  }
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const auto shim = (ec ? std::filesystem::current_path() : exe.parent_path()) / "libvbsim_capture_shim.so";
  if (!std::filesystem::exists(shim))
    throw std::runtime_error(fmt::format("the capture shim {} is missing (it is built with vbsim)", shim.string()));
  return shim.string();
}

LaunchResult run_under_shim(const std::vector<std::string>& command, const std::string& shim_path,
                            const std::string& raw_dir) {
  if (command.empty()) throw std::runtime_error("no application to run: give it after `--`");
  std::string preload = shim_path;
  if (const char* old = std::getenv("LD_PRELOAD"); old && *old) preload += std::string(":") + old;
  std::vector<char*> argv;
  for (const std::string& a : command) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  int ready[2];  // closed on exec; carries errno when exec fails
  if (::pipe2(ready, O_CLOEXEC) != 0) throw std::runtime_error(fmt::format("pipe: {}", std::strerror(errno)));
  // From before the fork until the application has ended, Ctrl-C (sent to the
  // whole process group) and SIGTERM (passed on) are its to handle; this
  // process notes them and waits for its end. (The child's exec resets the
  // handlers to their defaults.)
  g_child = 0;
  g_interrupted = 0;
  struct sigaction note {}, forward {}, old_int {}, old_term {};
  note.sa_handler = note_interrupt;
  forward.sa_handler = forward_signal;
  ::sigaction(SIGINT, &note, &old_int);
  ::sigaction(SIGTERM, &forward, &old_term);
  auto restore_handlers = [&] {
    ::sigaction(SIGINT, &old_int, nullptr);
    ::sigaction(SIGTERM, &old_term, nullptr);
    g_child = 0;
  };
  const pid_t child = ::fork();
  if (child < 0) {
    const int err = errno;
    restore_handlers();
    ::close(ready[0]);
    ::close(ready[1]);
    throw std::runtime_error(fmt::format("fork: {}", std::strerror(err)));
  }
  if (child == 0) {
    ::close(ready[0]);
    ::setenv("LD_PRELOAD", preload.c_str(), 1);
    ::setenv(kCaptureDirEnv, raw_dir.c_str(), 1);
    ::signal(SIGPIPE, SIG_DFL);  // vbsim ignores SIGPIPE (an ignored signal stays ignored across exec)
    ::execvp(argv[0], argv.data());
    const int err = errno;
    (void)!::write(ready[1], &err, sizeof err);
    ::_exit(127);
  }
  g_child = child;
  ::close(ready[1]);
  int exec_errno = 0;
  ssize_t got;
  do got = ::read(ready[0], &exec_errno, sizeof exec_errno);
  while (got < 0 && errno == EINTR);
  const bool exec_failed = got == sizeof exec_errno;
  ::close(ready[0]);
  int status = 0;
  pid_t done;
  do done = ::waitpid(child, &status, 0);
  while (done < 0 && errno == EINTR);
  restore_handlers();
  if (exec_failed) throw std::runtime_error(fmt::format("cannot run {}: {}", command[0], std::strerror(exec_errno)));
  LaunchResult r;
  r.interrupted = g_interrupted;
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  return r;
}

}  // namespace vbsim::capture
