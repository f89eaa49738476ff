#pragma once
// The options of the rigid-body-motion (RBM) motion solver: the `rigidBodyMotionSolverCoeffs`
// dictionary of constant/dynamicMeshDict. Every entry is optional; the defaults make
// `motionSolver rigidBodyMotionSolver;` alone the robust choice (coupled nonlinear RBM by
// reduced Newton, with 1/|d|² weights, docs/method.md §1 and §3).
//
//     rigidBodyMotionSolverCoeffs
//     {
//         coupling          coupled;              // coupled | decoupled            (thesis §2.3.2 / §2.3.1)
//         formulation       nonlinear;            // nonlinear | linearized         (thesis §2.3 / §2.4)
//         algorithm         reducedNewton;        // reducedNewton | newton | localGlobal  (coupled nonlinear only)
//         weighting         inverseDistanceSquared; // uniform | inverseDistance | inverseDistanceSquared
//         subSteps          auto;                 // auto | N ≥ 1                    (thesis §2.6)
//         maxSubStepSplits  6;                    // auto: halvings of a sub-step that inverts cells
//         maxSubSteps       100;                  // auto, linearized: cap on the automatic count
//         tolerance         1e-11;                // nonlinear convergence, relative to the cell size
//         relativeTolerance 1e-10;                // Newton's gradient reduction; Krylov tolerance
//                                                 //   (unset by default: each algorithm's own)
//         displacementTolerance 1e-6;             // reduced Newton: also converged when no node's
//                                                 //   estimated error exceeds this × its shortest edge
//                                                 //   (0: only the gradient tests, to round-off)
//         maxIterations     50;                   // nonlinear iterations (per sub-step; default:
//                                                 //   each algorithm's own, reduced Newton's 50)
//         linearSolver      automatic;            // automatic | direct | iterative | matrixFree
//         petscOptions      "-ksp_type cg -pc_type gamg";
//         stiffening        auto;                 // auto | none | inverseDistance (a b);
//                                                 //     quadratic inverseDistance (a b);
//                                                 //     power 0.8 inverseDistance (a b);
//                                                 //     movingAndFixed 0.75 0.2 (auto's)
//         untangle          on;                   // on | off: repair cells the solve left inverted
//         scaling           auto;                 // auto | rigid | similar | μ ≥ 0: neighbourhoods may
//                                                 //   also scale (reducedNewton in 2D; auto: similar
//                                                 //   there, rigid elsewhere; NeighbourhoodScaling.hpp)
//         transverseStiffness auto;             // auto | none | λ ≥ 0: penalty on the displacement's
//                                                 //   variation across a translation (reducedNewton;
//                                                 //   only in the solves where every moving prescribed
//                                                 //   point moves by one vector towards fixed walls
//                                                 //   facing it; auto: 100 in 2D, with
//                                                 //   stiffening auto's translation weights, none in 3D;
//                                                 //   TransverseGradientPenalty.hpp)
//         floatingPatches   (outlet "free.*");    // patches (names, groups or regular expressions)
//                                                 //   whose unconstrained points move freely
//     }
//
// Unknown keywords are errors that name the file and line and list the valid keywords (a
// misspelt keyword must not be ignored silently); bad values list the valid values.

#include "FoamDictionary.hpp"
#include "NeighbourhoodScaling.hpp"
#include "PetscSupport.hpp"
#include "RbmProblem.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rbm::motion {

enum class RbmCoupling { coupled, decoupled };
enum class RbmFormulation { nonlinear, linearized };
// How the coupled nonlinear energy is minimised: reducedNewton (the default), a Newton–CG on
// the displacements with the rotations eliminated (each node's rotation its best fit);
// newton, on all unknowns (SNES, analytic Hessian, started from the linearized solution); or
// localGlobal, alternation that hands over to Newton when it stalls.
enum class RbmAlgorithm { newton, localGlobal, reducedNewton };

// Stiffening of the edges near chosen patches, OpenFOAM's diffusivity syntax
// (`inverseDistance (patches)`, `quadratic inverseDistance (patches)`, and the wrapper
// `power k inverseDistance (patches)`, shaped like OpenFOAM's `exponential alpha <diffusivity>`):
// w_ij is multiplied by (h_min / d)^exponent, d the distance from the edge midpoint to the
// nearest face of the patches in the reference mesh, clipped below at h_min, the shortest
// edge of the mesh.
//
// The default, `stiffening auto;`, is `movingAndFixed 0.75 0.2` (below) in 2D (in 3D the
// single exponent below: there the split made the twisted cube's mesh worse) towards the patches the
// solver chooses (automaticStiffeningPatches in Stiffening.hpp: every patch with a boundary of
// its own, i.e. not empty, wedge, processor, cyclic or a symmetry plane), applied to a solve whose prescribed
// patches each move rigidly (a moving body in a fixed far field), and not to one where a
// prescribed patch deforms (a bending wing, a twisted cube), where it made the mesh worse;
// where the patches cannot be told apart (none of them moves, or every one does), `power 0.8
// inverseDistance` towards all of them. docs/motionSolver.md ("Default stiffening") has the
// measurements behind it. `stiffening none;` switches it off; an explicit form always applies.
inline constexpr double defaultStiffeningExponent = 0.8;

