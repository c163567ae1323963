// vbsim check: validates a trace and names every problem with its line (or
// record): format errors, then the consistency checks (trace_consistency.h).
// Runs of rays without expect are reported as one range. Exit status 0 when
// no error was found (warnings allowed unless --strict), 1 otherwise.
#include <fmt/format.h>

#include <array>
#include <optional>

#include "commands.h"
#include "progress/work_progress.h"
#include "scene/scene.h"
#include "scene/triangle_masks.h"
#include "threads_option.h"
#include "trace/checked_trace_source.h"
#include "trace/incomplete_reasons.h"
#include "trace/trace_file.h"

namespace vbsim::cli {

namespace {

struct CheckArgs {
  std::string trace;
  uint64_t max_per_check = 0;  // 0: every problem
  int64_t window = kDefaultParentWindow;  // --parent-window, as in replay
  bool strict = false;
  bool quiet = false;  // -q: warnings and the summary only when the check fails; errors always
  int threads = 1;     // --threads (every core by default)
};

/// "file:12" or "file: record 11" for a position of `word` ("line"/"record").
std::string place(const std::string& file, const char* word, int64_t pos) {
  return std::string(word) == "line" ? fmt::format("{}:{}", file, pos) : fmt::format("{}: record {}", file, pos);
}

std::string field_part(const std::string& field) {
  return field.empty() ? "" : fmt::format("field '{}': ", field);
}

class CheckReport {
 public:
  CheckReport(const CheckArgs& a, const std::string& file) : a_(a), file_(file) {}

  void error(const std::string& located_text) {
    ++errors_;
    fmt::print("error: {}\n", located_text);
  }
  /// A finding at the ray at `pos`; `text` is "field 'f': message".
  void finding(const TraceFinding& f, const char* word, int64_t pos) {
    const int k = static_cast<int>(f.check);
    const bool is_error = trace_check_is_error(f.check);
    (is_error ? errors_ : warnings_) += 1;
    ++counts_[k];
    if (a_.max_per_check > 0 && static_cast<uint64_t>(counts_[k]) > a_.max_per_check) return;
    if (a_.quiet && !is_error) return;
    fmt::print("{}: {} [{}]: {}{}\n", place(file_, word, pos), is_error ? "error" : "warning",
               trace_check_name(f.check), field_part(f.field), f.message);
  }
  /// Missing expect, merged into runs of consecutive rays.
  void missing_expect(const TraceFinding& f, const char* word, int64_t pos) {
    ++warnings_;
    ++counts_[static_cast<int>(TraceCheck::MissingExpect)];
    if (!run_) run_ = Run{pos, pos, 0, word, f.message};
    run_->last = pos;
    ++run_->rays;
  }
  void end_missing_run() {
    if (!run_) return;
    if (a_.quiet) {
      run_.reset();
      return;
    }
    const std::string where = run_->first == run_->last
                                  ? place(file_, run_->word, run_->first)
                                  : place(file_, run_->word, run_->first) + "-" + std::to_string(run_->last);
    fmt::print("{}: warning [missing_expect]: field 'expect': {} ray{}: {}\n", where, run_->rays,
               run_->rays == 1 ? "" : "s", run_->message);
    run_.reset();
  }
  int64_t errors() const { return errors_; }
  int64_t warnings() const { return warnings_; }
  std::string counts_text() const {
    std::string s;
    for (int k = 0; k < kTraceCheckCount; ++k)
      if (counts_[k] > 0) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", trace_check_name(static_cast<TraceCheck>(k)), counts_[k]);
    return s.empty() ? "none" : s;
  }

