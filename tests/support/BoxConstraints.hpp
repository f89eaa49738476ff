#pragma once
// The node classes of the distributed tests' box (DecomposedBox): bottom (zMin) and top (zMax)
// prescribed, the x-min side sliding on planes with the given normal, every other node free.

#include "DecomposedBox.hpp"
#include "MeshPart.hpp"
#include "RbmProblem.hpp"

#include <vector>

namespace rbm::test {

inline std::vector<motion::NodeConstraint> boxConstraints(const DecomposedBox& box, const Vector3& slidingNormal)
{
    using motion::NodeKind;
    std::vector<motion::NodeConstraint> constraints(box.mesh.points.size());
    for (Label p : patchMeshPoints(box.mesh, box.mesh.findPatch("xMin")))
        constraints[p] = {NodeKind::sliding, slidingNormal};
    for (const char* name : {"zMin", "zMax"})
        for (Label p : patchMeshPoints(box.mesh, box.mesh.findPatch(name))) constraints[p] = {NodeKind::prescribed};
    return constraints;
}

// The whole box's constraints of one rank's part, node by node.
inline std::vector<motion::NodeConstraint> partConstraints(const motion::MeshPart& part,
                                                           const std::vector<motion::NodeConstraint>& wholeConstraints)
{
    std::vector<motion::NodeConstraint> constraints;
    for (Label g : part.nodeGlobalIds()) constraints.push_back(wholeConstraints[g]);
    return constraints;
}

} // namespace rbm::test
