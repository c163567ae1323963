#include "capture/reference_comparison.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace vbsim::capture {

namespace {

using json = nlohmann::json;

/// Reads a JSON-lines file one object at a time, naming file and line in errors.
class JsonLines {
 public:
  explicit JsonLines(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw std::runtime_error(fmt::format("{}: cannot open", path));
  }
  bool next(json& out) {
    std::string text;
    while (std::getline(in_, text)) {
      ++line_;
      if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
      try {
        out = json::parse(text);
      } catch (const json::exception& e) {
        fail(fmt::format("not JSON: {}", e.what()));
      }
      if (!out.is_object()) fail("not a JSON object");
      return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw std::runtime_error(fmt::format("{}:{}: {}", path_, line_, message));
  }
  /// The integer field `key` of `j`.
  int64_t integer(const json& j, const char* key) const {
    const auto it = j.find(key);
    if (it == j.end() || !it->is_number_integer()) fail(fmt::format("field '{}': missing or not an integer", key));
    return it->get<int64_t>();
  }

 private:
  std::string path_;
  std::ifstream in_;
  int64_t line_ = 0;
};

}  // namespace

ReferenceComparison compare_with_reference(const std::string& hits_path, const std::string& reference_path,
                                           std::ostream* differences) {
  JsonLines hits(hits_path), reference(reference_path);
  ReferenceComparison c;
  json h, r;
  if (!hits.next(h) || h.value("format", "") != "vbsim-hits")
    hits.fail("not a hits file of vbsim replay (its first line names the format vbsim-hits)");
  while (hits.next(h)) {
    if (h.contains("partial")) hits.fail("the replay was stopped before its end: compare a complete replay");
    if (!reference.next(r))
      reference.fail(fmt::format("ends before ray {} of {}: the two files are not of the same trace",
                                 hits.integer(h, "id"), hits_path));
    const int64_t id = hits.integer(h, "id");
    if (reference.integer(r, "id") != id)
      reference.fail(fmt::format("ray {} where {} has ray {}: the two files are not of the same trace",
                                 reference.integer(r, "id"), hits_path, id));
    ++c.rays;
    const int64_t prim = hits.integer(h, "prim");
    bool same = false, same_t = false;
    const bool outside = r.value("not_captured", false);
    if (r.contains("occluded")) {
      same = r["occluded"].get<bool>() == (prim >= 0);
    } else if (!outside) {
      const int64_t want = reference.integer(r, "prim");
      same = want == prim;
      if (!same && want >= 0 && prim >= 0) {
        const double t = r.at("t").get<double>(), got = h.at("t").get<double>();
        same = same_t = std::fabs(got - t) <= 1e-6 * std::fabs(t);
      }
    }
    if (same) {
      ++c.agree;
      c.agree_same_t += same_t;
      continue;
    }
    ++c.differ;
    c.differ_outside += outside;
    const std::string verdict = h.value("verdict", "unscored");
    ++c.differ_by_verdict[verdict];
    if (differences) {
      json replay = {{"prim", prim}};
      if (prim >= 0) replay["t"] = h.at("t");
      json ref = r;
      ref.erase("id");
      *differences << json{{"id", id}, {"verdict", verdict}, {"replay", replay}, {"reference", ref}}.dump() << "\n";
    }
  }
  if (reference.next(r))
    reference.fail(fmt::format("ray {} has no replayed answer in {}: the two files are not of the same trace",
                               reference.integer(r, "id"), hits_path));
  return c;
}

}  // namespace vbsim::capture
