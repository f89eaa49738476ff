#include "RbmUntangling.hpp"

#include <algorithm>

namespace rbm::motion {

std::vector<UntanglePointConstraint> untangleConstraints(const RbmProblem& problem)
{
    std::vector<UntanglePointConstraint> constraints(static_cast<std::size_t>(problem.nodeCount()));
    for (int node = 0; node < problem.nodeCount(); ++node) {
        UntanglePointConstraint& constraint = constraints[node];
        switch (problem.kind(node)) {
        case NodeKind::prescribed: constraint.fixed = true; break;
        case NodeKind::sliding:
            constraint.normal = problem.slidingNormal(node);
            constraint.secondNormal = problem.secondSlidingNormal(node);
            break;
        case NodeKind::free: break;
        }
    }
    return constraints;
}

namespace {

std::string joinNames(std::vector<std::string> names)
{
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "patch " : ", ") + name;
    return text;
}

} // namespace

std::string cellPatchNames(const PolyMesh& mesh, Label cell)
{
    std::vector<std::string> names;
    for (const Patch& patch : mesh.patches)
        for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f)
            if (mesh.owner[f] == cell) names.push_back(patch.name);
    return joinNames(std::move(names));
}

std::string cellPatchNames(const PlanarMesh& mesh, Label cell)
{
    std::vector<std::string> names;
    for (const PlanarPatch& patch : mesh.patches)
        for (Label e = patch.startEdge; e < patch.startEdge + patch.edgeCount; ++e)
            if (mesh.edgeOwner[e] == cell) names.push_back(patch.name);
    return joinNames(std::move(names));
}

RbmUntangler::Outcome RbmUntangler::untangle(const RbmProblem& problem, const std::vector<Vector3>& referencePoints,
                                             std::vector<Vector3>& displacement, InvertedCellCounter& counter)
{
    if (!simplices_)
        simplices_ = std::make_unique<SimplexDecomposition>(twoD_ ? decomposeCells(twoD_->planar) : decomposeCells(mesh_));
    const int n = problem.nodeCount();
    std::vector<Vector3> moved(n);
    for (int node = 0; node < n; ++node) moved[node] = referencePoints[node] + displacement[node];
    std::vector<Vector3> candidate(n);
    std::vector<Label> cells;
    const InvertedCellTest test = [&](std::span<const Vector3> at) {
        for (int node = 0; node < n; ++node) candidate[node] = at[node] - referencePoints[node];
        counter.count(candidate, nullptr, &cells);
        return cells;
    };
    const UntangleResult result = rbm::untangle(*simplices_, referencePoints, untangleConstraints(problem), moved, test);
    // Only the free and sliding nodes moved: prescribed displacements stay bit-for-bit.
    for (int node = 0; node < n; ++node)
        if (problem.isUnknown(node)) displacement[node] = moved[node] - referencePoints[node];
    Outcome outcome;
    outcome.untangledCellCount = result.initialInverted - static_cast<Label>(result.remainingCells.size());
    if (result.untangled()) {
        outcome.reason = "; untangled " + std::to_string(result.initialInverted) + " inverted cell" +
                         (result.initialInverted == 1 ? "" : "s");
        return outcome;
    }
    std::string where = result.describe(moved, *simplices_);
    if (!result.remainingCells.empty()) {
        const Label first = result.remainingCells.front();
        const std::string patches = twoD_ ? cellPatchNames(twoD_->planar, first) : cellPatchNames(mesh_, first);
        if (!patches.empty()) where += " (cell " + std::to_string(first) + ": " + patches + ")";
    }
    outcome.reason = "; untangling: " + where;
    return outcome;
}

} // namespace rbm::motion
