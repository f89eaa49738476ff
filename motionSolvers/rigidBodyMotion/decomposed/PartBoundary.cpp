#include "PartBoundary.hpp"

#include "PatchNormals.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace rbm::motion {

namespace {

constexpr double vSmall = 1e-300;  // OpenFOAM's VSMALL, as PatchNormals normalises

// Patches whose normals the nodes need: sliding ones and the unconstrained ones that slide.
bool needsNormals(const BoundaryPatchDescription& patch, Label index, const UnconstrainedPatches& unconstrained)
{
    return patch.nodeClass == BoundaryNodeClass::sliding ||
           (patch.nodeClass == BoundaryNodeClass::free && !unconstrained.floats(index));
}

} // namespace

std::size_t sharedPatchCount(const PolyMesh& localMesh)
{
    const auto first = std::find_if(localMesh.patches.begin(), localMesh.patches.end(),
                                    [](const Patch& patch) { return patch.type == "processor"; });
    return static_cast<std::size_t>(first - localMesh.patches.begin());
}

BoundaryDescription partBoundaryDescription(const PolyMesh& localMesh, const BoundaryDescription& local,
                                            const MeshPart& part, const NodeExchange& exchange,
                                            const UnconstrainedPatches& unconstrained)
{
    // Exchanged in blocks of one entry per shared patch: the same layout on every rank.
    const auto patchCount = static_cast<int>(sharedPatchCount(localMesh));
    const std::size_t nodeCount = static_cast<std::size_t>(part.nodeCount());
    const std::vector<Label>& nodeOf = part.pointNodes();

    // Which patches each node is on, as counts of the ranks that saw it there.
    std::vector<double> onPatch(nodeCount * static_cast<std::size_t>(patchCount), 0.0);
    for (int p = 0; p < patchCount; ++p) {
        if (local[p].nodeClass == BoundaryNodeClass::ignored) continue;
        for (Label point : local[p].meshPoints) onPatch[nodeOf[point] * patchCount + p] = 1.0;
    }
    exchange.addGhostsToOwners(onPatch, patchCount);
    exchange.updateGhosts(onPatch, patchCount);

    // The sums of the unit normals of each sliding patch's faces around its nodes.
    std::vector<int> normalSlot(patchCount, -1);
    int slots = 0;
    for (int p = 0; p < patchCount; ++p)
        if (needsNormals(local[p], p, unconstrained)) normalSlot[p] = slots++;
    std::vector<double> normalSums(nodeCount * 3 * static_cast<std::size_t>(slots), 0.0);
    for (int p = 0; p < patchCount; ++p) {
        if (normalSlot[p] < 0) continue;
        const Patch& patch = localMesh.patches[p];
        for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
            const Vector3 n = faceUnitNormal(localMesh.face(f), localMesh.points);
            for (Label point : localMesh.face(f)) {
                double* sum = &normalSums[(nodeOf[point] * slots + normalSlot[p]) * 3];
                sum[0] += n.x;
                sum[1] += n.y;
                sum[2] += n.z;
            }
        }
    }
    if (slots > 0) {
        exchange.addGhostsToOwners(normalSums, 3 * slots);
        exchange.updateGhosts(normalSums, 3 * slots);
    }

    BoundaryDescription merged(local.size());
    for (std::size_t p = 0; p < local.size(); ++p) {
        BoundaryPatchDescription& patch = merged[p];
        patch.nodeClass = local[p].nodeClass;
        patch.mirror = local[p].mirror;
        if (patch.nodeClass == BoundaryNodeClass::ignored || static_cast<int>(p) >= patchCount) continue;
        if (normalSlot[p] >= 0) patch.nodeClass = BoundaryNodeClass::sliding;
        for (std::size_t node = 0; node < nodeCount; ++node) {
            if (onPatch[node * patchCount + p] == 0.0) continue;
            patch.meshPoints.push_back(static_cast<Label>(node));
            if (normalSlot[p] < 0) continue;
            const double* sum = &normalSums[(node * slots + normalSlot[p]) * 3];
            const Vector3 n{sum[0], sum[1], sum[2]};
            patch.slidingNormals.push_back(n / (norm(n) + vSmall));
        }
    }
    return merged;
}

std::vector<Vector3> partPrescribedValues(const BoundaryDescription& local, const MeshPart& part,
                                          const NodeExchange& exchange, const std::vector<int>& prescribingPatch,
                                          const std::vector<Vector3>& localValues)
{
    const std::size_t nodeCount = static_cast<std::size_t>(part.nodeCount());
    const std::vector<Label>& nodeOf = part.pointNodes();
    // Per node: the values evaluated and how many ranks evaluated them.
    std::vector<double> sums(4 * nodeCount, 0.0);
    for (std::size_t p = 0; p < local.size(); ++p) {
        if (local[p].nodeClass != BoundaryNodeClass::prescribed) continue;
        for (Label point : local[p].meshPoints) {
            const Label node = nodeOf[point];
            if (prescribingPatch[node] != static_cast<int>(p)) continue;
            double* sum = &sums[4 * node];
            if (sum[3] != 0.0) continue;  // a point twice in one patch's list is one evaluation
            const Vector3& u = localValues[point];
            sum[0] = u.x;
            sum[1] = u.y;
            sum[2] = u.z;
            sum[3] = 1.0;
        }
    }
    exchange.addGhostsToOwners(sums, 4);
    exchange.updateGhosts(sums, 4);
    std::vector<Vector3> values(nodeCount);
    for (std::size_t node = 0; node < nodeCount; ++node) {
        const double* sum = &sums[4 * node];
        if (prescribingPatch[node] >= 0 && sum[3] > 0.0) values[node] = Vector3{sum[0], sum[1], sum[2]} / sum[3];
    }
    return values;
}

} // namespace rbm::motion
