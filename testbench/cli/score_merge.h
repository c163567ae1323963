// Merging score tables: `vbsim score --merge PART.json...` joins the JSON
// tables of score runs over disjoint families (e.g. one run per family on a
// cluster, scripts/score_points.py) into the table one run over all of them
// gives: the parts' families and rows, in the order of the parts. Every row of
// a score table depends on its own family only, so the merged counts, rates and
// intervals are those of the single run (only rays_per_s, a timing, differs).
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vbsim::cli {

/// The merged table (`command` set to `command`; `parts`: each part's path and
/// provenance; no provenance of its own, the caller adds it). Throws
/// std::runtime_error naming the part when a part is not a score table, its
/// confidence settings or its (method, tester) list differ from the first
/// part's, or a family appears twice.
nlohmann::json merge_score_tables(const std::vector<std::string>& parts, const std::string& command);

}  // namespace vbsim::cli
