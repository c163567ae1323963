// The arithmetic of the traversal datapath per step, counted from the code
// (datapath_ops.cpp derives each count beside the function it counts). A
// pipelined unit computes every operation of its step whatever the early outs,
// so a test counts its whole path; the testers' double-precision redo of an
// exactly-zero edge function (a rare exception path) is not counted.
#pragma once
#include "datapath/op_counts.h"
#include "datapath/testers.h"

namespace vbsim {

/// One ray-box slab test (RayBoxTester::hits for one box; the two-child test is two of them).
OpCounts box_test_ops();
/// The box unit's per-ray set-up (RayBoxTester's constructor: 1/d, near sides).
OpCounts box_setup_ops();
/// One ray-triangle test of `kind` (its intersect(), every operation of a hit).
OpCounts triangle_test_ops(TesterKind kind);
/// The operations on the longest dependency chain of one ray-triangle test of
/// `kind`, one entry per operator the chain passes through (datapath_ops.cpp
/// derives each beside the code; docs/hw-model.md tabulates them). A pipelined
/// tester's latency is the sum of these operators' latencies.
OpCounts triangle_test_critical_path(TesterKind kind);
/// The tester's per-ray set-up (its constructor).
OpCounts triangle_setup_ops(TesterKind kind);
/// A push onto the traversal stack (BvhStepper::node_step when both children are met).
OpCounts stack_push_ops();
/// A pop from the traversal stack (BvhStepper::pop, one entry).
OpCounts stack_pop_ops();
/// Bits of one traversal-stack entry on chip (node reference 32 + count 32 + entry distance 32).
constexpr int kStackEntryBits = 96;

}  // namespace vbsim
