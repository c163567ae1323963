// Where the library finds its presets and technology files (io/data_dir.h):
// VBSIM_DATA_DIR before the directory set_data_dir() names, before the source
// tree; load_preset and the default technology file follow it, and a data
// directory without the preset is an error naming the file it looked for.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "energy/tech_file.h"
#include "hw/hw_config.h"
#include "io/data_dir.h"
#include "../system/run_vbsim.h"

using namespace vbsim;

namespace {

/// Leaves neither the environment variable nor a set directory behind.
struct DataDirReset {
  DataDirReset() { reset(); }
  ~DataDirReset() { reset(); }
  static void reset() {
    unsetenv("VBSIM_DATA_DIR");
    set_data_dir("");
  }
};

}  // namespace

TEST_CASE("the data directory: the environment, then set_data_dir, then the source tree", "[data_dir]") {
  const DataDirReset reset;
  const std::string source = VBSIM_SOURCE_DIR;
  CHECK(presets_dir() == source + "/model/hw/presets");
  CHECK(tech_dir() == source + "/model/energy/tech");

  set_data_dir("/opt/vbsim/share/vbsim");
  CHECK(presets_dir() == "/opt/vbsim/share/vbsim/presets");
  CHECK(tech_dir() == "/opt/vbsim/share/vbsim/tech");
  CHECK(default_tech_path() == "/opt/vbsim/share/vbsim/tech/45nm.json");

  setenv("VBSIM_DATA_DIR", "/elsewhere", 1);
  CHECK(presets_dir() == "/elsewhere/presets");
  CHECK(tech_dir() == "/elsewhere/tech");
  setenv("VBSIM_DATA_DIR", "", 1);  // empty: as if unset
  CHECK(presets_dir() == "/opt/vbsim/share/vbsim/presets");
}

TEST_CASE("presets are read from the data directory, and a missing one is named", "[data_dir]") {
  const DataDirReset reset;
  const auto dir = test::scratch_dir("data_dir");
  std::filesystem::create_directories(dir / "presets");
  // A preset of one's own under the name small: its clock is what the library reads.
  test::write_file(dir / "presets" / "small.json", R"({"clock_mhz": 123})");
  set_data_dir(dir.string());
  CHECK(hw::load_preset("small", "test").clock_mhz == 123);
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(hw::load_preset("large", "test"), Contains((dir / "presets" / "large.json").string()));
}
