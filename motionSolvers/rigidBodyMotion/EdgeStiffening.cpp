#include "EdgeStiffening.hpp"

#include "InputError.hpp"
#include "Stiffening.hpp"

#include <algorithm>
#include <sstream>

namespace rbm::motion {

namespace {

// The patches of the stiffening distance: the automatic choice and/or the names and groups
// the user listed.
std::vector<Label> stiffenedPatches(const RigidBodyMotionOptions& options, const PolyMesh& mesh,
                                    std::span<const Label> faceCounts)
{
    const StiffeningOptions& stiffening = options.stiffening;
    std::vector<Label> patches;
    if (stiffening.automaticPatches) patches = automaticStiffeningPatches(mesh, faceCounts);
    for (const std::string& name : stiffening.patches) {
        bool found = false;
        for (Label p = 0; p < static_cast<Label>(mesh.patches.size()); ++p) {
            const Patch& patch = mesh.patches[p];
            const bool inGroup = std::find(patch.inGroups.begin(), patch.inGroups.end(), name) != patch.inGroups.end();
            if (patch.name == name || inGroup) {
                if (std::find(patches.begin(), patches.end(), p) == patches.end()) patches.push_back(p);
                found = true;
            }
        }
        if (!found)
            throw InputError(options.file, stiffening.line,
                             "stiffening: unknown patch " + name + ". Valid patches are: " + patchNameList(mesh));
    }
    return patches;
}

} // namespace

EdgeStiffening::EdgeStiffening(const RigidBodyMotionOptions& options, const PolyMesh& mesh,
                               const std::vector<Vector3>& points0, const PseudoTwoDMesh* twoD,
                               const CellNeighbourGraph& graph, const std::vector<Vector3>& referencePoints,
                               int dimension)
    : EdgeStiffening(options, mesh, dimension,
                     [&mesh, &points0, twoD, &graph, &referencePoints, dimension](std::span<const Label> patches,
                                                                                   double exponent) {
                         NearestSurface surface;
                         if (twoD) {
                             std::vector<Label> planarPatches;
                             for (Label p = 0; p < static_cast<Label>(twoD->planar.patches.size()); ++p)
                                 if (std::find(patches.begin(), patches.end(), twoD->planar.patches[p].polyMeshPatch) !=
                                     patches.end())
                                     planarPatches.push_back(p);
                             surface = patchSurface(twoD->planar, planarPatches);
                         } else {
                             surface = patchSurface(mesh, points0, patches);
                         }
                         return stiffeningFactors(graph, referencePoints, dimension, surface, exponent);
                     })
{
    if (!automatic_ || dimension != 2 || options.weighting != EdgeWeighting::inverseDistanceSquared) return;
    translationSource_ = [&graph, &referencePoints]() {
        // f_ij = |d_ij| / h_min: 1/|d|² weights become 1/|d| (over h_min).
        std::vector<double> factors(graph.neighbours.size());
        double shortest = 0.0;
        for (int i = 0; i < graph.nodeCount(); ++i)
            for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
                Vector3 d = referencePoints[graph.neighbours[e]] - referencePoints[i];
                d.z = 0.0;
                factors[e] = norm(d);
                if (factors[e] > 0.0 && (shortest == 0.0 || factors[e] < shortest)) shortest = factors[e];
            }
        for (double& f : factors) f = f > 0.0 ? f / shortest : 1.0;
        return factors;
    };
}

EdgeStiffening::EdgeStiffening(const RigidBodyMotionOptions& options, const PolyMesh& mesh, int dimension,
                               FactorSource source, std::span<const Label> faceCounts)
    : dimension_(dimension), factorsTowards_(std::move(source))
{
    const StiffeningOptions& stiffening = options.stiffening;
    if (!stiffening.enabled()) return;
    patches_ = stiffenedPatches(options, mesh, faceCounts);
    exponent_ = stiffening.exponent;
    automatic_ = stiffening.automaticPatches;
    split_ = stiffening.split;
    // auto's split in 2D only: on the 10⁶-cell cube turned 30° (3D) it raised the worst
    // non-orthogonality from 18.8° to 42.4° (docs/motionSolver.md, "Default stiffening"). A
    // movingAndFixed written out applies in 3D too.
    if (split_ && dimension_ == 3 && !stiffening.splitWritten) split_.reset();
    // movingAndFixed: which patches move is known at the first solve that moves one.
    if (split_) return;
    whenRigid_ = std::make_shared<const std::vector<double>>(factorsTowards_(patches_, exponent_));
    inEffect_ = whenRigid_;
}

