// The technology file: the shipped default's figures, the SRAM interpolation,
// and errors naming the file and field.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "datapath/datapath_ops.h"
#include "energy/tech_file.h"
#include "io/data_dir.h"
#include "replay/replay_config.h"
#include "trace_test_support.h"

using namespace vbsim;
using vbsim::test::TempDir;
using vbsim::test::write_file;

namespace {

nlohmann::json figure(double v) { return {{"value", v}, {"source", "test"}}; }

/// A technology file with every operation at `op` pJ and mm².
nlohmann::json flat_tech(double op) {
  nlohmann::json e, a;
  for (const char* k : kOpKindNames) e[k] = figure(op), a[k] = figure(op);
  e["register_bit"] = figure(0.5);
  a["register_bit"] = figure(0.25);
  a["sram_bit"] = figure(1e-6);
  return {{"name", "flat"},
          {"node_nm", 45},
          {"energy_pj", e},
          {"area_mm2", a},
          {"sram_read_64bit_pj", {{{"bytes", 1024}, {"value", 4}}, {{"bytes", 4096}, {"value", 16}}}},
          {"dram_64bit_pj", figure(1000)},
          {"leakage_w_per_mm2", figure(0.01)}};
}

std::string error_of(const std::string& path) {
  try {
    load_tech_file(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("tech file: the shipped 45 nm figures", "[tech]") {
  const TechFile t = load_tech_file(default_tech_path());
  CHECK(t.node_nm == 45);
  CHECK(t.op_pj[0] == 0.9);  // Horowitz: fp32 add
  CHECK(t.op_pj[1] == 3.7);  // fp32 multiply
  CHECK(t.op_pj[7] == 0.1);  // int32 add
  // The three-half-plane test by hand: 22 adds x 0.9 + 20 multiplies x 3.7 +
  // 3 divides x 23 + 16 compares x 0.0652 + 2 selects x 0.025 pJ.
  CHECK(t.energy_pj(triangle_test_ops(TesterKind::ThreeHalfPlane)) ==
        Approx(22 * 0.9 + 20 * 3.7 + 3 * 23.0 + 16 * 0.0652 + 2 * 0.025));
  // SRAM: tabulated sizes exactly, between them a power law, beyond the table
  // the last segment's, flagged.
  bool ex = true;
  CHECK(t.sram_64bit_pj(8192, &ex) == Approx(10));
  CHECK_FALSE(ex);
  CHECK(t.sram_64bit_pj(16384, &ex) == Approx(10 * std::sqrt(2.0)));
  CHECK_FALSE(ex);
  CHECK(t.sram_64bit_pj(1 << 20) == Approx(100));
  CHECK(t.sram_64bit_pj(2 << 20, &ex) == Approx(100 * std::pow(2.0, std::log(5.0) / std::log(32.0))));
  CHECK(ex);
  CHECK(t.sram_64bit_pj(4096, &ex) == Approx(10 / std::sqrt(2.0)));
  CHECK(ex);
}

TEST_CASE("tech file: a user's file, and bad values named by file and field", "[tech]") {
  TempDir dir("tech_file_test");
  const std::string path = dir.file("tech.json");
  write_file(path, flat_tech(2).dump());
  const TechFile t = load_tech_file(path);
  CHECK(t.energy_pj(box_test_ops()) == 40);  // 20 operations at 2 pJ
  CHECK(t.sram_64bit_pj(2048) == Approx(8));

  const auto broken = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = flat_tech(2);
    edit(j);
    write_file(path, j.dump());
    return error_of(path);
  };
  CHECK(broken([](nlohmann::json& j) { j["energy_pj"]["fp32_mul"]["value"] = -1; }) ==
        path + ": field 'energy_pj.fp32_mul.value': must be >= 0");
  CHECK(broken([](nlohmann::json& j) { j["energy_pj"].erase("fp32_fma"); }) ==
        path + ": field 'energy_pj.fp32_fma': missing");
  CHECK(broken([](nlohmann::json& j) { j["area_mm2"]["fp32_add"]["value"] = "big"; }) ==
        path + ": field 'area_mm2.fp32_add.value': must be a finite number");
  CHECK(broken([](nlohmann::json& j) { j["energy_pj"]["fp64_add"] = figure(1); }) ==
        path + ": field 'energy_pj.fp64_add': unknown field");
  CHECK(broken([](nlohmann::json& j) { j["sram_read_64bit_pj"][1]["bytes"] = 512; }) ==
        path + ": field 'sram_read_64bit_pj[1].bytes': sizes must be listed in ascending order, each once");
  CHECK(broken([](nlohmann::json& j) { j["sram_read_64bit_pj"] = nlohmann::json::array(); }) ==
        path + ": field 'sram_read_64bit_pj': must be a non-empty list of {bytes, value, source}");
  CHECK(broken([](nlohmann::json& j) { j.erase("leakage_w_per_mm2"); }) ==
        path + ": field 'leakage_w_per_mm2': missing");
  CHECK(error_of(dir.file("absent.json")).find("cannot open") != std::string::npos);
}

namespace {

/// Every {value, source} figure under `j`, by its field name.
void collect_figures(const nlohmann::json& j, const std::string& at, std::vector<std::pair<std::string, nlohmann::json>>& out) {
  if (j.is_object() && j.contains("value")) {
    out.emplace_back(at, j);
    return;
  }
  if (j.is_object())
    for (const auto& [k, v] : j.items()) collect_figures(v, at.empty() ? k : at + "." + k, out);
  if (j.is_array())
    for (size_t i = 0; i < j.size(); ++i) collect_figures(j[i], at + "[" + std::to_string(i) + "]", out);
}

}  // namespace

TEST_CASE("tech file: the shipped 7 nm file loads, every figure with its source", "[tech]") {
  const std::string path = tech_dir() + "/7nm.json";
  const TechFile t = load_tech_file(path);
  CHECK(t.node_nm == 7);
  CHECK(t.op_pj[0] == 0.38);  // Jouppi et al., ISCA 2021: fp32 add at 7 nm
  CHECK(t.op_pj[1] == 1.31);  // fp32 multiply
  CHECK(t.op_pj[7] == 0.03);  // int32 add
  CHECK(t.sram_bit_mm2 == Approx(0.027e-6 * 1.6));  // TSMC N7's 0.027 um2 cell and the 45 nm file's periphery
  // Cheaper than 45 nm in every operation and every area figure.
  const TechFile t45 = load_tech_file(default_tech_path());
  for (int k = 0; k < kOpKinds; ++k) {
    INFO(kOpKindNames[k]);
    CHECK(t.op_pj[k] < t45.op_pj[k]);
    CHECK(t.op_mm2[k] < t45.op_mm2[k]);
  }
  REQUIRE(t.sram.size() == t45.sram.size());
  std::vector<std::pair<std::string, nlohmann::json>> figures;
  collect_figures(nlohmann::json::parse(vbsim::test::read_file(path)), "", figures);
  // 11 energies, 12 areas, 3 SRAM points, DRAM, leakage.
  CHECK(figures.size() == 28);
  for (const auto& [field, f] : figures) {
    INFO(field);
    REQUIRE(f.contains("source"));
    const std::string source = f["source"].get<std::string>();
    // A published figure names its publication and year; an estimate says so
    // and what it was derived from.
    const bool estimate = source.rfind("estimate: ", 0) == 0;
    const bool cited = source.find("20") != std::string::npos && source.find(',') != std::string::npos;
    CHECK((estimate || cited));
    CHECK(source.size() > 40);
  }
}

TEST_CASE("tech file: figures too large to total and SRAM sizes that are no sizes are refused", "[tech]") {
  // A figure near the double limit once priced a run as per_ray_pj null and
  // 0 Mrays/J with exit 0; SRAM sizes of 2^64 and 8192.5 bytes were accepted.
  TempDir dir("tech_file_limits_test");
  const std::string path = dir.file("tech.json");
  const auto broken = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = flat_tech(2);
    edit(j);
    write_file(path, j.dump());
    return error_of(path);
  };
  CHECK(broken([](nlohmann::json& j) { j["energy_pj"]["fp32_add"]["value"] = 1.797e308; }) ==
        path + ": field 'energy_pj.fp32_add.value': 1.797e+308 is beyond 1e+09: no node's figure is that large");
  CHECK(broken([](nlohmann::json& j) { j["area_mm2"]["sram_bit"]["value"] = 1e300; }) ==
        path + ": field 'area_mm2.sram_bit.value': 1e+300 is beyond 1e+09: no node's figure is that large");
  CHECK(broken([](nlohmann::json& j) { j["leakage_w_per_mm2"]["value"] = 2e9; }) ==
        path + ": field 'leakage_w_per_mm2.value': 2e+09 is beyond 1e+09: no node's figure is that large");
  CHECK(broken([](nlohmann::json& j) { j["sram_read_64bit_pj"][1]["bytes"] = 18446744073709551615.0; }) ==
        path + ": field 'sram_read_64bit_pj[1].bytes': 1.84467e+19 must be a whole number of bytes from 1 to 2^40");
  CHECK(broken([](nlohmann::json& j) { j["sram_read_64bit_pj"][1]["bytes"] = 8192.5; }) ==
        path + ": field 'sram_read_64bit_pj[1].bytes': 8192.5 must be a whole number of bytes from 1 to 2^40");
  CHECK(broken([](nlohmann::json& j) { j["sram_read_64bit_pj"][0]["value"] = 1e300; }) ==
        path + ": field 'sram_read_64bit_pj[0].value': 1e+300 is beyond 1e+09: no node's figure is that large");
  // The largest figures allowed still price a run finitely: a billion pJ per operation.
  write_file(path, flat_tech(1e9).dump());
  const TechFile t = load_tech_file(path);
  CHECK(std::isfinite(t.energy_pj(box_test_ops()) * 1e12));
}
