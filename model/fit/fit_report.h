// Fit reports: the human text and the JSON of `vbsim fit` results.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fit/fit_search.h"

namespace vbsim {

/// One result as text: the smallest value and the ray that needs it, the
/// largest value that still works, and the check; or "none exists" with the
/// rays that prove it.
std::string fit_text(const FitResult& r);

/// One result as JSON: key, description, rays, searched [low, high], feasible,
/// smallest {value, below, ray}, largest {value, above, ray}, check.
nlohmann::json fit_json(const FitResult& r);

}  // namespace vbsim
