#include "gen_directory.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "io/atomic_output_file.h"
#include "io/json_document.h"

namespace vbsim::cli {

namespace fs = std::filesystem;

namespace {

/// The file names an earlier gen listed (empty without a readable list).
std::set<std::string> owned_files(const fs::path& dir) {
  std::set<std::string> owned;
  const fs::path manifest = dir / kGenManifestName;
  if (!fs::is_regular_file(manifest)) return owned;
  nlohmann::json j;
  try {
    j = read_json_document(manifest.string());
  } catch (const JsonDocumentError&) {
    return owned;  // not a list gen wrote: it owns nothing there
  }
  if (j.is_object() && j.contains("files") && j["files"].is_array())
    for (const auto& f : j["files"])
      if (f.is_string() && fs::path(f.get<std::string>()).filename() == f.get<std::string>())
        owned.insert(f.get<std::string>());  // plain names only: never a path out of `dir`
  return owned;
}

bool is_trace_name(const fs::path& p) { return p.extension() == ".jsonl" || p.extension() == ".vbt"; }

}  // namespace

void prepare_gen_directory(const std::string& dir_text) {
  const fs::path dir(dir_text);
  if (!fs::exists(dir)) return;
  if (!fs::is_directory(dir)) throw std::runtime_error(fmt::format("{}: exists and is not a directory", dir_text));
  const std::set<std::string> owned = owned_files(dir);
  std::vector<std::string> foreign;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (is_trace_name(e.path()) && !owned.count(name)) foreign.push_back(name);
  }
  if (!foreign.empty()) {
    std::sort(foreign.begin(), foreign.end());
    std::string list;
    for (size_t i = 0; i < foreign.size() && i < 5; ++i) list += (i ? ", " : "") + foreign[i];
    if (foreign.size() > 5) list += fmt::format(" and {} more", foreign.size() - 5);
    throw std::runtime_error(fmt::format(
        "{}: holds trace files that vbsim gen did not write ({}); `vbsim score` would include them. "
        "Remove them or choose another directory",
        dir_text, list));
  }
  for (const std::string& name : owned) fs::remove(dir / name);
  fs::remove(dir / kGenManifestName);
}

void write_gen_manifest(const std::string& dir, const std::vector<std::string>& files, bool complete,
                        const nlohmann::json& provenance) {
  nlohmann::json names = nlohmann::json::array();
  for (const std::string& f : files) names.push_back(fs::path(f).filename().string());
  const fs::path path = fs::path(dir) / kGenManifestName;
  const nlohmann::json j = {{"complete", complete}, {"files", names}, {"provenance", provenance}};
  write_output_file(path.string(), j.dump(1) + "\n", "gen's file list");
}

}  // namespace vbsim::cli
