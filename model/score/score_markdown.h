// The markdown page of a score table (docs/results/accuracy.md): generated,
// with the command that regenerates it; summaries per tester (secondary-ray
// errors, the headline of every method; camera rays missed; cycles per ray in
// cycle mode), then per family its trade-off table (tradeoff_table.h) and the
// verdicts per ray kind, camera rays apart from secondary rays.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace vbsim {

std::string score_markdown(const nlohmann::json& score, const std::string& regenerate);

}  // namespace vbsim
