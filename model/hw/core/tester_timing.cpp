#include "hw/core/tester_timing.h"

#include <utility>

#include "datapath/datapath_ops.h"
#include "replay/config_fields.h"

namespace vbsim::hw {

namespace {

/// Each kind's name in the configuration and its member.
template <class F>
void for_each_kind(OperatorLatencies& op, F f) {
  f("fadd", op.fadd);
  f("fmul", op.fmul);
  f("fma", op.fma);
  f("fdiv", op.fdiv);
  f("fsqrt", op.fsqrt);
  f("fcmp", op.fcmp);
  f("fsel", op.fsel);
  f("iadd", op.iadd);
  f("ishift", op.ishift);
  f("cvt", op.cvt);
}

}  // namespace

uint32_t path_latency(const OpCounts& p, const OperatorLatencies& op) {
  return static_cast<uint32_t>(p.fadd * op.fadd + p.fmul * op.fmul + p.fma * op.fma + p.fdiv * op.fdiv +
                               p.fsqrt * op.fsqrt + p.fcmp * op.fcmp + p.fsel * op.fsel + p.iadd * op.iadd +
                               p.ishift * op.ishift + p.cvt * op.cvt);
}

uint32_t derived_triangle_latency(TesterKind kind, const OperatorLatencies& op) {
  return path_latency(triangle_test_critical_path(kind), op);
}

uint32_t derived_triangle_issue_interval(TesterKind kind, uint32_t operators) {
  if (operators == 0) return 1;
  const uint32_t ops = static_cast<uint32_t>(triangle_test_ops(kind).total());
  return (ops + operators - 1) / operators;
}

void read_operator_latencies(const nlohmann::json& j, const std::string& file, const std::string& path,
                             OperatorLatencies& op) {
  config_fields::Fields f(j, file, path);
  for_each_kind(op, [&](const char* name, uint32_t& v) { f.integer(name, v, 1, 100000); });
}

nlohmann::json operator_latencies_json(const OperatorLatencies& op) {
  nlohmann::json j = nlohmann::json::object();
  OperatorLatencies copy = op;
  for_each_kind(copy, [&](const char* name, uint32_t& v) { j[name] = v; });
  return j;
}

}  // namespace vbsim::hw