// `stiffening movingAndFixed a b;`: the patches of `auto`, split by how they are prescribed,
// each side with its own exponent: w_ij × (h_min/d_moving)^a × (h_min/d_fixed)^b, d_moving the
// distance to the prescribed patches that move, d_fixed to the other automatic patches (fixed,
// sliding, free). Applied as `auto` is (while every prescribed patch moves rigidly); where no
// automatic patch moves, or every one does, the single distance and defaultStiffeningExponent
// instead (EdgeStiffening.hpp has the rule).
struct SplitStiffeningExponents {
    double moving = 0.0;
    double fixed = 0.0;
    bool operator==(const SplitStiffeningExponents&) const = default;
};
// The default's: the cells near a moving body turn with it, those near the fixed walls only a
// little more than the rest (docs/motionSolver.md, "Default stiffening": the only pair of the
// study that improves on the single exponent on every case it measures).
inline constexpr SplitStiffeningExponents defaultSplitStiffening{0.75, 0.2};

struct StiffeningOptions {
    // 0: none; 1: inverseDistance; 2: quadratic inverseDistance; k: power k inverseDistance
    // (0 < k ≤ maxStiffeningExponent).
    double exponent = defaultStiffeningExponent;
    bool automaticPatches = true;      // `auto`: the solver chooses the patches; `patches` is empty
    std::vector<std::string> patches;  // patch names (or groups) as written
    // `auto` and `movingAndFixed a b` (automaticPatches, exponent the fallback's): the two
    // exponents; none with the explicit forms.
    std::optional<SplitStiffeningExponents> split = defaultSplitStiffening;
    // `movingAndFixed a b` written out: the split applies in 3D too. `auto`'s split applies to
    // planar (2D, pseudo-2D) problems only; a 3D problem takes the single exponent (EdgeStiffening).
    bool splitWritten = false;
    int line = 0;                      // of the entry, for errors about the patch names

    bool enabled() const { return exponent > 0.0; }
};

// Beyond this the far-field weights fall below rounding relative to the near ones on a
// boundary-layer mesh ((h_min/d)^k with d/h_min ~ 1e6), and the systems become singular in practice.
inline constexpr double maxStiffeningExponent = 4.0;

struct RigidBodyMotionOptions {
    RbmCoupling coupling = RbmCoupling::coupled;
    RbmFormulation formulation = RbmFormulation::nonlinear;
    RbmAlgorithm algorithm = RbmAlgorithm::reducedNewton;
    EdgeWeighting weighting = EdgeWeighting::inverseDistanceSquared;
    int subSteps = 0;                  // 0: automatic
    int maxSubStepSplits = 6;
    int maxSubSteps = 100;
    double tolerance = 1e-11;
    std::optional<double> relativeTolerance;
    // A millionth of each node's shortest edge: far below anything a mesh's quality or a flow
    // solver sees, so the solve stops there instead of spending CG iterations on driving the
    // gradient to its rounding level (docs/motionSolver.md, "Reduced Newton"). 0: off.
    double displacementTolerance = 1e-6;
    std::optional<int> maxIterations;
    LinearSolverKind linearSolver = LinearSolverKind::automatic;
    std::string petscOptions;                                        // as written
    std::vector<std::pair<std::string, std::string>> petscOptionList;  // (name, value or ""), parsed
    StiffeningOptions stiffening;
    bool untangle = true;              // untangling stage after a solve that left inverted cells (src/Untangling.hpp)
    // Rigid neighbourhoods (the thesis' energy) or neighbourhoods that may also scale, whose
    // scale costs `stiffness` (0: `similar`, free); the default solver in 2D only. `auto` (the
    // default, automaticScaling): similar where that is implemented, rigid elsewhere
    // (effectiveScaling in RbmSolverSelection.hpp; docs/motionSolver.md, "Neighbourhood scaling").
    bool automaticScaling = true;
    NeighbourhoodScaling scaling;      // when not automatic
    int scalingLine = 0;               // of the entry, for the error in 3D
    // λ of the penalty on the displacement's variation across a translation
    // (TransverseGradientPenalty.hpp; 0: `none`). `auto` (the default, automaticTransverseStiffness):
    // effectiveTransverseStiffness in RbmSolverSelection.hpp.
    bool automaticTransverseStiffness = true;
    double transverseStiffness = 0.0;  // when not automatic
    int transverseStiffnessLine = 0;
    // Patches whose condition neither prescribes nor slides their points (zeroGradient,
    // calculated, ...) keep their surface by default: the points slide on it. Listed here (names,
    // groups or regular expressions, as written), they float like interior points instead.
    std::vector<std::string> floatingPatches;
    int floatingPatchesLine = 0;
    std::string file;                  // the dictionary's file, for later errors

    bool automaticSubSteps() const { return subSteps == 0; }
    // A short description, e.g. "coupled nonlinear (reducedNewton), weighting
    // inverseDistanceSquared, subSteps auto, stiffening auto".
    std::string describe() const;

    // Reads the coefficient dictionary; throws rbm::InputError for unknown keywords and bad values.
    static RigidBodyMotionOptions read(const io::Dictionary& coefficients);
    // The keywords read() accepts, in documentation order.
    static const std::vector<std::string_view>& keywords();
};

std::string_view couplingName(RbmCoupling coupling);
std::string_view formulationName(RbmFormulation formulation);
std::string_view algorithmName(RbmAlgorithm algorithm);
std::string_view linearSolverName(LinearSolverKind kind);

// Splits a PETSc option string ("-ksp_type cg -ksp_monitor -ksp_rtol 1e-8") into (name,
// value) pairs, value "" for flags. A word that is not an option name (a '-' followed by a
// letter) and follows no option is an error (std::invalid_argument).
std::vector<std::pair<std::string, std::string>> parsePetscOptionString(std::string_view text);

} // namespace rbm::motion
