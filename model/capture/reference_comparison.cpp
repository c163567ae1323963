#include "capture/reference_comparison.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/line_reader.h"
#include "trace/trace_file.h"

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
    for (LineRead r; (r = read_bounded_line(in_, text)) != LineRead::kEnd;) {
      ++line_;
      if (r == LineRead::kTooLong) fail(fmt::format("longer than {} MiB: not a line of JSON", kMaxTextLineBytes >> 20));
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

/// The reference answers, one JSON object per ray as embree_hits.jsonl has
/// them, from that file or from a trace whose rays carry `reference`.
class ReferenceAnswers {
 public:
  explicit ReferenceAnswers(const std::string& path) : path_(path) {
    std::ifstream in(path, std::ios::binary);
    std::string first;
    read_bounded_line(in, first);  // a first line too long for either is refused by JsonLines
    if (first.rfind("VBSIMTRB", 0) == 0 || first.find("\"vbsim-trace\"") != std::string::npos)
      trace_ = open_trace(path);
    else
      lines_ = std::make_unique<JsonLines>(path);
  }
  bool next(json& out) {
    if (lines_) return lines_->next(out);
    TraceRay tr;
    if (!trace_->next(tr)) return false;
    out = {{"id", tr.id}};
    if (!tr.has_reference && tr.incomplete != 0) out["not_captured"] = true;  // a hit outside the trace
    else if (!tr.has_reference) fail(fmt::format("ray {} carries no reference answer", tr.id));
    else if (tr.reference_prim == kReferenceOccluded || (tr.kind == RayKind::Shadow && tr.reference_prim == -1))
      out["occluded"] = tr.reference_prim == kReferenceOccluded;
    else out["prim"] = tr.reference_prim;
    if (tr.has_reference_t) out["t"] = tr.reference_t;
    return true;
  }
  [[noreturn]] void fail(const std::string& message) const {
    if (lines_) lines_->fail(message);
    throw trace_->error_at_last_ray("reference", message);
  }
  int64_t integer(const json& j, const char* key) const {
    if (lines_) return lines_->integer(j, key);
    return j.at(key).get<int64_t>();
  }

 private:
  std::string path_;
  std::unique_ptr<JsonLines> lines_;
  std::unique_ptr<TraceSource> trace_;
};

}  // namespace

ReferenceComparison compare_with_reference(const std::string& hits_path, const std::string& reference_path,
                                           std::ostream* differences) {
  JsonLines hits(hits_path);
  ReferenceAnswers reference(reference_path);
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
