#include "trace/checked_trace_source.h"

#include <fmt/format.h>

#include "trace/text_trace_reader.h"

namespace vbsim {

namespace {

/// What a warning kind means, for the one-line summaries.
const char* warning_meaning(TraceCheck check) {
  switch (check) {
    case TraceCheck::IdOrder: return "ids out of order";
    case TraceCheck::ParentData: return "parent data inconsistent with the parent ray or triangle";
    case TraceCheck::Sign: return "a sign bit that contradicts the parent's geometric normal";
    case TraceCheck::MissingExpect: return "no expect (run `vbsim oracle` to score them)";
    case TraceCheck::ChildBeforeParent: return "a child before its parent";
  }
  return "";
}

}  // namespace

int64_t last_ray_position(const TraceSource& source, int64_t rays_read) {
  if (const auto* text = dynamic_cast<const TextTraceReader*>(&source)) return text->line_number();
  return rays_read - 1;
}

const char* position_word(const TraceSource& source) {
  return dynamic_cast<const TextTraceReader*>(&source) ? "line" : "record";
}

CheckedTraceSource::CheckedTraceSource(TraceSource& inner, const TraceConsistencyChecker::Options& options)
    : inner_(inner),
      checker_(options),
      position_word_(vbsim::position_word(inner)),
      text_(dynamic_cast<const TextTraceReader*>(&inner)) {}

bool CheckedTraceSource::next(TraceRay& out) {
  if (!inner_.next(out)) return false;
  ++rays_;
  findings_.clear();
  const int64_t position = text_ ? text_->line_number() : rays_ - 1;
  checker_.check(out, position, position_word_, findings_);
  for (const TraceFinding& f : findings_) {
    if (trace_check_is_error(f.check)) throw inner_.error_at_last_ray(f.field, f.message);
    const int k = static_cast<int>(f.check);
    // A ray counts once per kind, however many of its fields disagree.
    if (&f != &findings_.front() && (&f - 1)->check == f.check) continue;
    if (counts_[k]++ == 0) first_[k] = inner_.error_at_last_ray(f.field, f.message).what();
  }
  return true;
}

nlohmann::json CheckedTraceSource::summary_json() const {
  nlohmann::json warnings = nlohmann::json::object(), first = nlohmann::json::object();
  for (int k = 0; k < kTraceCheckCount; ++k) {
    const auto check = static_cast<TraceCheck>(k);
    if (trace_check_is_error(check)) continue;
    warnings[trace_check_name(check)] = counts_[k];
    if (counts_[k] > 0) first[trace_check_name(check)] = first_[k];
  }
  return {{"window", checker_.window()},
          {"warnings", warnings},
          {"first", first},
          {"parents_not_checked", checker_.parents_not_checked()},
          {"order_unchecked", checker_.order_unchecked()},
          {"ids_not_checked", ids_not_checked()}};
}

std::string CheckedTraceSource::warning_lines(const std::string& program, bool with_missing_expect) const {
  std::string out;
  for (int k = 0; k < kTraceCheckCount; ++k) {
    const auto check = static_cast<TraceCheck>(k);
    if (counts_[k] == 0 || trace_check_is_error(check)) continue;
    if (check == TraceCheck::MissingExpect && !with_missing_expect) continue;
    out += fmt::format("{}: warning: {} ray{}: {}; first: {}\n", program, counts_[k],
                       counts_[k] == 1 ? "" : "s", warning_meaning(check), first_[k]);
  }
  if (!out.empty()) out += fmt::format("{}: `vbsim check {}` lists every problem\n", program, inner_.path());
  return out;
}

}  // namespace vbsim
