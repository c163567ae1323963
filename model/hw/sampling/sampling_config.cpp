#include "hw/sampling/sampling_config.h"

#include <stdexcept>
#include <string>

namespace vbsim::hw {

void check_sampling_config(const SamplingConfig& c) {
  auto bad = [](const std::string& what) { throw std::invalid_argument(what); };
  if (c.unit == 0) bad("--sample-unit: must be >= 1");
  if (c.interval == 0) bad("--sample-interval: must be >= 1");
  if (c.offset >= 0 && static_cast<uint64_t>(c.offset) >= c.interval)
    bad("--sample-offset: must be below --sample-interval");
  if (!(c.confidence > 0 && c.confidence < 1)) bad("--sample-confidence: must lie strictly between 0 and 1");
  if (!(c.error >= 0 && c.error < 1)) bad("--sample-error: must lie in [0, 100%)");
  if (c.min_units < 2) bad("--sample-min-units: must be >= 2");
}

nlohmann::json sampling_config_json(const SamplingConfig& c) {
  return {{"unit", c.unit},         {"interval", c.interval},     {"warmup", c.warmup},
          {"offset", c.measured_offset()}, {"confidence", c.confidence}, {"error", c.error},
          {"min_units", c.min_units}, {"warm", c.warm}, {"head", c.head}, {"tail", c.tail},
          {"total", c.total}};
}

}  // namespace vbsim::hw
