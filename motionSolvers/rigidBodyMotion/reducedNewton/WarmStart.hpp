#pragma once
// The start of each reduced Newton solve, and everything that outlives a solve.
//
// Cold (no guess): the harmonic interpolation c n + P K⁻¹ P b(ū) of the prescribed
// displacements or, where the boundary is one rigid body in a fixed frame, the harmonic
// interpolation of the body's turn (TurnedStart.hpp), whichever has the lower energy.
//
// Warm (the previous time step's result): when the guess is this solver's own last result and
// the one before is known (a chain), a secant step along the boundary's path first,
// G = u_n + α (u_n − u_{n−1}), α fitting the prescribed change best (the start is then off by
// the second difference of the motion instead of the first); past a turning point of the motion
// (|α| > 2) the combination of the kept results that fits the new boundary best. Then the
// boundary mismatch moved in harmonically, start = G + K⁻¹ (b(new) − b(G)), K⁻¹ of the change
// taken from the extensions of earlier changes where it is their combination
// (HarmonicChangeBasis.hpp). A boundary back at rest starts on the reference mesh, its exact
// minimum.
//
// Along a chain the predictor misses by nearly the same field each step (its error is the
// curvature of the path), so the last Newton corrections (result − predictor) span a Galerkin
// step, c = (WᵀSW)⁻¹ Wᵀ(−∇Ẽ), that costs one S product per vector and no back-substitution
// (subspaceStep).
//
// Kept between solves: the last results (the predictor's history), the last corrections,
// the harmonic basis, and which unknown nodes border the prescribed ones.

#include "CompactUnknowns.hpp"
#include "HarmonicChangeBasis.hpp"
#include "LaplacianPreconditioner.hpp"
#include "RbmProblem.hpp"
#include "ReducedEnergy.hpp"
#include "ReducedIterate.hpp"
#include "RelativeDisplacement.hpp"

#include <span>
#include <string>
#include <vector>

namespace rbm::motion {

struct WarmStartOptions {
    // Cold starts (and warm ones without history): also try the turned start.
    bool turnedStart = true;
    // How many Newton corrections span the subspace step (0: none;
    // -rbm_reduced_correction_memory N).
    int correctionMemory = 3;
    // The harmonic correction from the basis of earlier changes (false: a back-substitution at
    // every step; -rbm_reduced_harmonic_basis false).
    bool harmonicBasis = true;
    // The displacement test's tolerance (≤ 0: off): corrections and subspace steps below ten
    // of it are noise, not kept or taken.
    double displacementTolerance = 1e-6;
};

class WarmStart {
public:
    WarmStart(const RbmProblem& problem, ReducedEnergy& energy, LaplacianPreconditioner& preconditioner,
              const RelativeDisplacement& relativeDisplacement, const WarmStartOptions& options);

    struct Start {
        ReducedIterate point;           // where Newton starts
        std::vector<double> predicted;  // compact: the predictor; this solve's correction is the result minus it
        bool chained = false;           // warm-started from this solver's own last result, with its history
        // The predictor meets the prescribed boundary to rounding (a turning point back to a
        // boundary met before, or a boundary back at rest): the start is usually the minimum.
        bool boundaryReproduced = false;
        bool subspaceStepDue = false;   // the kept corrections fit this start: try subspaceStep first
        std::string failure;            // a failed Laplacian solve (the reason), else empty
    };
    // The start for prescribedDisplacement, from initialGuess when given (warm).
    Start start(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess,
                const CompactUnknowns& unknowns);
    // One Galerkin step in the span of the kept corrections from point, taken when it lowers Ẽ
    // (Armijo); then point is the new one. Returns the subspace's dimension, 0 when no step was
    // taken.
    int subspaceStep(ReducedIterate& point, const CompactUnknowns& unknowns, bool monitor);
    // After a solve: its result u (converged or not) into the history, its correction into the
    // kept ones; warm: whether it had an initial guess.
    void record(const Start& start, const std::vector<Vector3>& u, bool converged, bool warm,
                const CompactUnknowns& unknowns);

    const HarmonicChangeBasis& harmonicBasis() const { return harmonicBasis_; }

private:
    // The start's unknowns (compact), before the turned start's choice.
    struct Predicted {
        std::vector<double> start;
        std::vector<double> predictorStart;  // the predictor's, where the reference mesh was taken instead
        std::string failure;                 // empty: the linear solves converged
        bool chained = false;                // from this solver's own last result, with its history
        bool boundaryReproduced = false;     // the predictor meets the prescribed boundary to rounding
    };
    // Warm: the secant along the history (when chained), then the boundary's mismatch moved
    // in harmonically; the reference mesh where the boundary is back at rest.
    Predicted predictFromGuess(std::span<const Vector3> prescribedDisplacement, const RbmState& initialGuess,
                               std::span<const double> offset);
    // Cold: the harmonic interpolation of the boundary.
    Predicted harmonicStart(std::span<const Vector3> prescribedDisplacement, std::span<const double> offset);
    // b(values) = Σ_{j prescribed} w ū_j − (K c)_k per unknown node k (compact).
    std::vector<double> boundaryRightHandSide(std::span<const Vector3> values, std::span<const double> slidingOffset);
    // Along a chain: base (the last result) ← the secant predictor, or past a turning point the
    // combination of the kept results that fits the new boundary best.
    void extrapolateAlongHistory(std::span<const Vector3> prescribedDisplacement, std::vector<Vector3>& base) const;
    // Where the boundary is one rigid body in a fixed frame: the turned start (TurnedStart.hpp)
    // from the reference mesh or the guess replaces point's displacements, rotations and energy
    // when its energy is lower.
    void keepTurnedStartIfLower(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess,
                                ReducedIterate& point);
    // At a turning point of the motion: the predictor G = u_0 + Σ_j c_j (u_0 − u_j) over
    // solutionHistory_ whose c fits the prescribed change on the prescribed nodes best (the
    // candidates in the .cpp), `secant` (c_1 alone) among them.
    std::vector<double> bestPredictorOnBoundary(std::span<const Vector3> prescribedDisplacement,
                                                std::vector<double> secant) const;

    const RbmProblem& problem_;
    ReducedEnergy& energy_;
    LaplacianPreconditioner& preconditioner_;
    const RelativeDisplacement& relativeDisplacement_;
    WarmStartOptions options_;  // with PETSc's options read (before harmonicBasis_, which takes one)
    HarmonicChangeBasis harmonicBasis_;
    // The last results (node displacements, newest first), for the predictor of warm starts:
    // the secant from the first two, a fit on the boundary over all at a turning point. An empty
    // one is the reference mesh (no displacement: the result before a cold solve).
    static constexpr std::size_t keptResults = 4;
    std::vector<std::vector<Vector3>> solutionHistory_;
    // The last Newton corrections (result − predictor, compact), newest first.
    std::vector<std::vector<double>> recentCorrections_;
    bool correctionsFromChain_ = false;  // recentCorrections_ are a chain's (else one unchained solve's)
    std::vector<int> boundaryNeighbours_;  // unknown nodes (compact) next to a prescribed one, then -1
    // Work arrays: a trial point, released after each use (releaseTrial): NewtonCg holds its
    // own for the line search, and both kept would be 96 bytes a node more at the peak.
    std::vector<Vector3> trial_;
    std::vector<Matrix3> trialRotations_;
    void releaseTrial();
};

} // namespace rbm::motion