void EdgeStiffening::releaseFactors()
{
    if (split_ || released_) return;
    appliedWhenReleased_ = inEffect_ != nullptr;
    inEffect_.reset();
    whenRigid_.reset();
    released_ = true;
}

void EdgeStiffening::restoreFactors()
{
    if (!released_) return;
    released_ = false;
    if (!appliedWhenReleased_) return;
    whenRigid_ = std::make_shared<const std::vector<double>>(factorsTowards_(patches_, exponent_));
    inEffect_ = whenRigid_;
}

std::vector<double> EdgeStiffening::factorsInEffect() const
{
    if (inEffect_) return *inEffect_;
    if (released_ && appliedWhenReleased_) return factorsTowards_(patches_, exponent_);
    return {};
}

bool EdgeStiffening::followMotion(bool allPatchesRigid, const std::vector<bool>& moved, bool translation)
{
    if (!automatic_) return false;
    if (translation && translationSource_ && !released_) {
        if (!translationComputed_) {
            std::vector<double> factors = translationSource_();
            if (!factors.empty()) translationWeights_ = std::make_shared<const std::vector<double>>(std::move(factors));
            translationComputed_ = true;
        }
        if (inEffect_ == translationWeights_) return false;
        inEffect_ = translationWeights_;
        return true;
    }
    if (released_) {
        // The rule below on the state the factors had when released; applying them again
        // computes them again.
        if (allPatchesRigid == appliedWhenReleased_) return false;
        appliedWhenReleased_ = allPatchesRigid;
        released_ = false;
        if (allPatchesRigid) {
            whenRigid_ = std::make_shared<const std::vector<double>>(factorsTowards_(patches_, exponent_));
            inEffect_ = whenRigid_;
        }
        return true;
    }
    if (!allPatchesRigid) {
        if (!inEffect_) return false;
        inEffect_ = nullptr;
        return true;
    }
    if (split_) {
        std::vector<Label> moving;
        std::vector<Label> fixed;
        for (Label p : patches_) (p < static_cast<Label>(moved.size()) && moved[p] ? moving : fixed).push_back(p);
        // Nothing to tell apart: auto's single distance and exponent.
        if (moving.empty() || fixed.empty()) moving.clear();
        // Computed when first applied (a deforming motion never needs them), again when the
        // moving patches change.
        if (!whenRigid_ || moving != moving_) {
            std::vector<double> factors;
            if (moving.empty()) {
                factors = factorsTowards_(patches_, exponent_);
            } else {
                factors = factorsTowards_(moving, split_->moving);
                const std::vector<double> towardsFixed = factorsTowards_(fixed, split_->fixed);
                for (std::size_t e = 0; e < factors.size(); ++e) factors[e] *= towardsFixed[e];
            }
            whenRigid_ = std::make_shared<const std::vector<double>>(std::move(factors));
            moving_ = std::move(moving);
            inEffect_ = whenRigid_;
            return true;
        }
    }
    if (inEffect_ && inEffect_ == whenRigid_) return false;
    if (!whenRigid_)  // released while not applied, then taken off the release by a deforming step
        whenRigid_ = std::make_shared<const std::vector<double>>(factorsTowards_(patches_, exponent_));
    inEffect_ = whenRigid_;
    return true;
}

std::string EdgeStiffening::describeAutomatic(const RigidBodyMotionOptions& options, const PolyMesh& mesh) const
{
    if (!options.stiffening.automaticPatches || patches_.empty()) return {};
    std::ostringstream text;
    std::ostringstream names;
    for (std::size_t k = 0; k < patches_.size(); ++k) names << (k ? " " : "") << mesh.patches[patches_[k]].name;
    // split_ is set where the split applies (auto's in 2D only, a written movingAndFixed everywhere).
    if (split_)
        text << " = power " << split_->moving << " inverseDistance (the moving ones of " << names.str()
             << ") × power " << split_->fixed << " inverseDistance (the others), or power " << exponent_
             << " inverseDistance (all) where none or all move,";
    else
        text << " = power " << exponent_ << " inverseDistance (" << names.str() << ")";
    text << " while every prescribed patch moves rigidly";
    return text.str();
}

} // namespace rbm::motion
