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

} // namespace rbm::motion
