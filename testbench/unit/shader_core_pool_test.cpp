// The shader cores' timing (hw/source/shader_core_pool.h), worked out by hand.
#include <catch2/catch.hpp>

#include "hw/source/shader_core_pool.h"

using vbsim::hw::ShaderConfig;
using vbsim::hw::ShaderCorePool;

namespace {

ShaderConfig pool_config(uint32_t cores, uint32_t lanes, uint32_t ops_per_lane, uint32_t latency) {
  ShaderConfig c;
  c.cores = cores;
  c.simd_lanes = lanes;
  c.ops_per_lane_cycle = ops_per_lane;
  c.pipeline_latency = latency;
  return c;
}

}  // namespace

TEST_CASE("shader cores: a ray's latency is its lane's, the throughput the core's", "[shader_cores]") {
  // One core of 2 lanes, 1 operation a lane a cycle, 4 cycles of pipeline: 2
  // operations a cycle in all.
  ShaderCorePool pool(pool_config(1, 2, 1, 4));
  // 7 operations on one lane: 7 cycles, then 4: there at 11. They take 3.5 of
  // the core's issue cycles.
  CHECK(pool.run(0, 7) == 11);
  // The next ray, ready at 0 as well, starts when the core has issue slots
  // again: cycle ceil(3.5) = 4, there at 4 + 7 + 4 = 15.
  CHECK(pool.run(0, 7) == 15);
  // A ray ready after the core has caught up starts at once: 10 + 2 + 4.
  CHECK(pool.run(10, 2) == 16);
  CHECK(pool.rays() == 3);
  CHECK(pool.ops() == 16);
  CHECK(pool.wait_cycles() == 4);
  CHECK(pool.lane_cycles() == 16);
  CHECK(pool.capacity(10) == 20);
}

TEST_CASE("shader cores: rays go to the core that can start them first", "[shader_cores]") {
  // Two cores of one lane, 2 operations a lane a cycle, no pipeline latency.
  ShaderCorePool pool(pool_config(2, 1, 2, 0));
  CHECK(pool.run(0, 4) == 2);  // core 0: ceil(4 / 2) cycles
  CHECK(pool.run(0, 4) == 2);  // core 1, free
  CHECK(pool.run(0, 3) == 4);  // core 0 again from cycle 2: 2 + ceil(3 / 2)
  CHECK(pool.run(1, 1) == 3);  // core 1 from cycle 2 (its slots taken to there): 2 + 1
  CHECK(pool.wait_cycles() == 2 + 1);
}
