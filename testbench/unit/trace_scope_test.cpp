// TraceScope: hierarchical names matched exactly or with '*' within one level;
// a parent's pattern keeps its children, never a sibling that shares a prefix.
#include <catch2/catch.hpp>

#include "hw/observe/trace_scope.h"

using namespace vbsim::hw;

TEST_CASE("a trace scope keeps the instance it names and its children only", "[unit][tracing]") {
  const TraceScope one("accelerator.core_1");
  CHECK(one.matches("accelerator.core_1"));
  CHECK(one.matches("accelerator.core_1.box_unit"));
  CHECK(one.matches("accelerator.core_1.l1.tags"));
  CHECK_FALSE(one.matches("accelerator.core_10"));
  CHECK_FALSE(one.matches("accelerator.core_10.box_unit"));
  CHECK_FALSE(one.matches("accelerator"));
  CHECK_FALSE(one.matches("accelerator.core_"));

  const TraceScope cores("accelerator.core_*");
  CHECK(cores.matches("accelerator.core_1"));
  CHECK(cores.matches("accelerator.core_10.box_unit"));
  CHECK_FALSE(cores.matches("accelerator.l2_cache"));
  CHECK_FALSE(cores.matches("accelerator"));

  const TraceScope units("accelerator.*.box_unit,accelerator.l2_cache");
  CHECK(units.matches("accelerator.core_3.box_unit"));
  CHECK_FALSE(units.matches("accelerator.core_3.triangle_tester"));
  CHECK(units.matches("accelerator.l2_cache"));
  CHECK_FALSE(units.matches("accelerator.l2_cache_x"));

  CHECK(TraceScope("").matches("anything"));
  CHECK(TraceScope("acc*").matches("accelerator.core_0"));  // '*' at the end of a level
  CHECK_FALSE(TraceScope("acc*").matches("other.core_0"));
  CHECK_THROWS_AS(TraceScope("a,,b"), TraceScopeError);
}

TEST_CASE("a trace scope that names no instance is an error listing the instances", "[unit][tracing]") {
  const std::vector<std::string> names = {"accelerator", "accelerator.core_0", "accelerator.core_1"};
  CHECK_NOTHROW(TraceScope("accelerator.core_1").check(names));
  CHECK_NOTHROW(TraceScope("").check(names));
  CHECK_THROWS_WITH(TraceScope("accelerator.core_2,accelerator.core_0").check(names),
                    Catch::Contains("'accelerator.core_2'") && Catch::Contains("accelerator.core_1") &&
                        !Catch::Contains("'accelerator.core_0'"));
  CHECK_THROWS_AS(TraceScope("accelerator.core").check(names), TraceScopeError);
}
