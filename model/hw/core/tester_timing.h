// The triangle tester's latency and issue interval derived from its own
// arithmetic (docs/hw-model.md, "Tester latency from its arithmetic"): the
// latency is the sum of the operator latencies along the test's longest
// dependency chain (triangle_test_critical_path), the issue interval the test's
// operations over the operators the unit has (one per operation: 1).
#pragma once
#include <cstdint>

#include <nlohmann/json.hpp>

#include "datapath/op_counts.h"
#include "datapath/testers.h"

namespace vbsim::hw {

/// Cycles from an operator's inputs to its result, per kind of operator
/// (op_counts.h). Defaults: SimTRaX's example configuration, from 65 nm
/// synthesis (FPADD 2, FPMUL 2, FPCMP 1, FPMIN 1, INTADD 1, CONV 1, BITWISE 1,
/// FPINV 16); fma, fdiv and fsqrt have no SimTRaX unit: fma as its multiply and
/// add in sequence (4), a divide and a square root as long as the reciprocal (16).
struct OperatorLatencies {
  uint32_t fadd = 2, fmul = 2, fma = 4, fdiv = 16, fsqrt = 16, fcmp = 1, fsel = 1, iadd = 1, ishift = 1, cvt = 1;
};

/// How the triangle unit's timing is set: from the tester's arithmetic
/// (`derive`), or the `latency` and `issue_interval` given.
struct TriangleTiming {
  bool derive = false;
  OperatorLatencies op;
  /// Arithmetic operators in one tester pipeline; 0: one per operation of a test
  /// (fully pipelined, issue interval 1).
  uint32_t operators = 0;
};

/// Cycles along `path` with latencies `op`.
uint32_t path_latency(const OpCounts& path, const OperatorLatencies& op);
/// The derived latency of a `kind` tester.
uint32_t derived_triangle_latency(TesterKind kind, const OperatorLatencies& op);
/// The derived issue interval: ceil(triangle_test_ops(kind) / operators), 1 with operators 0.
uint32_t derived_triangle_issue_interval(TesterKind kind, uint32_t operators);

/// Reads `operator_latency` into `op`; errors name `file` and the field under `path`.
void read_operator_latencies(const nlohmann::json& j, const std::string& file, const std::string& path,
                             OperatorLatencies& op);
nlohmann::json operator_latencies_json(const OperatorLatencies& op);

}  // namespace vbsim::hw
