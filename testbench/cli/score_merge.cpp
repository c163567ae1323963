#include "score_merge.h"

#include <fmt/format.h>

#include <fstream>
#include <set>

#include "io/json_document.h"

namespace vbsim::cli {

namespace {

nlohmann::json read_table(const std::string& path) {
  const nlohmann::json j = read_json_document(path);  // errors name the path and line
  if (!j.is_object() || !j.contains("families") || !j["families"].is_array() || !j.contains("rows") ||
      !j["rows"].is_array() || !j.contains("confidence"))
    throw std::runtime_error(fmt::format("{}: not a score table (vbsim score --out)", path));
  return j;
}

/// The (method, tester) configurations of a table, in row order.
std::vector<std::pair<std::string, std::string>> configurations(const nlohmann::json& table) {
  std::vector<std::pair<std::string, std::string>> out;
  std::set<std::pair<std::string, std::string>> seen;
  for (const auto& r : table["rows"]) {
    std::pair<std::string, std::string> c{r.value("method", ""), r.value("tester", "")};
    if (seen.insert(c).second) out.push_back(c);
  }
  return out;
}

}  // namespace

nlohmann::json merge_score_tables(const std::vector<std::string>& parts, const std::string& command) {
  if (parts.empty()) throw std::runtime_error("score --merge: no score table given");
  nlohmann::json merged = read_table(parts.front());
  nlohmann::json provenances = nlohmann::json::array();  // each part's own, with its traces' checksums
  provenances.push_back({{"path", parts.front()}, {"provenance", merged.value("provenance", nlohmann::json())}});
  const auto configs = configurations(merged);
  std::set<std::string> families;
  for (const auto& f : merged["families"]) families.insert(f.value("name", ""));
  for (size_t i = 1; i < parts.size(); ++i) {
    const nlohmann::json part = read_table(parts[i]);
    if (part["confidence"] != merged["confidence"])
      throw std::runtime_error(fmt::format("{}: confidence settings differ from {}'s", parts[i], parts.front()));
    if (configurations(part) != configs)
      throw std::runtime_error(
          fmt::format("{}: its methods and testers differ from {}'s; merge runs of one method list", parts[i],
                      parts.front()));
    for (const auto& f : part["families"]) {
      if (!families.insert(f.value("name", "")).second)
        throw std::runtime_error(fmt::format("{}: family '{}' is already in an earlier part", parts[i],
                                             f.value("name", "")));
      merged["families"].push_back(f);
    }
    for (const auto& r : part["rows"]) merged["rows"].push_back(r);
    provenances.push_back({{"path", parts[i]}, {"provenance", part.value("provenance", nlohmann::json())}});
  }
  merged["command"] = command;
  merged.erase("provenance");
  merged["parts"] = std::move(provenances);
  return merged;
}

}  // namespace vbsim::cli
