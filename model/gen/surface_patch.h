// Tessellated surface patches for the failure-case scenarios: a map from
// patch coordinates (a, b) to points (double precision), sampled on a grid and
// rounded once to float32 per vertex, two triangles per cell. Shared edges use
// the very same float vertices on both sides. Winding: a triangle's geometric
// normal points along d(map)/da x d(map)/db (for a frame, along its n).
#pragma once
#include <functional>
#include <vector>

#include "datapath/triangle.h"
#include "gen/scenario_trace_builder.h"

namespace vbsim {

/// An orthonormal frame at `centre`: e1, e2 span the patch, n = e1 x e2.
struct SurfaceFrame {
  DVec3 centre, e1, e2, n;
  DVec3 at(double a, double b, double h) const { return centre + a * e1 + b * e2 + h * n; }
};

/// The frame at `centre` whose normal is tilted from +z by `tilt` radians
/// about the axis (1, 1, 0) / sqrt 2 (no axis-aligned plane, so hit points round).
SurfaceFrame tilted_frame(DVec3 centre, double tilt);

/// Triangles of the map over [a0, a1] x [b0, b1] with na x nb cells.
std::vector<Triangle> tessellate(const std::function<DVec3(double, double)>& map, double a0, double a1,
                                 int na, double b0, double b1, int nb);

/// A flat sheet folded about the line a = 0 of `f`: the half a <= 0 lies in
/// the frame's plane, the half a >= 0 is turned by `fold` radians toward +n
/// (positive: a valley, concave on the front side; negative: a ridge, convex).
/// The dihedral angle on the front side is pi - fold.
DVec3 folded_sheet(const SurfaceFrame& f, double fold, double a, double b);

}  // namespace vbsim
