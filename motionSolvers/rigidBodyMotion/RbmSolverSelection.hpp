#pragma once
// The solver object of one RBM problem, chosen by the user's options (RigidBodyMotionOptions):
// the one place where `rigidBodyMotionSolverCoeffs` is translated into the options of the
// thesis' variants and the coupled nonlinear algorithms:
//
//   coupling decoupled                       → DecoupledSolver (linearized or nonlinear model)
//   coupled, formulation linearized          → CoupledLinearizedSolver
//   coupled nonlinear, algorithm reducedNewton → ReducedNewtonSolver (the default)
//   coupled nonlinear, algorithm newton      → CoupledNewtonSolver
//   coupled nonlinear, algorithm localGlobal → LocalGlobalThenNewton
//
// `tolerance` is one thing in all of them: the error allowed in a node's displacement,
// relative to the cell size. The iterations that move nodes directly (decoupled nonlinear,
// local/global) stop when no node moves by more than tolerance × its shortest edge; the
// Newton solvers test the gradient such an error produces, tolerance × (mean w|d| over the
// edges) × √(unknown nodes). `relativeTolerance` is the gradient's reduction and the Krylov
// tolerance; `maxIterations` counts nonlinear iterations, per sub-step.

#include "RbmProblem.hpp"
#include "RigidBodyMotionOptions.hpp"

#include <memory>
#include <string>

namespace rbm::motion {

// local/global without `maxIterations`: enough iterations to reach the thesis' tolerance on
// its cases (§3.1), few enough that a stall hands over to Newton early.
inline constexpr int defaultLocalGlobalMaximumIterations = 200;

// `scaling auto` in 2D: the scale costs 0.3 × its neighbourhood's squared size. Measured
// (docs/motionSolver.md, "Neighbourhood scaling"): better than rigid on every OpenFOAM
// tutorial that translates or squeezes, while the thesis' translated squares keep beating
// OpenFOAM's best diffusivity (a free scale, `similar`, does best on the squeezes but loses
// that case).
inline constexpr double automaticScaleStiffness = 0.3;

// `transverseStiffness auto`: λ of the penalty on the displacement's variation across a
// translation (TransverseGradientPenalty.hpp) for the default solver in 2D. Measured on
// OpenFOAM's movingCone (docs/motionSolver.md, "Translations"): with the translation weights of
// stiffening auto (EdgeStiffening.hpp) λ = 100 runs all 600 steps at 22.78° worst
// non-orthogonality, λ = 1000 at 22.96°; the rigid energy alone stops at step 361.
inline constexpr double automaticTransverseStiffness = 100.0;
// The λ in effect for a problem of this dimension: auto is automaticTransverseStiffness for
// the default solver (coupled nonlinear reducedNewton) in 2D, 0 elsewhere; an explicit value
// as written.
double effectiveTransverseStiffness(const RigidBodyMotionOptions& options, int dimension);

// The neighbourhoods' scaling in effect for a problem of this dimension: `scaling auto` is
// automaticScaleStiffness for the default solver (reducedNewton) in 2D and rigid elsewhere;
// an explicit value as written (rbm::InputError for a scaling other than rigid in 3D).
NeighbourhoodScaling effectiveScaling(const RigidBodyMotionOptions& options, int dimension);
// ", scaling auto = rigid" (or its stiffness) for `scaling auto`, in a solver's description;
// empty for a scaling written out.
std::string describeAutomaticScaling(const RigidBodyMotionOptions& options, int dimension);

// The solver for `problem` (which must outlive it).
std::unique_ptr<RbmSolver> makeRbmSolver(const RbmProblem& problem, const RigidBodyMotionOptions& options);

} // namespace rbm::motion
