#include "provenance/provenance.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "provenance/file_digest.h"
#include "vbsim_version.h"  // generated at build time (scripts/cmake/write_version.cmake)

namespace vbsim {

namespace {

std::vector<std::string>& stored_command_line() {
  static std::vector<std::string> args;
  return args;
}

/// Checksums already computed in this process (an input often feeds several outputs).
const FileDigest& cached_digest(const std::string& path) {
  static std::map<std::string, FileDigest> cache;
  auto it = cache.find(path);
  if (it == cache.end()) it = cache.emplace(path, sha256_file(path)).first;
  return it->second;
}

}  // namespace

const char* vbsim_version() { return VBSIM_VERSION; }
const char* vbsim_revision() { return VBSIM_REVISION; }
std::string vbsim_version_line() { return fmt::format("vbsim {} (revision {})", VBSIM_VERSION, VBSIM_REVISION); }

void set_command_line(int argc, const char* const* argv) {
  stored_command_line().assign(argv, argv + argc);
}

const std::vector<std::string>& command_line() { return stored_command_line(); }

void omit_from_command_line(const std::string& option) {
  std::vector<std::string>& line = stored_command_line();
  std::vector<std::string> kept;
  for (size_t i = 0; i < line.size(); ++i) {
    if (i > 0 && line[i] == option) {
      ++i;  // its value
      continue;
    }
    if (i > 0 && line[i].rfind(option + "=", 0) == 0) continue;
    kept.push_back(line[i]);
  }
  line = std::move(kept);
}

nlohmann::json provenance_json(const std::vector<std::string>& inputs) {
  nlohmann::json files = nlohmann::json::array();
  std::vector<std::string> seen;
  for (const std::string& path : inputs) {
    if (path.empty() || std::find(seen.begin(), seen.end(), path) != seen.end()) continue;
    seen.push_back(path);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      // A pipe (/dev/stdin, <(...)) was read once, by the run: no checksum to give.
      files.push_back({{"path", path}, {"bytes", nullptr}, {"sha256", nullptr}, {"note", "not a regular file"}});
      continue;
    }
    const FileDigest& d = cached_digest(path);
    files.push_back({{"path", path}, {"bytes", d.bytes}, {"sha256", d.sha256}});
  }
  const nlohmann::json j = {{"program", "vbsim"},
                            {"version", VBSIM_VERSION},
                            {"revision", VBSIM_REVISION},
                            {"command", command_line()},
                            {"inputs", std::move(files)}};
  // Arguments and paths need not be UTF-8: invalid bytes become U+FFFD, so that
  // every JSON writer can dump the object.
  return nlohmann::json::parse(j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

std::string provenance_line(const std::vector<std::string>& inputs) { return provenance_json(inputs).dump(); }

}  // namespace vbsim
