// Watertightness measurement: rays aimed exactly at the shared edges and shared
// vertices of a closed mesh, tested by brute force against every triangle.
//
// Targets: for every edge (used by exactly two triangles in a closed mesh) the
// float points a + s (b - a) for s = 1/4, 3/4 and the float midpoint 0.5 (a + b),
// each exactly on the edge when no step rounds; for every vertex the vertex itself.
// Each target is shot at from every origin with d = target - o in float32, tmin 0,
// tmax +inf. A ray is shot only when it crosses the surface transversally at its
// target (|cos(d, Ng)| > 0.01 with the same sign for every triangle incident to
// the target): then the exact ray meets the mesh near the target, and a
// watertight tester must report a hit on one of the incident triangles.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "datapath/testers.h"
#include "datapath/triangle.h"

namespace vbsim {

struct WatertightnessCounts {
  int64_t rays = 0;         ///< rays shot
  int64_t hit = 0;          ///< rays that report at least one hit on the mesh
  int64_t lost = 0;         ///< rays with no hit on the mesh at all (a closed mesh must be hit)
  int64_t holes = 0;        ///< rays that hit none of the triangles incident to their target
  int64_t double_hits = 0;  ///< rays whose smallest t is reported by more than one triangle
  int64_t exact_aim = 0;    ///< rays passing exactly through their target, which lies exactly
                            ///< on the edge or vertex (no rounding in target or in d)
  int64_t skipped = 0;      ///< (target, origin) pairs not shot: grazing at the target
  int64_t open_edges = 0;   ///< edges in one triangle only (an open mesh): not aimed at
};

/// Counts for `mesh` (closed: every edge in exactly two triangles, by exact vertex
/// positions) under tester `kind`, shooting every target from every origin.
/// Throws std::invalid_argument naming the first edge that is not shared by two
/// triangles, unless `allow_open`: then an open mesh (a scanned model with holes)
/// is measured at its interior edges and vertices only, boundary edges and their
/// vertices being no target, and `lost` keeps its meaning only for rays whose
/// target is interior (such a ray crosses the surface there).
WatertightnessCounts measure_watertightness(const std::vector<Triangle>& mesh, TesterKind kind,
                                            const std::vector<Vec3f>& origins, bool allow_open = false);

/// Number of targets measure_watertightness() aims at: 3 per edge + 1 per vertex
/// (interior ones only with `allow_open`).
int64_t watertightness_target_count(const std::vector<Triangle>& mesh, bool allow_open = false);

/// Deterministic origins for a mesh: `outside` points on a sphere of 2.5x the
/// bounding box half-diagonal around its centre and `inside` points within 0.3x
/// the smallest half-extent of the centre (inside for meshes like a sphere or box),
/// drawn from std::mt19937(seed).
std::vector<Vec3f> watertightness_origins(const std::vector<Triangle>& mesh, int outside,
                                          int inside, uint32_t seed);

/// One row of the standard measurement: a named closed mesh under one tester.
struct WatertightnessRow {
  std::string mesh;
  int64_t triangles = 0;
  TesterKind tester = TesterKind::ThreeHalfPlane;
  WatertightnessCounts counts;
};

/// The standard measurement: icosphere (1280 triangles) and tessellated box
/// (768 triangles), each at the origin and scaled by 2.5 + translated by 1000.37
/// on every axis, from 4 outside + 4 inside origins (seed 2013); one row per
/// mesh and tester, meshes in that order, testers in the order given.
std::vector<WatertightnessRow> standard_watertightness_rows(
    const std::vector<TesterKind>& testers = {TesterKind::ThreeHalfPlane,
                                              TesterKind::MollerTrumbore});

/// Rows as a markdown table (header line, separator line, one line per row).
std::string format_watertightness_table(const std::vector<WatertightnessRow>& rows);

/// The standard measurement for both testers as a markdown table.
std::string watertightness_report();

}  // namespace vbsim