 private:
  struct Run {
    int64_t first, last, rays;
    const char* word;
    std::string message;
  };
  const CheckArgs& a_;
  std::string file_;
  int64_t errors_ = 0, warnings_ = 0;
  std::array<int64_t, kTraceCheckCount> counts_{};
  std::optional<Run> run_;
};

int run_check(const CheckArgs& a) {
  check_threads_option(a.threads);
  std::unique_ptr<TraceSource> source = open_trace(a.trace);  // a bad header is thrown: exit 2
  source->set_parse_threads(a.threads);  // the same rays and errors, in the same order, as one thread
  CheckReport report(a, a.trace);
  Scene scene;
  TraceConsistencyChecker::Options opt;
  opt.window = static_cast<std::size_t>(a.window);
  try {
    MeterWorkProgress loading("scene", ProgressMeter::terminal_or_null(a.quiet));
    scene = load_header_scene(source->header(), &loading);
    source->set_triangle_count(scene.size());
    opt.triangles = &scene.triangles;
  } catch (const SceneError& e) {
    report.error(fmt::format("{}: header: field 'scene': {} (the checks against the scene are skipped)",
                             a.trace, e.what()));
  }
  TraceConsistencyChecker checker(opt);
  const char* word = position_word(*source);
  std::vector<TraceFinding> findings;
  TraceRay ray;
  int64_t rays = 0, unreadable = 0, incomplete = 0;
  int64_t incomplete_by_reason[kIncompleteReasonCount] = {};
  int64_t with_reference = 0, reference_scored = 0, reference_agrees = 0, first_disagreement = -1;
  for (;;) {
    try {
      if (!source->next(ray)) break;
    } catch (const TraceError& e) {
      report.end_missing_run();
      report.error(e.what());
      ++unreadable;
      // A line or record can be skipped; an error about the file as a whole ends the check.
      if (e.place == TraceError::Place::Line || e.place == TraceError::Place::Record) continue;
      break;
    }
    ++rays;
    if (ray.incomplete != 0) {
      ++incomplete;
      for (int k = 0; k < kIncompleteReasonCount; ++k) incomplete_by_reason[k] += (ray.incomplete >> k) & 1u;
    }
    const int64_t pos = last_ray_position(*source, rays + unreadable);
    if (ray.has_reference) {  // the renderer's own answer against the exact one
      ++with_reference;
      if (ray.has_expect) {
        ++reference_scored;
        const bool occluding = ray.reference_prim == kReferenceOccluded;
        const bool agrees = ray.kind == RayKind::Shadow || occluding
                                ? (ray.expect_prim >= 0) == (occluding || ray.reference_prim >= 0)
                                : ray.reference_prim == ray.expect_prim;
        reference_agrees += agrees;
        if (!agrees && first_disagreement < 0) first_disagreement = pos;
      }
    }
    findings.clear();
    checker.check(ray, pos, word, findings);
    bool missing = false;
    for (const TraceFinding& f : findings) {
      if (f.check == TraceCheck::MissingExpect) {
        missing = true;
        report.missing_expect(f, word, pos);
      } else {
        report.end_missing_run();
        report.finding(f, word, pos);
      }
    }
    if (!missing) report.end_missing_run();
  }
  report.end_missing_run();
  const int rc = report.errors() > 0 || (a.strict && report.warnings() > 0) ? 1 : 0;
  if (a.quiet && rc == 0) return rc;
  fmt::print("vbsim check {}: {} ray{}, {} error{}, {} warning{} ({})", a.trace, rays, rays == 1 ? "" : "s",
             report.errors(),
             report.errors() == 1 ? "" : "s", report.warnings(), report.warnings() == 1 ? "" : "s",
             report.counts_text());
  fmt::print("; parent data checked within the last {} rays, {} children's parents not among them\n",
             checker.window(), checker.parents_not_checked());
  if (incomplete > 0) {  // not a fault of the trace: a statement about what it could not hold
    std::string reasons;
    for (int k = 0; k < kIncompleteReasonCount; ++k)
      if (incomplete_by_reason[k] > 0)
        reasons += fmt::format("{}{} {}", reasons.empty() ? "" : ", ", incomplete_reason_name(k), incomplete_by_reason[k]);
    fmt::print("vbsim check: {} ray{} marked incomplete ({}): their renderer's answers involved what the trace does "
               "not hold; replays leave them unscored unless --score-incomplete\n",
               incomplete, incomplete == 1 ? "" : "s", reasons);
  }
  if (with_reference > 0) {
    if (reference_scored > 0)
      fmt::print("vbsim check: {} rays carry the answer of {}: {} of the {} with an exact answer agree with it "
                 "(the same triangle, or occluded alike), {} differ{}\n",
                 with_reference, source->header().reference, reference_agrees, reference_scored,
                 reference_scored - reference_agrees,
                 first_disagreement >= 0 ? fmt::format(" (the first at {} {})", word, first_disagreement) : "");
    else
      fmt::print("vbsim check: {} rays carry the answer of {}; none has an exact answer to hold it against (vbsim "
                 "oracle TRACE -o OUT fills them in)\n", with_reference, source->header().reference);
  }
  if (checker.order_unchecked() > 0)
    fmt::print("vbsim check: {} children whose parent was not in the window could not be ordered (ids do not ascend)\n",
               checker.order_unchecked());
  if (source->ids_not_checked() > 0)
    fmt::print("vbsim check: {} rays' ids could not be checked against every earlier id for a duplicate (the ids "
               "run in more separate ranges than the bounded id record keeps)\n",
               source->ids_not_checked());
  return rc;
}

}  // namespace

void add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand("check", "validate a trace: name every problem with its line");
  cmd->add_option("trace", args->trace, "trace file (.jsonl text or .vbt binary)")->required();
  cmd->add_option("--max-per-check", args->max_per_check,
                  "print at most N problems of each kind (0: all; all are counted)")
      ->capture_default_str();
  add_parent_window_option(*cmd, args->window, "--parent-window,--window");
  add_threads_option(*cmd, args->threads, "threads that parse the rays (text traces)");
  cmd->add_flag("--strict", args->strict, "exit 1 on warnings too");
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing when the check passes (errors are always printed)");
  cmd->callback([args] {
    const int rc = run_check(*args);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace vbsim::cli
