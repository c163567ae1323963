// Hand-built scenes for cycle counts computed by hand: three floors under a
// three-node BVH, rays straight down, a one-core one-slot configuration, and
// a feed of a list of rays.
#pragma once
#include <cstdint>

#include <vector>

#include "hw/hw_config.h"
#include "hw/source/ray_feed.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "trace/trace_record.h"

namespace vbsim::hw::test {

/// One core, one slot, ideal memory of latency `mem`; box, triangle and
/// avoidance latencies lb, lt, la; one pipeline each, issue interval 1.
inline HwConfig one_slot(uint32_t mem, uint32_t lb, uint32_t lt, uint32_t la) {
  HwConfig c;
  c.cores = 1;
  c.slots_per_core = 1;
  c.memory.ideal = true;
  c.memory.ideal_latency = mem;
  c.box = {1, lb, 1};
  c.triangle = {1, lt, 1};
  c.avoidance = {1, la, 1};
  c.source = {1, 0, 0};
  return c;
}

inline Triangle floor_at(float z) { return Triangle{{0, 0, z}, {1, 0, z}, {0, 1, z}}; }

inline Bounds3f box_of(float zlo, float zhi) {
  Bounds3f b;
  b.lo = {0, 0, zlo};
  b.hi = {1, 1, zhi};
  return b;
}

// Three floors: prim 0 at z = 0, prim 1 at z = -1, prim 2 at z = -2. By hand:
// node 0 = {node 1 (z -1..0), leaf [prim 2]}, node 1 = {leaf [prim 0], leaf [prim 1]}.
struct ThreeFloors {
  Scene scene = make_scene({floor_at(0), floor_at(-1), floor_at(-2)});
  Bvh bvh;
  ThreeFloors() {
    bvh.tris = {{scene.triangles[0], 0}, {scene.triangles[1], 1}, {scene.triangles[2], 2}};
    bvh.nodes.resize(2);
    bvh.nodes[0].set_child(0, box_of(-1, 0), {1, 0});
    bvh.nodes[0].set_child(1, box_of(-2, -2), {2, 1});
    bvh.nodes[0].axis = 2;
    bvh.nodes[1].set_child(0, box_of(0, 0), {0, 1});
    bvh.nodes[1].set_child(1, box_of(-1, -1), {1, 1});
    bvh.nodes[1].axis = 2;
    bvh.root = {0, 0};
    bvh.root_bounds = box_of(-2, 0);
    bvh.depth = 3;
  }
};

/// The same three floors as one root leaf (no nodes).
struct ThreeFloorsLeaf {
  Scene scene = make_scene({floor_at(0), floor_at(-1), floor_at(-2)});
  Bvh bvh;
  ThreeFloorsLeaf() {
    for (uint32_t i = 0; i < 3; ++i) bvh.tris.push_back({scene.triangles[i], i});
    bvh.root = {0, 3};
    bvh.root_bounds = box_of(-2, 0);
    bvh.depth = 1;
  }
};

/// One floor (z = 0) as a root leaf.
struct OneFloorLeaf {
  Scene scene = make_scene({floor_at(0)});
  Bvh bvh;
  OneFloorLeaf() {
    bvh.tris.push_back({scene.triangles[0], 0});
    bvh.root = {0, 1};
    bvh.root_bounds = box_of(0, 0);
    bvh.depth = 1;
  }
};

inline TraceRay down_from(int64_t id, float z) {
  TraceRay r;
  r.id = id;
  r.o = {0.25f, 0.25f, z};
  r.d = {0, 0, -1};
  return r;
}

/// The rays of `rays` (which outlives the feed), one after the other.
inline RayFeed feed_of(const std::vector<TraceRay>& rays) {
  return [&rays, next = size_t{0}](TraceRay& tr) mutable {
    if (next == rays.size()) return false;
    tr = rays[next++];
    return true;
  };
}

}  // namespace vbsim::hw::test
