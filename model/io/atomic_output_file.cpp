#include "io/atomic_output_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <vector>

#include <fmt/format.h>

#include "io/stale_temporaries.h"

namespace vbsim {

namespace {

// ---- signal-time cleanup of open temporaries ----
// A fixed table, so that the handler only reads memory and calls unlink(),
// both async-signal-safe. Slots beyond the table are simply not cleaned up.
constexpr int kCleanupSlots = 1024;  // untouched slots cost no memory (zero pages)
constexpr size_t kCleanupPathBytes = 4096;
std::array<std::array<char, kCleanupPathBytes>, kCleanupSlots> g_cleanup_paths;
std::array<std::atomic<bool>, kCleanupSlots> g_cleanup_used{};
std::atomic<bool> g_handlers_installed{false};

extern "C" void remove_temporaries_and_reraise(int sig) {
  for (int i = 0; i < kCleanupSlots; ++i)
    if (g_cleanup_used[i].load()) ::unlink(g_cleanup_paths[i].data());
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

int g_interrupt_exit_code = 130;

extern "C" void remove_temporaries_and_exit(int) {
  for (int i = 0; i < kCleanupSlots; ++i)
    if (g_cleanup_used[i].load()) ::unlink(g_cleanup_paths[i].data());
  static const char kMessage[] = "vbsim: interrupted\n";
  [[maybe_unused]] const ssize_t n = ::write(2, kMessage, sizeof kMessage - 1);
  ::_exit(g_interrupt_exit_code);
}

/// Installs the cleanup handler for SIGINT and SIGTERM where their action is
/// still the default (a program's own handler stays in charge).
void install_cleanup_handlers() {
  if (g_handlers_installed.exchange(true)) return;
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction current {};
    if (sigaction(sig, nullptr, &current) == 0 && current.sa_handler == SIG_DFL)
      std::signal(sig, remove_temporaries_and_reraise);
  }
}

int register_temporary(const std::string& path) {
  if (path.size() >= kCleanupPathBytes) return -1;
  for (int i = 0; i < kCleanupSlots; ++i) {
    bool expected = false;
    if (g_cleanup_used[i].load() || !g_cleanup_used[i].compare_exchange_strong(expected, true)) continue;
    // A signal between the claim and the copy unlinks a stale name of this
    // process (already gone) or "": harmless.
    std::memcpy(g_cleanup_paths[i].data(), path.c_str(), path.size() + 1);
    install_cleanup_handlers();
    return i;
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0) g_cleanup_used[slot].store(false);
}

std::string temporary_name(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return fmt::format("{}.partial-{}-{}", path, ::getpid(), counter.fetch_add(1));
}

std::string reason() { return errno != 0 ? std::strerror(errno) : "I/O error"; }

// ---- held commits ----
struct HeldOutput {
  std::string temp, path;
  int slot;  ///< its place on the cleanup list, -1: none
};
std::atomic<bool> g_holding{false};
std::mutex g_held_mutex;
std::vector<HeldOutput> g_held;  // in the order of their commit()

void hold(std::string temp, std::string path, int slot) {
  std::lock_guard<std::mutex> lock(g_held_mutex);
  g_held.push_back({std::move(temp), std::move(path), slot});
}

}  // namespace

AtomicOutputFile::AtomicOutputFile(std::string path, bool binary) : path_(std::move(path)) {
  if (path_.empty()) throw OutputError("<empty>", "output path is empty");
  struct stat st {};
  if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    in_place_ = true;
    temp_ = path_;
  } else {
    // A symbolic link keeps pointing at the file it names: the new file replaces that file.
    std::error_code ec;
    if (std::filesystem::is_symlink(path_, ec)) {
      const std::filesystem::path target = std::filesystem::canonical(path_, ec);
      if (!ec) path_ = target.string();
    }
    remove_stale_temporaries(path_);  // those of runs that were killed (stale_temporaries.h)
    temp_ = temporary_name(path_);
  }
  std::ios::openmode mode = std::ios::out | std::ios::trunc;
  if (binary) mode |= std::ios::binary;
  errno = 0;
  out_.open(temp_, mode);
  if (!out_) throw OutputError(path_, "cannot create: " + reason());
  if (!in_place_) registry_slot_ = register_temporary(temp_);
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!done_) discard();
}

