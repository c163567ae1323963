// Fuzz target: the configuration reader (replay fields and the `hw` object) on
// any bytes. A configuration it accepts must echo (replay_config_json,
// hw_config_json) as JSON that it accepts again with the same result: no
// value may wrap, overflow or turn into null on the way.
#include "fuzz_support.h"
#include "hw/hw_config.h"
#include "replay/replay_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vbsim;
  const std::string path = fuzz::input_file(data, size, ".json");
  nlohmann::json j;
  try {
    j = read_config_json(path);
  } catch (const ConfigError&) {
    return 0;
  }
  try {
    ReplayOptions opt;
    apply_replay_config(j, path, opt);
    nlohmann::json echo = replay_config_json(opt);
    ReplayOptions again;
    try {
      apply_replay_config(echo, "echo", again);
    } catch (const ConfigError& e) {
      fuzz::finding(std::string("the echoed configuration is refused: ") + e.what());
    }
    if (replay_config_json(again) != echo) fuzz::finding("the echoed configuration reads back differently");
    if (j.is_object() && j.contains("hw")) {
      hw::HwConfig cfg = hw::load_preset("small", "fuzz");
      hw::apply_hw_config(j["hw"], path, cfg);
      const nlohmann::json hw_echo = hw::hw_config_json(cfg);
      hw::HwConfig cfg_again = hw::load_preset("small", "fuzz");
      try {
        hw::apply_hw_config(hw_echo, "echo", cfg_again);
      } catch (const ConfigError& e) {
        fuzz::finding(std::string("the echoed hw configuration is refused: ") + e.what());
      }
      if (hw::hw_config_json(cfg_again) != hw_echo) fuzz::finding("the echoed hw configuration reads back differently");
    }
  } catch (const ConfigError&) {
  }
  return 0;
}
