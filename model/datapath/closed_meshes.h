// Closed triangle meshes generated in code, for watertightness measurements.
// Every generator builds an indexed mesh in double precision, rounds each vertex
// to float32 once, and emits triangles that reference those rounded vertices, so
// neighbouring triangles share vertex positions bit for bit. Winding is outward:
// Ng = (v1-v0) x (v2-v0) points out of the solid.
#pragma once
#include <vector>

#include "datapath/triangle.h"

namespace vbsim {

/// Similarity applied in double before the single rounding to float32:
/// p -> scale * p + (tx, ty, tz).
struct MeshPlacement {
  double scale = 1.0;
  double tx = 0.0, ty = 0.0, tz = 0.0;
};

/// Unit icosphere: the icosahedron with every face split in four `subdivisions`
/// times, new vertices pushed onto the unit sphere; 20 * 4^subdivisions triangles.
std::vector<Triangle> make_icosphere(int subdivisions, const MeshPlacement& placement = {});

/// Surface of the cube [-1, 1]^3 with each face cut into cells x cells squares,
/// two triangles per square (diagonals alternate); 12 * cells^2 triangles.
std::vector<Triangle> make_tessellated_box(int cells, const MeshPlacement& placement = {});

}  // namespace vbsim
