// Settings that take a comma-separated list of numbers (`--set k=0,8,16`),
// read through ScenarioSettings so that a bad entry names the key.
#pragma once
#include <string>
#include <vector>

#include "gen/scenario.h"

namespace vbsim {

/// The numbers of `key` (comma-separated), or `fallback` when not set. Throws
/// naming the key on an empty list or an entry that is not a finite number.
std::vector<double> number_list(const ScenarioSettings& settings, const std::string& key,
                                const std::vector<double>& fallback);

/// `count` values from `lo` to `hi` spaced evenly on a log scale (lo, hi > 0).
std::vector<double> log_spaced(double lo, double hi, int count);

}  // namespace vbsim
