// Names of the ray/triangle testers, as configuration files and the CLI spell them.
#include "datapath/testers.h"

namespace vbsim {

namespace {
struct TesterName {
  TesterKind kind;
  const char* name;
};
constexpr TesterName kTesterNames[] = {
    {TesterKind::ThreeHalfPlane, "three-half-plane"},
    {TesterKind::MollerTrumbore, "moller-trumbore"},
    {TesterKind::PbrtWatertight, "pbrt-watertight"},
};
}  // namespace

const char* tester_name(TesterKind kind) {
  for (const TesterName& entry : kTesterNames)
    if (entry.kind == kind) return entry.name;
  return "unknown-tester";
}

bool parse_tester(const std::string& name, TesterKind& out) {
  for (const TesterName& entry : kTesterNames) {
    if (name == entry.name) {
      out = entry.kind;
      return true;
    }
  }
  return false;
}

}  // namespace vbsim
