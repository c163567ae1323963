// Oracle: ties on shared edges, vertices and duplicates, the open ray interval,
// intended origins, fill_expect, BVH coverage checks, and a cross-check of the
// filtered BVH traversal against a brute-force rational search on random scenes.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "exact/expected_answers.h"
#include "exact/oracle.h"
#include "oracle_test_support.h"

using namespace vbsim;

namespace {

ExactRay make_ray(Vec3f o, Vec3f d) {
  ExactRay r;
  r.o = to_exact(o);
  r.d = to_exact(d);
  return r;
}

mpq_class plane_offset(const ExactVec3& p, const Triangle& tri) {
  const ExactVec3 v0 = to_exact(tri.v0);
  const ExactVec3 e1 = test::sub(to_exact(tri.v1), v0), e2 = test::sub(to_exact(tri.v2), v0);
  return test::det3(test::sub(p, v0), e1, e2);
}

// The oracle over differently shaped BVHs of one scene: one leaf, median
// splits with one triangle per leaf, and the project's SAH BVH (build_bvh).
struct Oracles {
  Scene scene;
  Bvh one_leaf, leaf1, sah;
  Oracle a, b, c;
  explicit Oracles(std::vector<Triangle> tris)
      : scene(make_scene(std::move(tris))),
        one_leaf(test::single_leaf_bvh(scene)),
        leaf1(test::MedianBvhBuilder(scene, 1).build()),
        sah(build_bvh(scene)),
        a(scene, one_leaf),
        b(scene, leaf1),
        c(scene, sah) {}

  // Checks all three against the reference and returns the ties.
  std::vector<int32_t> ties(const ExactRay& ray) const {
    const test::ReferenceClosest ref = test::reference_closest(scene, ray);
    for (const Oracle* o : {&a, &b, &c}) {
      const OracleAnswer ans = o->answer(ray);
      REQUIRE(o->closest_ties(ray) == ref.ties);
      if (ref.ties.empty()) {
        REQUIRE(ans.prim == -1);
      } else {
        REQUIRE(ans.prim == ref.ties.front());
        REQUIRE(ans.t_exact == ref.t);
      }
    }
    return ref.ties;
  }
};

Triangle tri(Vec3f a, Vec3f b, Vec3f c) { return {a, b, c}; }

}  // namespace