void AtomicOutputFile::check() const {
  if (!out_) throw OutputError(path_, "write failed: " + reason());
}

void AtomicOutputFile::commit() {
  if (done_) {
    if (!committed_) throw OutputError(path_, "written after it was discarded");
    return;
  }
  errno = 0;
  out_.flush();
  bool ok = static_cast<bool>(out_);
  std::string why = ok ? "" : reason();
  out_.close();
  if (ok && !out_) {
    ok = false;
    why = reason();
  }
  if (ok && !in_place_ && g_holding.load()) {  // complete: renamed by commit_held_outputs()
    hold(temp_, path_, registry_slot_);
    registry_slot_ = -1;
    done_ = committed_ = true;
    return;
  }
  if (ok && !in_place_ && std::rename(temp_.c_str(), path_.c_str()) != 0) {
    ok = false;
    why = fmt::format("cannot rename {} to it: {}", temp_, reason());
  }
  if (!ok) {
    discard();
    throw OutputError(path_, "write failed: " + why);
  }
  unregister_temporary(registry_slot_);
  done_ = committed_ = true;
}

void AtomicOutputFile::discard() noexcept {
  if (done_) return;
  done_ = true;
  if (out_.is_open()) out_.close();
  if (!in_place_) ::unlink(temp_.c_str());
  unregister_temporary(registry_slot_);
}

void hold_output_commits() { g_holding = true; }

void commit_held_outputs() {
  std::lock_guard<std::mutex> lock(g_held_mutex);
  g_holding = false;
  std::string failed_path, why;
  for (const HeldOutput& h : g_held) {
    errno = 0;
    if (failed_path.empty() && std::rename(h.temp.c_str(), h.path.c_str()) != 0) {
      failed_path = h.path;
      why = fmt::format("cannot rename {} to it: {}", h.temp, reason());
    }
    if (!failed_path.empty()) ::unlink(h.temp.c_str());
    unregister_temporary(h.slot);
  }
  g_held.clear();
  if (!failed_path.empty()) throw OutputError(failed_path, "write failed: " + why);
}

void discard_held_outputs() noexcept {
  std::lock_guard<std::mutex> lock(g_held_mutex);
  g_holding = false;
  for (const HeldOutput& h : g_held) {
    ::unlink(h.temp.c_str());
    unregister_temporary(h.slot);
  }
  g_held.clear();
}

std::string finished_output_path(const std::string& path) {
  std::string named = path;
  std::error_code ec;
  if (std::filesystem::is_symlink(path, ec)) {  // as the constructor names it
    const std::filesystem::path target = std::filesystem::canonical(path, ec);
    if (!ec) named = target.string();
  }
  std::lock_guard<std::mutex> lock(g_held_mutex);
  for (auto h = g_held.rbegin(); h != g_held.rend(); ++h)
    if (h->path == named) return h->temp;
  return path;
}

CommitsAtOnce::CommitsAtOnce() : was_holding_(g_holding.exchange(false)) {}
CommitsAtOnce::~CommitsAtOnce() { g_holding = was_holding_; }

void exit_on_interrupt(int exit_code) {
  g_interrupt_exit_code = exit_code;
  g_handlers_installed = true;  // this handler removes the temporaries too
  for (int sig : {SIGINT, SIGTERM}) std::signal(sig, remove_temporaries_and_exit);
}

void write_output_file(const std::string& path, const std::string& text, const char* what) {
  try {
    AtomicOutputFile out(path);
    out.stream() << text;
    out.commit();
  } catch (const OutputError& e) {
    throw OutputError(e.path, fmt::format("{} ({})", e.message, what));
  }
}

}  // namespace vbsim
