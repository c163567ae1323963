// Watertightness of an open mesh (allow_open): boundary edges and their
// vertices are no target; interior ones are measured as on a closed mesh.
#include <catch2/catch.hpp>

#include "datapath/closed_meshes.h"
#include "datapath/watertightness.h"

namespace vbsim {
namespace {

/// The 4x4-cell box without its +z face (the last 32 of its 192 triangles).
std::vector<Triangle> box_without_top() {
  std::vector<Triangle> box = make_tessellated_box(4);
  box.resize(box.size() - 32);
  return box;
}

TEST_CASE("watertightness: an open mesh is aimed at its interior edges and vertices only", "[tester]") {
  const std::vector<Triangle> open = box_without_top();
  // By hand: the closed box has 288 edges and 98 vertices; its top face held 40
  // interior edges and 9 interior vertices. Open: 248 edges, 16 of them on the
  // rim; 89 vertices, 16 on the rim. Targets: 3 x 232 interior edges + 73 vertices.
  CHECK(watertightness_target_count(open, true) == 3 * 232 + 73);
  CHECK_THROWS_WITH(watertightness_target_count(open), Catch::Contains("not closed"));
  const std::vector<Vec3f> origins = watertightness_origins(open, 4, 4, 2013);
  const WatertightnessCounts c = measure_watertightness(open, TesterKind::ThreeHalfPlane, origins, true);
  CHECK(c.open_edges == 16);
  CHECK(c.rays + c.skipped == 8 * (3 * 232 + 73));
  CHECK(c.rays > 3000);
  CHECK(c.lost == 0);  // interior targets: the ray crosses the surface there
  CHECK(c.holes == 0);
  const WatertightnessCounts closed =
      measure_watertightness(make_tessellated_box(4), TesterKind::ThreeHalfPlane, origins, true);
  CHECK(closed.open_edges == 0);  // allow_open changes nothing on a closed mesh
}

TEST_CASE("watertightness: the pbrt-watertight tester loses no ray either", "[tester]") {
  const std::vector<Triangle> box = make_tessellated_box(4);
  const WatertightnessCounts c =
      measure_watertightness(box, TesterKind::PbrtWatertight, watertightness_origins(box, 4, 4, 2013));
  CHECK(c.rays > 3000);
  CHECK(c.lost == 0);
  CHECK(c.holes == 0);
}

}  // namespace
}  // namespace vbsim
