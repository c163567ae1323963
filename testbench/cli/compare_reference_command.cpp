// vbsim compare-reference: a replay's answers against the capturing renderer's
// own (a capture's embree_hits.jsonl), ray by ray, with the oracle's verdict on
// every ray where they differ (model/capture/reference_comparison.h).
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "capture/reference_comparison.h"
#include "commands.h"
#include "io/atomic_output_file.h"
#include "io/output_paths.h"

namespace vbsim::cli {

namespace {

struct CompareArgs {
  std::string hits, reference, out;
  bool quiet = false;
};

void run_compare(const CompareArgs& a) {
  check_output_paths({{"hits", a.hits}, {"reference", a.reference}}, {{"option '--out'", a.out}});
  std::unique_ptr<AtomicOutputFile> file;
  if (!a.out.empty()) file = std::make_unique<AtomicOutputFile>(a.out);
  std::ostream& differences = file ? file->stream() : std::cout;
  const capture::ReferenceComparison c = capture::compare_with_reference(a.hits, a.reference, &differences);
  if (file) file->commit();
  if (a.quiet) return;
  std::string verdicts;
  for (const auto& [v, n] : c.differ_by_verdict) verdicts += fmt::format("{}{} {}", verdicts.empty() ? "" : ", ", v, n);
  fmt::print(stderr,
             "vbsim compare-reference: {} rays; {} agree with the reference ({} on another triangle at its distance); "
             "{} differ ({} of them on geometry outside the trace){}{}{}\n",
             c.rays, c.agree, c.agree_same_t, c.differ, c.differ_outside, c.differ ? "; the replay's verdicts: " : "",
             verdicts, file ? fmt::format("; every difference -> {}", a.out) : "");
  if (c.differ_by_verdict.count("unscored") && c.differ_by_verdict.at("unscored") == c.differ)
    fmt::print(stderr, "  (no verdicts: replay a trace scored by `vbsim oracle TRACE -o OUT` to judge the differences)\n");
}

}  // namespace

void add_compare_reference_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare-reference",
      "compare a replay's answers (vbsim replay --hits) with the capturing renderer's own (a capture's "
      "embree_hits.jsonl): every ray where they differ, with the replay's verdict from the oracle");
  cmd->add_option("hits", args->hits, "the replay's hits file (vbsim replay TRACE --hits FILE)")->required();
  cmd->add_option("reference", args->reference, "the renderer's answers (embree_hits.jsonl of vbsim capture)")
      ->required();
  cmd->add_option("-o,--out", args->out,
                  "write the differing rays here, one JSON line each: id, verdict, replay, reference [stdout]");
  cmd->add_flag("--quiet,-q", args->quiet, "print no summary");
  cmd->callback([args] { run_compare(*args); });
}

}  // namespace vbsim::cli
