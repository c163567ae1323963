// The standard watertightness measurement and its markdown table.
#include <fmt/format.h>

#include <utility>

#include "datapath/closed_meshes.h"
#include "datapath/watertightness.h"

namespace vbsim {

namespace {
constexpr uint32_t kOriginSeed = 2013;
constexpr int kOutsideOrigins = 4;
constexpr int kInsideOrigins = 4;
const MeshPlacement kFarAway{2.5, 1000.37, 1000.37, 1000.37};
}  // namespace

std::vector<WatertightnessRow> standard_watertightness_rows(
    const std::vector<TesterKind>& testers) {
  const std::pair<const char*, std::vector<Triangle>> meshes[] = {
      {"icosphere", make_icosphere(3)},
      {"icosphere x2.5 +1000.37", make_icosphere(3, kFarAway)},
      {"box 8x8", make_tessellated_box(8)},
      {"box 8x8 x2.5 +1000.37", make_tessellated_box(8, kFarAway)},
  };
  std::vector<WatertightnessRow> rows;
  for (const auto& [name, mesh] : meshes) {
    const std::vector<Vec3f> origins =
        watertightness_origins(mesh, kOutsideOrigins, kInsideOrigins, kOriginSeed);
    for (TesterKind kind : testers) {
      rows.push_back({name, static_cast<int64_t>(mesh.size()), kind,
                      measure_watertightness(mesh, kind, origins)});
    }
  }
  return rows;
}

std::string format_watertightness_table(const std::vector<WatertightnessRow>& rows) {
  std::string out =
      "| mesh | triangles | tester | rays | lost | holes | double hits | exact aim | skipped |\n"
      "|---|---:|---|---:|---:|---:|---:|---:|---:|\n";
  for (const WatertightnessRow& row : rows) {
    const WatertightnessCounts& c = row.counts;
    out += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", row.mesh,
                       row.triangles, tester_name(row.tester), c.rays, c.lost, c.holes,
                       c.double_hits, c.exact_aim, c.skipped);
  }
  return out;
}

std::string watertightness_report() {
  return format_watertightness_table(standard_watertightness_rows());
}

}  // namespace vbsim
