// Point-triangle distances computed by hand, and the point query over a scene.
#include <catch2/catch.hpp>

#include <cmath>

#include "scene/surface_proximity.h"

using namespace vbsim;

TEST_CASE("point-triangle distance: the plane inside, an edge or a vertex outside, a degenerate triangle",
          "[scene]") {
  const Triangle t{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  CHECK(point_triangle_distance({0.25f, 0.25f, 2}, t) == 2.0);
  CHECK(point_triangle_distance({0.25f, 0.25f, -3}, t) == 3.0);
  CHECK(point_triangle_distance({2, 0, 0}, t) == 1.0);                         // beyond vertex v1
  CHECK(point_triangle_distance({0.5f, -1, 0}, t) == 1.0);                     // below edge v0-v1
  CHECK(point_triangle_distance({1, 1, 0}, t) == Approx(std::sqrt(0.5)));      // beyond the hypotenuse
  CHECK(point_triangle_distance({1, 1, 1}, t) == Approx(std::sqrt(1.5)));
  const Triangle flat{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};                         // zero area: its segment
  CHECK(point_triangle_distance({1, 1, 0}, flat) == 1.0);
  CHECK(point_triangle_distance({3, 0, 0}, flat) == 1.0);
}

TEST_CASE("surface proximity: a point on a triangle, near one, and far from all", "[scene]") {
  const SurfaceProximity s({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{5, 5, 5}, {6, 5, 5}, {5, 6, 5}}});
  int64_t nearest = -7;
  CHECK(s.within({0.25f, 0.25f, 0}, 0.0f, &nearest));
  CHECK(nearest == 0);
  CHECK(s.within({5.25f, 5.25f, 5.001f}, 0.01f, &nearest));
  CHECK(nearest == 1);
  CHECK_FALSE(s.within({5.25f, 5.25f, 5.1f}, 0.01f, &nearest));
  CHECK(nearest == -1);
  CHECK_FALSE(s.within({2, 2, 2}, 0.5f));
  CHECK(SurfaceProximity({}).within({0, 0, 0}, 1.0f) == false);
}
