#pragma once
// How far a motion squeezes a mesh's cells: per cell that is valid before and after, its size
// after over its size before (2D: signed area; 3D: volume), at the 1st percentile, not the
// minimum, so that the few cells a failed step itself degenerated next to its inverted ones
// do not stand for the motion. 0 when no cell is valid in both.

#include "PlanarMesh.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <span>

namespace rbm {

double smallestCellSizeRatio(const PlanarMesh& planar, std::span<const Vector3> movedPoints);
double smallestCellSizeRatio(const PolyMesh& mesh, std::span<const Vector3> pointsBefore,
                             std::span<const Vector3> pointsAfter);

} // namespace rbm
