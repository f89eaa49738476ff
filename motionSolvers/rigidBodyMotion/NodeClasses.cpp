#include "NodeClasses.hpp"

#include <cmath>

namespace rbm::motion {

void addSlidingNormal(bool planar, NodeConstraint& constraint, int& prescriber, Vector3 normal, bool mirror)
{
    const double length = norm(normal);
    if (!(length > 1e-8)) return;  // a plane parallel to the 2D plane: no in-plane constraint
    normal /= length;
    if (constraint.kind == NodeKind::free) {
        constraint = {NodeKind::sliding, normal, mirror};
    } else if (norm(cross(constraint.normal, normal)) <= 1e-6) {
        constraint.mirror = constraint.mirror || mirror;  // a mirror on the same plane
    } else if (!planar && constraint.secondNormal == Vector3{}) {
        // Two different planes (3D): the node slides along their intersection line.
        constraint.secondNormal = normal;
    } else if (!planar && std::abs(dot(normal, cross(constraint.normal, constraint.secondNormal))) <=
                              1e-6 * norm(cross(constraint.normal, constraint.secondNormal))) {
        // A further plane through the same line (its normal ⟂ the line): still that line.
    } else {
        // Two lines in 2D meet in a point, so do three planes in 3D: the node stays.
        constraint = {NodeKind::prescribed, {}};
        prescriber = heldNode;
    }
}

namespace {

// Adds a sliding plane (a line in 2D) of 3D normal `normal` to a node's constraint.
void addSlidingPlane(const PseudoTwoDMesh* twoD, NodeConstraint& constraint, int& prescriber, Vector3 normal,
                     bool mirror)
{
    if (twoD) {
        normal = twoD->frame.toLocal(normal);
        normal.z = 0.0;
    }
    addSlidingNormal(twoD != nullptr, constraint, prescriber, normal, mirror);
}

// Wedge meshes: the points on the axis slide along it.
void constrainWedgeAxis(const PseudoTwoDMesh& wedge, std::vector<NodeConstraint>& classes, std::vector<int>& prescriber)
{
    // A point where the two wedge planes meet lies on the axis of the axisymmetric domain:
    // OpenFOAM's wedge condition keeps it there (a point off the axis would open a hole along
    // it). In the front plane the axis is a line; the point slides along it, a mirror line of
    // the domain, unless a patch prescribes it.
    const Vector3 acrossAxis = cross(wedge.frame.normal, wedge.wedgeAxis);
    for (int node = 0; node < static_cast<int>(classes.size()); ++node) {
        if (wedge.backPointOfNode[node] != wedge.frontPointOfNode[node]) continue;
        if (classes[node].kind == NodeKind::prescribed) continue;
        addSlidingPlane(&wedge, classes[node], prescriber[node], acrossAxis, true);
    }
}

} // namespace

NodeClasses classifyNodes(const BoundaryDescription& boundary, const PseudoTwoDMesh* twoD,
                          const CellNeighbourGraph& graph, UnconstrainedPatches& unconstrained)
{
    const int n = static_cast<int>(graph.offsets.size()) - 1;
    NodeClasses result;
    std::vector<NodeConstraint>& classes = result.constraints;
    std::vector<int>& prescriber = result.prescribingPatch;
    classes.assign(n, NodeConstraint{});
    prescriber.assign(n, -1);
    const BoundaryDescription& conditions = boundary;
    for (std::size_t patch = 0; patch < conditions.size(); ++patch) {
        const BoundaryPatchDescription& condition = conditions[patch];
        const BoundaryNodeClass nodeClass = condition.nodeClass;
        // Cyclic points are classified with their partners (CyclicCoupling.hpp).
        if (nodeClass == BoundaryNodeClass::ignored || nodeClass == BoundaryNodeClass::coupled) continue;
        // A patch its condition leaves unconstrained keeps its surface unless it floats
        // (UnconstrainedPatches.hpp).
        if (nodeClass == BoundaryNodeClass::free && unconstrained.floats(static_cast<Label>(patch))) continue;
        const std::vector<Label>& points = condition.meshPoints;
        const std::vector<Vector3>& slidingNormals =
            nodeClass == BoundaryNodeClass::free
                ? unconstrained.slidingNormals(static_cast<Label>(patch), points)
                : condition.slidingNormals;
        for (std::size_t k = 0; k < points.size(); ++k) {
            const int node = twoD ? twoD->nodeOfPoint[points[k]] : points[k];
            if (node < 0) continue;
            NodeConstraint& constraint = classes[node];
            if (nodeClass == BoundaryNodeClass::prescribed) {
                // Prescribed beats sliding beats free; between prescribing patches the first wins.
                if (constraint.kind != NodeKind::prescribed || prescriber[node] == heldNode) {
                    constraint = {NodeKind::prescribed, {}};
                    prescriber[node] = static_cast<int>(patch);
                }
                continue;
            }
            if (constraint.kind == NodeKind::prescribed) continue;
            addSlidingPlane(twoD, constraint, prescriber[node], slidingNormals[k], condition.mirror);
        }
    }
    if (twoD && twoD->kind == PseudoTwoDKind::Wedge) constrainWedgeAxis(*twoD, classes, prescriber);
    // Nodes without neighbours (points no cell uses) cannot move.
    for (int node = 0; node < n; ++node) {
        if (graph.offsets[node + 1] == graph.offsets[node] && classes[node].kind != NodeKind::prescribed) {
            classes[node] = {NodeKind::prescribed, {}};
            prescriber[node] = heldNode;
        }
    }
    return result;
}

PrescribedGroups groupPrescribedNodes(const std::vector<int>& prescribingPatch, int patchCount)
{
    const int n = static_cast<int>(prescribingPatch.size());
    PrescribedGroups groups;
    groups.offsets.assign(patchCount + 1, 0);
    for (int node = 0; node < n; ++node)
        if (prescribingPatch[node] >= 0) ++groups.offsets[prescribingPatch[node] + 1];
    for (int p = 0; p < patchCount; ++p) groups.offsets[p + 1] += groups.offsets[p];
    groups.nodes.assign(groups.offsets.back(), 0);
    std::vector<int> next(groups.offsets.begin(), groups.offsets.end() - 1);
    for (int node = 0; node < n; ++node)
        if (prescribingPatch[node] >= 0) groups.nodes[next[prescribingPatch[node]]++] = node;
    return groups;
}

} // namespace rbm::motion
