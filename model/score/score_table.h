// Score tables: the rows of a score run, one per (family, method, tester, ray
// kind) plus an `all` row per configuration, as JSON and as markdown. Rates are
// per million scored rays (rays with `expect`), each with its 95% Wilson score
// interval; the avoidance unit's rates are per candidate hit.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "score/score_run.h"

namespace vbsim {

/// The JSON document: `command`, `confidence`, `families` (name, traces,
/// generator) and `rows` (family, method, tester, kind, rays, scored, counts,
/// per_million {verdict: {rate, lower, upper}}, avoidance; `all` rows add
/// rays_per_s and config).
nlohmann::json score_json(const std::vector<ScoreFamily>& families, const std::vector<ScoreCell>& cells,
                          const std::string& command);

/// The markdown page (docs/results/accuracy.md): a header saying it is
/// generated and how to regenerate it (`regenerate`), then a table per family.
std::string score_markdown(const nlohmann::json& score, const std::string& regenerate);

/// A per-million rate for a table: integers from 100 up, one decimal from 1, two
/// significant digits below 1, "0" for zero.
std::string format_per_million(double x);

}  // namespace vbsim
