#include "replay/ray_conservation.h"

#include <fmt/format.h>

namespace vbsim {

void check_ray_conservation(const std::string& run, uint64_t rays_in, uint64_t rays_out, uint64_t rays_dropped) {
  if (rays_in == rays_out + rays_dropped) return;
  throw ConservationError(fmt::format(
      "{}: ray conservation broken: {} rays read, {} counted in the statistics{}; the run is not valid", run,
      rays_in, rays_out, rays_dropped ? fmt::format(" and {} dropped in flight", rays_dropped) : std::string()));
}

}  // namespace vbsim
