// Tester names: the spelling configuration files and the CLI use.
#include <catch2/catch.hpp>

#include <string>

#include "datapath/testers.h"

namespace vbsim {
namespace {

TEST_CASE("tester names round-trip and unknown names are refused", "[tester]") {
  CHECK(std::string(tester_name(TesterKind::ThreeHalfPlane)) == "three-half-plane");
  CHECK(std::string(tester_name(TesterKind::MollerTrumbore)) == "moller-trumbore");
  for (TesterKind kind : {TesterKind::ThreeHalfPlane, TesterKind::MollerTrumbore}) {
    TesterKind parsed = kind == TesterKind::ThreeHalfPlane ? TesterKind::MollerTrumbore
                                                           : TesterKind::ThreeHalfPlane;
    REQUIRE(parse_tester(tester_name(kind), parsed));
    CHECK(parsed == kind);
  }
  TesterKind untouched = TesterKind::MollerTrumbore;
  CHECK_FALSE(parse_tester("three_half_plane", untouched));
  CHECK_FALSE(parse_tester("Moller-Trumbore", untouched));
  CHECK_FALSE(parse_tester("", untouched));
  CHECK(untouched == TesterKind::MollerTrumbore);
}

}  // namespace
}  // namespace vbsim
