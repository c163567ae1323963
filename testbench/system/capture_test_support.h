// Reading a capture directory in the capture tests: the trace's rays and
// Embree's answers (embree_hits.jsonl) indexed by trace id.
#pragma once
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_vbsim.h"
#include "trace/text_trace_reader.h"

namespace vbsim::test {

inline std::vector<TraceRay> read_trace(const std::filesystem::path& p) {
  TextTraceReader reader(p.string());
  std::vector<TraceRay> rays;
  for (TraceRay tr; reader.next(tr);) rays.push_back(tr);
  return rays;
}

/// One JSON object per trace id, from a capture's embree_hits.jsonl.
inline std::vector<nlohmann::json> read_embree_hits(const std::filesystem::path& p, std::size_t rays) {
  std::vector<nlohmann::json> hits(rays);
  std::istringstream in(read_file(p));
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line);
    hits.at(j["id"].get<std::size_t>()) = j;
  }
  return hits;
}

/// A trace file without its header line (which names the command line).
inline std::string trace_rays_text(const std::filesystem::path& trace) {
  const std::string all = read_file(trace);
  return all.substr(all.find('\n') + 1);
}

}  // namespace vbsim::test
