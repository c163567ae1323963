// Score tables: the rows of a score run as JSON, per (family, method, tester)
// one row per ray kind present, a `secondary` row (every kind but `primary`,
// i.e. every ray leaving a surface: the rows that measure self-intersection)
// and an `all` row. Rates are per million scored rays (rays with `expect`),
// each with its 95% Wilson score interval; the avoidance unit's rates are per
// candidate hit. score_markdown.h and tradeoff_table.h read this JSON.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "energy/tech_file.h"
#include "score/score_run.h"

namespace vbsim {

/// The kind of the rows that sum every ray with a parent surface.
constexpr const char* kSecondaryKind = "secondary";

/// The JSON document: `command`, `confidence`, `families` (name, traces,
/// generator) and `rows` (family, method, tester, kind, rays, scored, counts,
/// per_million {verdict: {rate, lower, upper}}, errors {count, per_million}
/// (self_hit + false_hit + missed), emission and offset fallbacks, avoidance;
/// `all` rows add rays_per_s, ops_per_ray, config and, when measured, `cycle`
/// {preset, rays, cycles, cycles_per_ray, rays_per_cycle, tech, total_pj,
/// energy_per_ray_pj (operations, memory, leakage: the cycle-level replay's
/// hw.energy.per_ray_pj), chip_mm2 (hw.area.chip_mm2)}) and `energy`
/// {tech, per_ray_pj, method_per_ray_pj}: the operations' energy priced by
/// `tech` (null: the shipped default; energy/operation_energy.h).
nlohmann::json score_json(const std::vector<ScoreFamily>& families, const std::vector<ScoreCell>& cells,
                          const std::string& command, const TechFile* tech = nullptr);

/// A per-million rate for a table: integers from 100 up, one decimal from 1, two
/// significant digits below 1, "0" for zero.
std::string format_per_million(double x);

}  // namespace vbsim
