// Runs the vbsim program as a user would, for the system tests: exit code and
// everything it printed (stdout and stderr together).
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace vbsim::test {

struct RunResult {
  int exit_code = -1;
  std::string output;
};

/// Runs the shell command `cmd`, stderr joined to stdout.
inline RunResult run_command(const std::string& cmd) {
  RunResult r;
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline RunResult run_vbsim(const std::string& args) { return run_command(std::string(VBSIM_BINARY) + " " + args); }

/// As run_vbsim, through bash rather than sh, for arguments that need it
/// (process substitution <(...)).
inline RunResult run_vbsim_bash(const std::string& args) {
  const auto script = std::filesystem::temp_directory_path() / ("vbsim_bash_" + std::to_string(::getpid()) + ".sh");
  std::ofstream(script) << std::string(VBSIM_BINARY) << " " << args << "\n";
  const RunResult r = run_command("bash " + script.string());
  std::filesystem::remove(script);
  return r;
}

/// A fresh scratch directory for one test; the process id keeps test runs of
/// different build trees (or ctest -j) apart.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("vbsim_system_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline std::string source_dir() { return VBSIM_SOURCE_DIR; }

}  // namespace vbsim::test
