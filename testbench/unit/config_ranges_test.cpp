// Configuration values are checked in the type they are stored in: no integer
// wraps, no float32 overflows to inf or underflows to 0, and every error names
// the file and the field; an accepted configuration echoes as JSON that reads
// back to the same configuration.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "hw/hw_config.h"
#include "replay/replay_config.h"
#include "replay/replay_stats.h"

using namespace vbsim;

namespace {

std::string config_error(const std::string& text, bool hw = false) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    if (hw) {
      hw::HwConfig c;
      hw::apply_hw_config(j, "c.json", c);
    } else {
      ReplayOptions opt;
      apply_replay_config(j, "c.json", opt);
    }
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("config integers outside their type are errors, never wrapped", "[config]") {
  CHECK_THAT(config_error(R"({"validity_bit": {"guard_bits": 4294967301}})"),
             Catch::StartsWith("c.json: field 'validity_bit.guard_bits'") && Catch::Contains("out of range"));
  CHECK_THAT(config_error(R"({"validity_bit": {"guard_bits": -2147483649}})"), Catch::Contains("out of range"));
  CHECK_THAT(config_error(R"({"validity_bit": {"min_exponent": 18446744073709551615}})"),
             Catch::Contains("validity_bit.min_exponent") && Catch::Contains("out of range"));
  CHECK_THAT(config_error(R"({"validity_bit": {"weights": {"ray": 2.5}}})"),
             Catch::Contains("validity_bit.weights.ray") && Catch::Contains("integer"));
  CHECK_THAT(config_error(R"({"cores": 18446744073709551615})", true),
             Catch::StartsWith("c.json: field 'hw.cores'") && Catch::Contains("1..4096"));
  CHECK_THAT(config_error(R"({"cores": 4294967297})", true), Catch::Contains("hw.cores"));
  CHECK_THAT(config_error(R"({"memory": {"l1": {"size_bytes": 4294967360}}})", true),
             Catch::Contains("hw.memory.l1.size_bytes"));
  CHECK(config_error(R"({"validity_bit": {"guard_bits": 7}})") == "(accepted)");
}

TEST_CASE("config float32 fields refuse overflow to inf and underflow to 0", "[config]") {
  CHECK_THAT(config_error(R"({"tmin_eps": 1e300})"),
             Catch::StartsWith("c.json: field 'tmin_eps'") && Catch::Contains("out of range for a float32"));
  CHECK_THAT(config_error(R"({"validity_bit": {"eps": 3.5e38}})"), Catch::Contains("validity_bit.eps"));
  CHECK_THAT(config_error(R"({"offset_normal_eps": 1e-50})"), Catch::Contains("rounds to 0"));
  CHECK(config_error(R"({"tmin_eps": 1e-40})") == "(accepted)");  // a float32 denormal, not zero
  CHECK(config_error(R"({"tmin_eps": 3.4e38})") == "(accepted)");
  CHECK_THAT(config_error(R"({"clock_mhz": 1e308})", true), Catch::Contains("hw.clock_mhz"));
}

TEST_CASE("config errors name the file they come from", "[config]") {
  const auto path = (std::filesystem::temp_directory_path() / ("vbsim_cfg_" + std::to_string(::getpid()) + ".json")).string();
  std::ofstream(path) << R"({"adaptive": {"int_scale": 1e39}})";
  ReplayOptions opt;
  CHECK_THROWS_WITH(load_replay_config(path, opt), Catch::StartsWith(path + ": field 'adaptive.int_scale'"));
  std::ofstream(path) << "{\"tmin_eps\": ";
  CHECK_THROWS_WITH(load_replay_config(path, opt), Catch::StartsWith(path + ": line 1: not valid JSON"));
  // A number beyond double is nlohmann-json's out_of_range, not a parse error (found by fuzzing).
  std::ofstream(path) << "{\"adaptive\": {\"float_scale\": 1.5e2263761063757594}}";
  CHECK_THROWS_WITH(load_replay_config(path, opt), Catch::StartsWith(path + ": line 1: not valid JSON"));
  std::filesystem::remove(path);
  CHECK_THROWS_WITH(load_replay_config(path, opt), Catch::StartsWith(path + ": cannot open"));
}

TEST_CASE("an accepted configuration echoes as one that reads back the same", "[config]") {
  const char* configs[] = {
      R"({"method": "validity-bit", "tmin_eps": 3.4e38, "validity_bit": {"eps": 1e-40, "guard_bits": 23}})",
      R"({"method": "offset-adaptive+primid", "adaptive": {"origin": 0.03125, "int_scale": 999999}})",
      R"({"method": "tmin", "tmin_eps": 0.1, "offset_normal_eps": 1.0000001})",
  };
  for (const char* text : configs) {
    INFO(text);
    ReplayOptions opt;
    apply_replay_config(nlohmann::json::parse(text), "c.json", opt);
    const nlohmann::json echo = replay_config_json(opt);
    ReplayOptions again;
    REQUIRE_NOTHROW(apply_replay_config(echo, "echo", again));
    CHECK(replay_config_json(again) == echo);
  }
  for (const std::string& preset : hw::preset_names()) {
    const hw::HwConfig c = hw::load_preset(preset, "test");
    hw::HwConfig again;
    hw::apply_hw_config(hw::hw_config_json(c), "echo", again);
    CHECK(hw::hw_config_json(again) == hw::hw_config_json(c));
  }
}
