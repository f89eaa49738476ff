#include "EdgeStiffening.hpp"

#include "InputError.hpp"
#include "Stiffening.hpp"

#include <algorithm>

namespace rbm::motion {

namespace {

// The patches of the stiffening distance: the automatic choice and/or the names and groups
// the user listed.
std::vector<Label> stiffenedPatches(const RigidBodyMotionOptions& options, const PolyMesh& mesh)
{
    const StiffeningOptions& stiffening = options.stiffening;
    std::vector<Label> patches;
    if (stiffening.automaticPatches) patches = automaticStiffeningPatches(mesh);
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
{
    const StiffeningOptions& stiffening = options.stiffening;
    if (!stiffening.enabled()) return;
    std::vector<Label> patches = stiffenedPatches(options, mesh);
    NearestSurface surface;
    if (twoD) {
        std::vector<Label> planarPatches;
        for (Label p = 0; p < static_cast<Label>(twoD->planar.patches.size()); ++p)
            if (std::find(patches.begin(), patches.end(), twoD->planar.patches[p].polyMeshPatch) != patches.end())
                planarPatches.push_back(p);
        surface = patchSurface(twoD->planar, planarPatches);
    } else {
        surface = patchSurface(mesh, points0, patches);
    }
    inEffect_ = std::make_shared<const std::vector<double>>(
        stiffeningFactors(graph, referencePoints, dimension, surface, stiffening.exponent));
    patches_ = std::move(patches);
    if (stiffening.automaticPatches) automatic_ = inEffect_;
}

bool EdgeStiffening::followMotion(bool allPatchesRigid)
{
    if (!automatic_ || allPatchesRigid == (inEffect_ != nullptr)) return false;
    inEffect_ = allPatchesRigid ? automatic_ : nullptr;
    return true;
}

} // namespace rbm::motion
