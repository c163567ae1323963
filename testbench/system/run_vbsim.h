// Runs the vbsim program as a user would, for the system tests: exit code and
// everything it printed (stdout and stderr together).
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace vbsim::test {

struct RunResult {
  int exit_code = -1;
  std::string output;
};

/// Runs the shell command `cmd`, reading its stdout.
inline RunResult run_command(const std::string& cmd) {
  RunResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// Runs `vbsim ARGS` through the shell, reading its stdout.
inline RunResult run_vbsim_raw(const std::string& args) { return run_command(std::string(VBSIM_BINARY) + " " + args); }

inline RunResult run_vbsim(const std::string& args) { return run_vbsim_raw(args + " 2>&1"); }

/// As run_vbsim, through bash rather than sh, for arguments that need it
/// (process substitution <(...)).
inline RunResult run_vbsim_bash(const std::string& args) {
  const auto script = std::filesystem::temp_directory_path() / ("vbsim_bash_" + std::to_string(::getpid()) + ".sh");
  std::ofstream(script) << std::string(VBSIM_BINARY) << " " << args << "\n";
  const RunResult r = run_command("bash " + script.string() + " 2>&1");
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

/// Polls `dir` every 10 ms, for up to a minute, until it holds a file whose
/// name contains `fragment` and that has more than `min_bytes` bytes (a
/// running command's output temporary); false when none came.
inline bool wait_for_file(const std::filesystem::path& dir, const std::string& fragment, std::uintmax_t min_bytes = 0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec))
      if (e.path().filename().string().find(fragment) != std::string::npos && e.file_size(ec) > min_bytes) return true;
  }
  return false;
}

/// Exit code, stdout and stderr of one run, kept apart.
struct SplitRun {
  int exit_code = -1;
  std::string out, err;
};

inline SplitRun run_vbsim_split(const std::string& args) {
  static int runs = 0;
  const auto err_file = std::filesystem::temp_directory_path() /
                        ("vbsim_stderr_" + std::to_string(::getpid()) + "_" + std::to_string(++runs));
  const RunResult r = run_vbsim_raw(args + " 2>" + err_file.string());
  SplitRun s{r.exit_code, r.output, read_file(err_file)};
  std::filesystem::remove(err_file);
  return s;
}

/// `text` without what records its making (the command line, checksums): a
/// trace header's "provenance" field, a hits file's first line, a PLY
/// "comment vbsim-provenance" line. What is left is what a seed determines.
inline std::string without_provenance(std::string text) {
  if (text.rfind("{\"format\":\"vbsim-hits\"", 0) == 0) return text.substr(text.find('\n') + 1);
  const size_t line_end = text.find('\n');
  const size_t field = text.find(",\"provenance\":{");
  if (field != std::string::npos && field < line_end) {
    const size_t object_end = text.rfind('}', line_end);  // the header's own closing brace
    text.erase(field, object_end - field);
  }
  const size_t comment = text.find("\ncomment vbsim-provenance ");
  if (comment != std::string::npos) text.erase(comment + 1, text.find('\n', comment + 1) - comment);
  return text;
}

}  // namespace vbsim::test
