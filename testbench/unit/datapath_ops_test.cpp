// The traversal datapath's operation counts, recounted by hand from the code
// (ray_box_tester.h, the three testers' intersect() and constructors,
// bvh_stepper.h's push and pop), kind by kind.
#include <catch2/catch.hpp>

#include "datapath/datapath_ops.h"

using namespace vbsim;

namespace {
OpCounts counts(int fadd, int fmul, int fma, int fdiv, int fsqrt, int fcmp, int fsel, int iadd, int ishift, int cvt) {
  OpCounts c;
  c.fadd = fadd, c.fmul = fmul, c.fma = fma, c.fdiv = fdiv, c.fsqrt = fsqrt;
  c.fcmp = fcmp, c.fsel = fsel, c.iadd = iadd, c.ishift = ishift, c.cvt = cvt;
  return c;
}
}  // namespace

TEST_CASE("datapath ops: the box test and its set-up", "[datapath_ops]") {
  // hits(): 3 axes x (near, far) x (bound - o, * inv) = 6 fadd + 6 fmul; 3 max
  // for the entry (with tmin), 2 min for the exit, * kWiden, min with tmax,
  // entry <= limit.
  CHECK(box_test_ops() == counts(6, 7, 0, 0, 0, 7, 0, 0, 0, 0));
  CHECK(box_test_ops().total() == 20);
  // Per axis: |d|, copysign, the compare with 1e-18, 1 / d, inv >= 0.
  CHECK(box_setup_ops() == counts(0, 0, 0, 3, 0, 6, 6, 0, 0, 0));
}

TEST_CASE("datapath ops: each tester's triangle test", "[datapath_ops]") {
  // Three half-plane: 9 + 6 + 3 + 2 + 2 fadd; 6 + 6 + 3 + 3 + 2 fmul;
  // 3 + 6 + 1 + 1 + 2 + 2 + 1 compares; |det| and the conditional negation;
  // t, u, v divides.
  CHECK(triangle_test_ops(TesterKind::ThreeHalfPlane) == counts(22, 20, 0, 3, 0, 16, 2, 0, 0, 0));
  CHECK(triangle_test_ops(TesterKind::ThreeHalfPlane).total() == 63);
  // Möller–Trumbore: e1, e2 (6), s (3), u + v (1) and 4 dots' and 2 crosses'
  // adds (8 + 6); 2 crosses' and 4 dots' products (12 + 12) and 3 * inv_det;
  // det == 0, u's two bounds, v >= 0, u + v <= 1, t's two bounds, front.
  CHECK(triangle_test_ops(TesterKind::MollerTrumbore) == counts(24, 27, 0, 1, 0, 8, 0, 0, 0, 0));
  CHECK(triangle_test_ops(TesterKind::MollerTrumbore).total() == 60);
  // pbrt-v4: 6 difference-of-products (6 fmul, 12 fma, 6 fadd) and the rest
  // as listed in datapath_ops.cpp.
  CHECK(triangle_test_ops(TesterKind::PbrtWatertight) == counts(39, 40, 12, 1, 0, 28, 13, 1, 0, 0));
  CHECK(triangle_test_ops(TesterKind::PbrtWatertight).total() == 134);
  // The per-ray set-ups: max_dimension (3 abs, 2 compares), then the shear.
  CHECK(triangle_setup_ops(TesterKind::ThreeHalfPlane) == counts(0, 0, 0, 3, 0, 3, 3, 0, 0, 0));
  CHECK(triangle_setup_ops(TesterKind::PbrtWatertight) == counts(0, 0, 0, 3, 0, 3, 5, 0, 0, 0));
  CHECK(triangle_setup_ops(TesterKind::MollerTrumbore).total() == 0);
}

TEST_CASE("datapath ops: stack push and pop", "[datapath_ops]") {
  CHECK(stack_push_ops() == counts(0, 0, 0, 0, 0, 0, 0, 3, 0, 0));
  CHECK(stack_pop_ops() == counts(0, 0, 0, 0, 0, 1, 0, 4, 0, 0));
  CHECK(kStackEntryBits == 96);
}
