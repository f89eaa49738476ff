#pragma once
// What rbm tells a user whose step left inverted cells: the robust options their
// `rigidBodyMotionSolverCoeffs` leaves out (each can change the result), or, with all of them
// in effect, what the motion asks of the mesh that none of them can give (a squeeze, a
// rotation too large for the cells around the body) and what can.

#include "RigidBodyMotionOptions.hpp"

#include <string>
#include <vector>

namespace rbm::motion {

// A squeeze below this (cell size after / before at the 1st percentile) is what folded the
// cells: a body closing a gap (OpenFOAM's movingCone squeezes cells to 0.02).
inline constexpr double squeezeAdviceRatio = 0.35;

// `dimension`: the problem's (2: planar); `largestRotationDegrees`: the largest rigid rotation
// of a prescribed patch in the step; `cellSizeRatio`: smallestCellSizeRatio
// (src/CellSizeRatio.hpp) of the step's mesh.
std::string invertedStepAdvice(const RigidBodyMotionOptions& options, int dimension, double largestRotationDegrees,
                               double cellSizeRatio);

// The options in effect that a robust choice would change for a problem of this dimension
// (empty: the robust choices are in effect).
std::vector<std::string> robustOptionChanges(const RigidBodyMotionOptions& options, int dimension);

} // namespace rbm::motion
