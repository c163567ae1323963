// Ray conservation: every ray a run reads leaves it counted, exactly once, in
// the statistics (or, for a stopped cycle-level run, among the rays dropped in
// flight). A run that would lose or double-count a ray fails loudly instead of
// writing statistics that look whole.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

namespace vbsim {

struct ConservationError : std::logic_error {
  using std::logic_error::logic_error;
};

/// Throws ConservationError naming `run` (e.g. the trace and method) unless
/// rays_in == rays_out + rays_dropped.
void check_ray_conservation(const std::string& run, uint64_t rays_in, uint64_t rays_out,
                            uint64_t rays_dropped = 0);

}  // namespace vbsim