TEST_CASE("a ray through a shared edge ties both triangles", "[oracle]") {
  const Triangle far = tri({-5, -5, -3}, {5, -5, -3}, {0, 5, -3});
  const Triangle t_hi = tri({1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  const Triangle t_lo = tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const Oracles o({far, t_hi, far, t_lo});  // the edge's triangles are 1 and 3
  const ExactRay r = make_ray({0.5f, 0.5f, 1}, {0, 0, -1});
  CHECK(o.ties(r) == std::vector<int32_t>{1, 3});
  const OracleAnswer ans = o.b.answer(r);
  CHECK(ans.prim == 1);
  CHECK(ans.t_exact == 1);
  CHECK(ans.t == 1.0);
}

TEST_CASE("a ray through a fan's shared vertex ties all six triangles", "[oracle]") {
  const Vec3f rim[6] = {{1, 0, 0}, {0.5f, 1, 0}, {-0.5f, 1, 0}, {-1, 0, 0}, {-0.5f, -1, 0}, {0.5f, -1, 0}};
  std::vector<Triangle> fan;
  for (int k = 0; k < 6; ++k) fan.push_back(tri({0, 0, 0}, rim[k], rim[(k + 1) % 6]));
  fan.push_back(tri({-9, -9, -1}, {9, -9, -1}, {0, 9, -1}));  // behind the fan
  const Oracles o(fan);
  CHECK(o.ties(make_ray({0, 0, 2}, {0, 0, -1})) == std::vector<int32_t>{0, 1, 2, 3, 4, 5});
  // A slanted ray through the same vertex.
  CHECK(o.ties(make_ray({0.25f, 0.5f, 1}, {-0.25f, -0.5f, -1})) ==
        std::vector<int32_t>{0, 1, 2, 3, 4, 5});
  // Just beside the vertex only one triangle is hit.
  CHECK(o.ties(make_ray({0.001f, 0.0001f, 2}, {0, 0, -1})).size() == 1);
}

TEST_CASE("duplicated triangles tie, whatever their winding", "[oracle]") {
  const Triangle t = tri({0, 0, 1}, {2, 0, 1}, {0, 2, 1});
  const Triangle flipped = tri(t.v0, t.v2, t.v1);
  const Oracles o({tri({0, 0, 5}, {2, 0, 5}, {0, 2, 5}), t, flipped, t});
  CHECK(o.ties(make_ray({0.5f, 0.5f, 0}, {0, 0, 1})) == std::vector<int32_t>{1, 2, 3});
}

TEST_CASE("the intended ray's interval is open and in-plane triangles are not hit", "[oracle]") {
  const Triangle floor = tri({-1, -1, 0}, {3, -1, 0}, {-1, 3, 0});
  const Triangle wall = tri({2, -5, -5}, {2, 5, -5}, {2, 0, 5});
  const Oracles o({floor, wall});
  SECTION("a ray in the floor's plane passes through the floor and hits the wall") {
    const ExactRay r = make_ray({-0.5f, 0, 0}, {1, 0, 0});
    CHECK(o.ties(r) == std::vector<int32_t>{1});
    CHECK(o.a.answer(r).t_exact == mpq_class(5, 2));
  }
  SECTION("t exactly at tmax is not a hit") {
    ExactRay r = make_ray({0, 0, 0.5f}, {1, 0, 0});  // wall at t = 2
    r.has_tmax = true;
    r.tmax = 2;
    CHECK(o.ties(r).empty());
    r.tmax = mpq_class(std::nextafter(2.0f, 3.0f));
    CHECK(o.ties(r) == std::vector<int32_t>{1});
  }
  SECTION("t exactly 0 is not a hit") {
    CHECK(o.ties(make_ray({0.5f, 0.5f, 0}, {1, 0, 1})) == std::vector<int32_t>{1});  // leaves the floor
    CHECK(o.ties(make_ray({0.5f, 0.5f, 0}, {-1, 0, 1})).empty());
  }
}

TEST_CASE("intended_ray: parent plane point, then parent_uv, then projection", "[oracle]") {
  // Dyadic vertices, so that v1 - v0 is exact in float (an exactly in-plane direction).
  const Triangle parent = tri({0.125f, 0.25f, 0.375f}, {1.25f, 0.125f, 0.75f}, {0.375f, 1.125f, -0.5f});
  const Triangle behind = tri({-9, -9, 5}, {9, -9, 5}, {0, 9, 5});
  const Scene scene = make_scene({parent, behind});
  TraceRay cam;
  cam.id = 7;
  cam.o = {0.3f, -0.7f, 2.1f};
  cam.d = {0.1f, 0.9f, -1.7f};
  const ParentRays parents = collect_parent_rays({cam});

  ExactVec3 hit_point;
  REQUIRE(exact_plane_point(cam.o, cam.d, parent, hit_point));
  const float t_f = static_cast<float>(-plane_offset(to_exact(cam.o), parent).get_d()) /
                    dot(cam.d, geometric_normal(parent));
  TraceRay child;
  child.id = 8;
  child.parent = 7;
  child.kind = RayKind::Reflect;
  child.o = cam.o + t_f * cam.d;  // float: off the plane
  child.d = {0.2f, 0.1f, 1.0f};
  child.parent_prim = 0;
  REQUIRE(plane_offset(to_exact(child.o), parent) != 0);

  SECTION("camera rays keep o") {
    const ExactRay r = intended_ray(cam, scene, find_parent(parents, cam.parent));
    CHECK(r.o.x == to_exact(cam.o).x);
    CHECK_FALSE(r.has_tmax);
  }
  SECTION("the parent ray's exact plane point, on the plane in rationals") {
    const ExactRay r = intended_ray(child, scene, find_parent(parents, child.parent));
    CHECK(plane_offset(r.o, parent) == 0);
    CHECK(r.o.x == hit_point.x);
    CHECK(r.o.y == hit_point.y);
    CHECK(r.o.z == hit_point.z);
    CHECK(r.d.z == 1);
    // The child leaves the parent (t = 0 there) and reaches the far triangle.
    const Bvh bvh = test::single_leaf_bvh(scene);
    CHECK(Oracle(scene, bvh).answer(r).prim == 1);
  }
  SECTION("parent_uv when the parent ray is unknown or parallel to the plane") {
    child.has_parent_uv = true;
    child.parent_u = 0.25f;
    child.parent_v = 0.5f;
    const ExactVec3 expect = exact_barycentric_point(parent, 0.25f, 0.5f);
    for (const ParentRays* p : {static_cast<const ParentRays*>(nullptr), &parents}) {
      ParentRays parallel;
      parallel[7] = {cam.o, parent.v1 - parent.v0};  // in-plane direction
      const ExactRay r = intended_ray(child, scene, p ? find_parent(parallel, child.parent) : nullptr);
      CHECK(r.o.x == expect.x);
      CHECK(r.o.z == expect.z);
      CHECK(plane_offset(r.o, parent) == 0);
    }
  }
  SECTION("projection of o without parent ray and uv; o itself on a degenerate parent") {
    const ExactRay r = intended_ray(child, scene, nullptr);
    CHECK(plane_offset(r.o, parent) == 0);
    const ExactVec3 po = test::sub(to_exact(child.o), r.o);
    const ExactVec3 e1 = test::sub(to_exact(parent.v1), to_exact(parent.v0));
    CHECK(po.x * e1.x + po.y * e1.y + po.z * e1.z == 0);
    const Scene degenerate = make_scene({tri({0, 0, 0}, {1, 1, 1}, {2, 2, 2})});
    const ExactRay rd = intended_ray(child, degenerate, nullptr);
    CHECK(rd.o.x == to_exact(child.o).x);
  }
  SECTION("a parent_prim out of range is an error naming the ray") {
    child.parent_prim = 2;
    CHECK_THROWS_WITH(intended_ray(child, scene, find_parent(parents, child.parent)), Catch::Contains("ray 8"));
  }
}

TEST_CASE("an empty scene answers misses", "[oracle]") {
  const Scene empty = make_scene({});
  const Bvh bvh = build_bvh(empty);
  const Oracle oracle(empty, bvh);
  CHECK(oracle.answer(make_ray({0, 0, 0}, {0, 0, 1})).prim == -1);
  CHECK(oracle.closest_ties(make_ray({0, 0, 0}, {0, 0, 1})).empty());
}

TEST_CASE("fill_expect writes the exact answers", "[oracle]") {
  const Scene scene = make_scene({tri({-1, -1, 3}, {5, -1, 3}, {-1, 5, 3}), tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
  const Bvh bvh = test::MedianBvhBuilder(scene, 1).build();
  std::vector<TraceRay> rays(3);
  rays[0].id = 0;
  rays[0].o = {0.25f, 0.25f, 1};
  rays[0].d = {0, 0, 3};  // floor at t = -1/3: behind; ceiling at t = 2/3
  rays[1].id = 1;
  rays[1].o = {0.25f, 0.25f, 1};
  rays[1].d = {0, 0, -3};  // floor at t = 1/3
  rays[2].id = 2;
  rays[2].o = {0.25f, 0.25f, 1};
  rays[2].d = {1, 0, 0};   // parallel to both planes: a miss
  fill_expect(rays, scene, bvh);
  CHECK(rays[0].expect_prim == 0);
  CHECK(rays[0].expect_t == 2.0 / 3.0);
  CHECK(rays[1].expect_prim == 1);
  CHECK(rays[1].expect_t == 1.0 / 3.0);
  CHECK(rays[2].has_expect);
  CHECK(rays[2].expect_prim == -1);
  CHECK_FALSE(rays[2].has_expect_t);
}

TEST_CASE("the oracle rejects a BVH that does not cover the scene", "[oracle]") {
  const Scene scene = make_scene({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), tri({0, 0, 1}, {1, 0, 1}, {0, 1, 1})});
  Bvh bvh = test::MedianBvhBuilder(scene, 1).build();
  CHECK_NOTHROW(Oracle(scene, bvh));
  CHECK_NOTHROW(Oracle(scene, build_bvh(scene, {1})));
  const Scene twins = make_scene({scene.triangles[0], scene.triangles[0]});
  Bvh twice = test::MedianBvhBuilder(twins, 1).build();
  twice.tris[1].prim = twice.tris[0].prim;
  CHECK_THROWS_WITH(Oracle(twins, twice), Catch::Contains("two leaves"));
  Bvh small_box = bvh;
  small_box.nodes[0].box[2][0][1] = small_box.nodes[0].box[2][1][1] + 0.25f;  // child 1: low z above high z
  CHECK_THROWS_WITH(Oracle(scene, small_box),
                    Catch::Contains("node 0 child 1: box, or a box above it, does not enclose prim"));
  Bvh small_root = bvh;
  small_root.root_bounds.hi.z = 0.5f;  // the triangle at z = 1 sticks out of the root's box
  CHECK_THROWS_WITH(Oracle(scene, small_root), Catch::Contains("box, or a box above it, does not enclose prim 1"));
  // A child's box larger than its parent's (a low-precision box rounded
  // outward) is fine while every triangle lies inside every box above it.
  Bvh wide_child = bvh;
  wide_child.nodes[0].box[0][0][0] -= 1.0f;  // child 0 reaches 1 beyond the root's box in -x
  wide_child.nodes[0].box[1][1][1] += 1.0f;  // child 1 beyond it in +y
  CHECK_NOTHROW(Oracle(scene, wide_child));
  Bvh dangling = bvh;
  dangling.nodes[0].count[0] = 0;  // child 0 now claims to be an interior node
  dangling.nodes[0].ref[0] = 5;
  CHECK_THROWS_WITH(Oracle(scene, dangling), Catch::Contains("out of range"));
}

namespace {

std::vector<Triangle> random_triangles(std::mt19937& rng, int n) {
  std::uniform_int_distribution<int> grid(-4, 4), kind(0, 9);
  std::uniform_real_distribution<float> real(-2, 2);
  auto gp = [&] { return Vec3f{grid(rng) * 0.5f, grid(rng) * 0.5f, grid(rng) * 0.5f}; };
  auto rp = [&] { return Vec3f{real(rng), real(rng), real(rng)}; };
  std::vector<Triangle> out;
  while (static_cast<int>(out.size()) < n) {
    const int k = out.empty() ? 0 : kind(rng);
    if (k <= 2) out.push_back({gp(), gp(), gp()});
    else if (k <= 4) out.push_back({rp(), rp(), rp()});
    else if (k == 5) {  // near-degenerate sliver
      const Vec3f a = rp(), b = rp();
      out.push_back({a, b, 0.5f * (a + b) + Vec3f{1e-6f, -2e-6f, 1e-6f}});
    } else if (k == 6) {  // coplanar on z = 0.5, sharing the grid
      out.push_back({{grid(rng) * 0.5f, grid(rng) * 0.5f, 0.5f}, {grid(rng) * 0.5f, grid(rng) * 0.5f, 0.5f},
                     {grid(rng) * 0.5f, grid(rng) * 0.5f, 0.5f}});
    } else if (k == 7) {  // duplicate, sometimes flipped
      const Triangle t = out[std::uniform_int_distribution<size_t>(0, out.size() - 1)(rng)];
      out.push_back(kind(rng) < 5 ? t : Triangle{t.v0, t.v2, t.v1});
    } else {  // shares an edge or a vertex with an earlier triangle
      const Triangle t = out[std::uniform_int_distribution<size_t>(0, out.size() - 1)(rng)];
      out.push_back({t.v1, t.v0, k == 8 ? gp() : rp()});
    }
  }
  return out;
}

}  // namespace

TEST_CASE("filtered BVH traversal equals brute-force rationals on random scenes", "[oracle]") {
  std::mt19937 rng(2024);
  int hits = 0, multi_ties = 0, children = 0;
  for (int n : {50, 120, 200}) {
    const Oracles o(random_triangles(rng, n));
    const Scene& s = o.scene;
    std::uniform_int_distribution<int> grid(-6, 6), pick(0, n - 1), mode(0, 3);
    std::uniform_real_distribution<float> real(-3, 3);
    std::vector<TraceRay> trace;
    for (int i = 0; i < 60; ++i) {
      TraceRay r;
      r.id = static_cast<int64_t>(trace.size());
      r.o = i % 2 ? Vec3f{real(rng), real(rng), real(rng)}
                  : Vec3f{grid(rng) * 0.5f, grid(rng) * 0.5f, grid(rng) * 0.5f};
      const Triangle& t = s.triangles[static_cast<size_t>(pick(rng))];
      const int m = mode(rng);
      const Vec3f target = m == 0 ? t.v1 : m == 1 ? 0.5f * (t.v0 + t.v2) : m == 2 ? (1 / 3.0f) * (t.v0 + t.v1 + t.v2)
                                                                             : Vec3f{real(rng), real(rng), real(rng)};
      r.d = target - r.o;
      if (r.d == Vec3f{}) r.d = {0, 0, 1};
      if (i % 5 == 0) r.tmax = 1;  // shadow ray to the target
      const std::vector<int32_t> ties = o.ties(intended_ray(r, s, nullptr));
      hits += !ties.empty();
      multi_ties += ties.size() > 1;
      trace.push_back(r);
      // A child from the exact hit: float origin off the plane, intended origin on it.
      if (ties.empty() || i % 2) continue;
      const OracleAnswer a = o.a.answer(intended_ray(r, s, nullptr));
      TraceRay c;
      c.id = static_cast<int64_t>(trace.size());
      c.parent = r.id;
      c.parent_prim = a.prim;
      c.o = r.o + static_cast<float>(a.t) * r.d;
      const Triangle& aim = s.triangles[static_cast<size_t>(pick(rng))];
      c.d = i % 4 ? aim.v0 - c.o : Vec3f{real(rng), real(rng), real(rng)};
      if (c.d == Vec3f{}) c.d = {1, 0, 0};
      trace.push_back(c);
      const ParentRays parents = collect_parent_rays(trace);
      const ExactRay cr = intended_ray(c, s, find_parent(parents, c.parent));
      REQUIRE(plane_offset(cr.o, s.triangles[static_cast<size_t>(a.prim)]) == 0);
      const std::vector<int32_t> child_ties = o.ties(cr);
      // The intended origin is on the parent's plane: the parent is never re-hit.
      CHECK(std::find(child_ties.begin(), child_ties.end(), a.prim) == child_ties.end());
      ++children;
    }
  }
  CHECK(hits > 60);
  CHECK(multi_ties > 5);
  CHECK(children > 30);
}
