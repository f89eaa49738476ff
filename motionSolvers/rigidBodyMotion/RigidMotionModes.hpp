#pragma once
// The rigid motions of the whole mesh in the unknowns of the coupled systems: the near null
// space that algebraic multigrid needs to coarsen these systems well.
//
// A rigid motion of every node (translation t, rotation Ω about a centre c) has zero RBM
// energy (docs/method.md §2): u_i = t + Ω × (x_i − c) and every node's rotation ω_i = Ω. So the
// coupled matrices are nearly singular along these vectors wherever the prescribed nodes are
// far away, which is exactly what smoothed-aggregation AMG (GAMG) must know to build coarse
// spaces that represent them; its default (a constant per unknown component) misses the
// coupling between u and ω and converges slowly on 6-unknown blocks.
//
// 3D: 6 modes (3 translations, 3 rotations); 2D: 3 (2 translations, 1 rotation). Each is a
// vector of problem.unknownCount() entries in the compact block layout, with sliding
// constraints applied (RbmProblem::projectSliding) and the set orthonormalised
// (modified Gram–Schmidt; modes that vanish under the constraints are dropped).

#include "RbmProblem.hpp"

#include <vector>

namespace rbm::motion {

std::vector<std::vector<double>> rigidMotionModes(const RbmProblem& problem);

} // namespace rbm::motion
