#pragma once
// The sub-step displacement method (thesis §2.6): the prescribed motion is applied in n
// increments, each solved around the mesh the previous increment produced, so that every
// increment is small for the linearized method.
//
// Automatic n (thesis §2.6): for every node whose displacement is given (prescribed nodes,
// and sliding nodes through the normal component of their plane's displacement), the
// smallest n with |u_b| / n shorter than the shortest reference distance from b to any
// neighbour, i.e. n_b = ⌊|u_b| / d_min(b)⌋ + 1 (1 for a node that does not move); n is the
// largest n_b.
//
// Two ways to chain the increments:
//   previousSubStep  (the thesis) increment k is solved as a problem of its own around the
//                    mesh of increment k−1 (reference points x + u_{k−1}, weights recomputed)
//                    with the prescribed increment ū(s_k) − ū(s_{k−1}); displacements add up,
//                    rotations compose. Needed by the linearized variants.
//   initialMesh      every increment is solved against the initial mesh for the total
//                    prescribed displacement ū(s_k), warm-started from increment k−1
//                    (continuation; the result depends only on the final boundary, docs/method.md §5).
//
// The boundary motion at fraction s ∈ (0, 1] of the step is ū(s) = s ū unless a motion law
// is given (a rotation should be split into rotations, not into chords).

#include "RbmProblem.hpp"

#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

// Thesis §2.6: the number of sub-steps for the given prescribed displacements (≥ 1).
int automaticSubStepCount(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement);

// The count `subSteps auto` uses for the linearized variants (issue 12). The thesis' rule
// compares |u_b| with the first cell height: on a boundary-layer mesh (wall spacing ~1e-5
// chord) a 4° rotation asks for 15 381 sub-steps although one linearized step of that
// rotation is valid (the linearized solve reproduces a rigid motion with node-local
// rotations; the error of the small-angle model grows with the angle, not with |u_b|).
// So every group of prescribed nodes (one per moving patch; groupNodes[groupOffsets[g] ..
// groupOffsets[g+1]) ) is split into its best rigid motion (centroid translation + best
// rotation of its nodes, the fit of §2.3 over the group) and the rest:
//   rotation angle θ_g and → ⌈(|θ_g| + |t_g − t_o| / gap_g) / maxAngle⌉ sub-steps: the
//   translation t_g           centroid's translation relative to the nearest other group o
//                            shears the cells between them by about |t_g − t_o| / gap_g
//                            (gap_g: clearance between the group's bounding circle and the
//                            nearest node of another group), so a translation of the whole
//                            mesh needs one sub-step;
//   non-rigid part r_b     → the thesis' rule on |r_b| (⌊|r_b| / d_min(b)⌋ + 1), parts below
//                            1e-9 of the group's size and motion being rounding;
//   sliding nodes          → the thesis' rule on the normal component, as above;
// n is the largest of these. A sub-step that still inverts cells is halved by the caller
// (maxSubStepSplits), so the count need not be conservative.
inline constexpr double defaultMaxSubStepAngleDegrees = 10.0;
int rotationAwareSubStepCount(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                              std::span<const int> groupOffsets, std::span<const int> groupNodes,
                              double maxAngleRadians);

enum class SubStepReference { previousSubStep, initialMesh };

struct SubStepOptions {
    int count = 0;  // 0: automatic (thesis §2.6)
    SubStepReference reference = SubStepReference::previousSubStep;
};

// Makes the solver of one increment for a problem (called once per increment in
// previousSubStep mode, once in total in initialMesh mode).
using RbmSolverFactory = std::function<std::unique_ptr<RbmSolver>(const RbmProblem&)>;
// The prescribed displacement of every node (relative to the initial mesh) at fraction s.
using BoundaryMotion = std::function<std::vector<Vector3>(double fraction)>;

struct SubSteppedResult : RbmResult {
    int subStepCount = 1;
};

// Displacements and rotations relative to the initial mesh of problem. iterations and
// linearIterations are summed over the increments; converged only if every increment
// converged; residualNorm and reason are the last increment's; energy is the exact energy E
// of the final state on the initial mesh.
SubSteppedResult solveInSubSteps(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                                 const RbmSolverFactory& makeSolver, SubStepOptions options = {});
// The same with a motion law: boundaryMotion(1) is the final prescribed displacement, and the
// automatic count is taken from it.
SubSteppedResult solveInSubSteps(const RbmProblem& problem, const BoundaryMotion& boundaryMotion,
                                 const RbmSolverFactory& makeSolver, SubStepOptions options = {});

} // namespace rbm::motion
