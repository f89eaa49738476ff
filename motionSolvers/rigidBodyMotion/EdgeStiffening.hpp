#pragma once
// The stiffening in effect (RigidBodyMotionOptions' `stiffening`, Stiffening.hpp's factors):
// the factor f_ij of every edge, computed from the reference mesh, and the rule of
// `stiffening auto` that applies it only while every prescribed patch moves rigidly (a body
// moving in a fixed far field), not where a prescribed patch deforms (a bending wing), where
// it makes the mesh worse (docs/motionSolver.md, "Default stiffening").
//
// `stiffening movingAndFixed a b` splits auto's patches in two: the MOVING ones, prescribed
// patches whose prescribed displacement has been non-zero in some solve so far, and the FIXED
// ones, every other automatic patch (prescribed zero — fixedValue (0 0 0), uniformFixedValue
// (0 0 0) —, sliding, free). The rule reads the values the boundary conditions give, rbm's or
// OpenFOAM's, so that it holds for any condition type (sixDoFRigidBodyDisplacement, a host's
// setPatchDisplacement) without a list of types; a patch counts as moving from the first solve
// it moves in. Then
//
//     f_ij = (h_min / d_moving)^a · (h_min / d_fixed)^b
//
// each factor Stiffening.hpp's with its own patches (the same exact distances, clipped at
// h_min). Where the split leaves one side empty (no automatic patch moves, or every one does)
// there is nothing to tell apart, and auto's single factor applies. The factors are computed
// at the first solve that moves a patch, again only when the set of moving patches grows.
//
// Translations (2D, `stiffening auto` with the default solver's transverse penalty,
// TransverseGradientPenalty.hpp): while every moving prescribed point moves by one vector
// towards fixed walls that face it (TransverseGradientPenalty::translationTowardsFixedWalls),
// the factors are f_ij = |d_ij| / h_min instead, which turn the default 1/|d|² weights into
// 1/|d| ones (no stiffening; other weightings: no factors). A body translating towards a wall
// squeezes the cells between uniformly only with those: the stiffening makes the cells far
// from the body the softest, and 1/|d|² weights the largest cells, so the squeeze collects
// there (OpenFOAM's movingCone with the penalty: stiffening auto stops at step 450 of 600,
// stiffening none with 1/|d|² at 559–568, 1/|d| runs to the end; docs/motionSolver.md,
// "Translations").
//
// The factors are shared with the problems built from them (one array of about 200 bytes per
// cell in 3D instead of three).

#include "CellNeighbourGraph.hpp"
#include "PolyMesh.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RigidBodyMotionOptions.hpp"
#include "Vector3.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rbm::motion {

class EdgeStiffening {
public:
    EdgeStiffening() = default;   // no stiffening
    // `referencePoints`: the problem's nodes (2D: planar nodes of `twoD`); `points0`: the
    // mesh's. Throws InputError (options.file, the stiffening entry's line) for a patch name
    // that is neither a patch nor a group of `mesh`. Every argument must outlive this object
    // (movingAndFixed computes its factors at the first solve).
    EdgeStiffening(const RigidBodyMotionOptions& options, const PolyMesh& mesh, const std::vector<Vector3>& points0,
                   const PseudoTwoDMesh* twoD, const CellNeighbourGraph& graph,
                   const std::vector<Vector3>& referencePoints, int dimension);
    // Stiffening.hpp's factors per directed graph edge towards `patches` (indices into the
    // mesh's patches) with `exponent`.
    using FactorSource = std::function<std::vector<double>(std::span<const Label> patches, double exponent)>;
    // The same rules with the factors computed elsewhere: on one rank's part of a decomposed
    // mesh (`mesh` its local mesh, whose patches are everyone's; `faceCounts` per patch its
    // faces over all ranks, for `stiffening auto`'s choice), from the surface gathered from all
    // ranks (PartStiffening.hpp). Collective when `source` is.
    EdgeStiffening(const RigidBodyMotionOptions& options, const PolyMesh& mesh, int dimension, FactorSource source,
                   std::span<const Label> faceCounts = {});

    // The factors in effect, per directed edge of the graph; null: no stiffening.
    const std::shared_ptr<const std::vector<double>>& factors() const { return inEffect_; }
    // The patches the distance is measured to (indices into mesh.patches).
    const std::vector<Label>& patches() const { return patches_; }
    // movingAndFixed: the patches of the moving distance in the factors computed last (empty
    // before the first solve that moves one, and where auto's single factor applies).
    const std::vector<Label>& movingPatches() const { return moving_; }
    // Whether `stiffening auto` (or movingAndFixed) decides per motion (followMotion below).
    bool automatic() const { return automatic_; }
    // `stiffening auto`: the factors for a motion whose prescribed patches do (not) all move
    // rigidly; `moved` (per mesh patch): whether the patch has moved in some solve so far, which
    // movingAndFixed splits the patches by. Returns whether the factors in effect changed (the
    // problem must be rebuilt).
    // `translation`: every moving prescribed point moves by one vector and the transverse
    // penalty applies (TransverseGradientPenalty::translationTowardsFixedWalls; the translation
    // factors above apply, where set).
    bool followMotion(bool allPatchesRigid, const std::vector<bool>& moved, bool translation = false);
    // Whether the factors in effect are the translation factors.
    bool translationFactorsInEffect() const { return inEffect_ && inEffect_ == translationWeights_; }
    // Lets go of the factors once the problem in use has its weights from them (8 bytes per
    // directed edge alive through the solver's set-up, solves and output otherwise: 210 MB at
    // 10⁶ hexahedra). factors() is then null until followMotion() or restoreFactors() applies
    // them again, which computes them again (the distances: a second cost only when a
    // deforming spell ends or the boundary conditions change). No-op with movingAndFixed's
    // split (its factors depend on the motion seen so far).
    void releaseFactors();
    // After releaseFactors(): the factors in effect then, computed again (nothing to do
    // otherwise), for a problem rebuilt with the same stiffening.
    void restoreFactors();
    // The factors in effect, as factors() would give them had they not been released (a copy).
    std::vector<double> factorsInEffect() const;
    // What `stiffening auto` chose, in words, to follow options.describe()'s "stiffening auto":
    // " = power 0.8 inverseDistance (patches) while every prescribed patch moves rigidly" (or
    // the split's words); empty for other stiffening entries or without patches.
    std::string describeAutomatic(const RigidBodyMotionOptions& options, const PolyMesh& mesh) const;

private:
    std::shared_ptr<const std::vector<double>> inEffect_;
    std::shared_ptr<const std::vector<double>> whenRigid_;   // auto: the factors when applied
    bool released_ = false;         // releaseFactors(): inEffect_ and whenRigid_ let go of
    bool appliedWhenReleased_ = false;  // whether the factors were in effect then (and since)
    std::vector<Label> patches_;
    std::vector<Label> moving_;
    bool automatic_ = false;
    std::optional<SplitStiffeningExponents> split_;
    double exponent_ = 0.0;
    int dimension_ = 3;
    // What the factors are computed by (movingAndFixed computes them at the first solve).
    FactorSource factorsTowards_;
    // The translation factors (set by the first constructor in 2D with 1/|d|² weights; empty:
    // none) and the factors once computed.
    std::function<std::vector<double>()> translationSource_;
    std::shared_ptr<const std::vector<double>> translationWeights_;
    bool translationComputed_ = false;
};

} // namespace rbm::motion
