#include "io/stale_temporaries.h"

#include <signal.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>

namespace vbsim {

namespace fs = std::filesystem;

namespace {

/// True when `s` is one or more decimal digits.
bool all_digits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

}  // namespace

bool parse_temporary_name(const std::string& name, const std::string& base, long& pid) {
  const std::string prefix = base + ".partial-";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return false;
  const std::string rest = name.substr(prefix.size());
  const auto dash = rest.find('-');
  if (dash == std::string::npos) return false;
  const std::string pid_text = rest.substr(0, dash), n_text = rest.substr(dash + 1);
  if (!all_digits(pid_text) || !all_digits(n_text) || pid_text.size() > 9) return false;
  pid = std::strtol(pid_text.c_str(), nullptr, 10);
  return pid > 0;
}

bool process_running(long pid) { return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH; }

int remove_stale_temporaries(const std::string& path) noexcept {
  int removed = 0;
  try {
    const fs::path p(path);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    const std::string base = p.filename().string();
    if (base.empty()) return 0;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      long pid = 0;
      if (!parse_temporary_name(it->path().filename().string(), base, pid) || process_running(pid)) continue;
      std::error_code rm;
      if (fs::remove_all(it->path(), rm) > 0 && !rm) ++removed;
    }
  } catch (...) {  // a name that is no valid path, an allocation failure: nothing removed
  }
  return removed;
}

}  // namespace vbsim
