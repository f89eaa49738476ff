#include "CyclicCoupling.hpp"

#include "InputError.hpp"

#include <cmath>
#include <map>

namespace rbm::motion {

namespace {

// q in the 2D frame (rows e1, e2, normal): q_local(i, j) = f_i · (q f_j).
rbm::Matrix3 inFrame(const rbm::Matrix3& q, const PlaneFrame& frame)
{
    const Vector3 f[3] = {frame.e1, frame.e2, frame.normal};
    rbm::Matrix3 local;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) local.m[i][j] = dot(f[i], q * f[j]);
    return local;
}

// The unit axis of a rotation matrix (zero for the identity).
Vector3 rotationAxis(const rbm::Matrix3& r)
{
    const Vector3 axis{r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1)};
    const double length = norm(axis);
    return length > 1e-12 ? axis / length : Vector3{};
}

std::string patchPairName(const PolyMesh& mesh, Label a, Label b)
{
    return "cyclic patches '" + mesh.patches[a].name + "' and '" + mesh.patches[b].name + "'";
}

} // namespace

CyclicCoupling coupleCyclicNodes(const PolyMesh& mesh, std::span<const CyclicPatchPairing> pairings,
                                 const PseudoTwoDMesh* twoD, const std::string& file)
{
    CyclicCoupling coupling;
    std::map<int, std::size_t> pairOfNode;  // node → its entry in coupling.pairs
    for (const CyclicPatchPairing& pairing : pairings) {
        const std::string name = patchPairName(mesh, pairing.patchA, pairing.patchB);
        rbm::Matrix3 q = pairing.rotation;
        if (twoD) {
            q = inFrame(q, twoD->frame);
            if (std::abs(q(2, 2) - 1.0) > 1e-9)
                throw InputError(file, 0,
                                 name + ": their rotation axis is not normal to the plane of this pseudo-2D mesh, which "
                                        "rbm solves in that plane");
            q.m[0][2] = q.m[1][2] = q.m[2][0] = q.m[2][1] = 0.0;
            q.m[2][2] = 1.0;
        }
        for (const auto& [pointA, pointB] : pairing.points) {
            const int a = twoD ? twoD->nodeOfPoint[pointA] : pointA;
            const int b = twoD ? twoD->nodeOfPoint[pointB] : pointB;
            if (a < 0 || b < 0) continue;  // a point no cell uses
            if (twoD && (twoD->frontPointOfNode[a] == pointA) != (twoD->frontPointOfNode[b] == pointB))
                throw InputError(file, 0,
                                 name + ": their transform carries a point of one plane of this pseudo-2D mesh onto "
                                        "the other plane");
            if (a == b) {
                const Vector3 axis = rotationAxis(q);
                if (!(axis == Vector3{})) coupling.axisNodes.push_back({a, axis, pairing.patchA});
                continue;
            }
            const auto atA = pairOfNode.find(a);
            if (atA != pairOfNode.end() && coupling.pairs[atA->second].a == a && coupling.pairs[atA->second].b == b)
                continue;  // the other plane's twin of a pair met already (2D)
            for (const int node : {a, b})
                if (const auto other = pairOfNode.find(node); other != pairOfNode.end()) {
                    const CyclicCoupling::NodePair& met = coupling.pairs[other->second];
                    throw InputError(file, 0,
                                     name + ": point " + std::to_string(node == a ? pointA : pointB) +
                                         " also has a partner through " + patchPairName(mesh, met.patchA, met.patchB) +
                                         "; rbm ties each point to one partner only");
                }
            pairOfNode[a] = pairOfNode[b] = coupling.pairs.size();
            coupling.pairs.push_back({a, b, q, pairing.patchA, pairing.patchB});
        }
    }
    return coupling;
}

std::vector<double> interfaceEdgeFactors(const CyclicCoupling& coupling, const CellNeighbourGraph& graph)
{
    if (coupling.pairs.empty()) return {};
    std::vector<Label> side(static_cast<std::size_t>(graph.nodeCount()), -1);
    for (const CyclicCoupling::NodePair& pair : coupling.pairs) {
        side[pair.a] = pair.patchA;
        side[pair.b] = pair.patchB;
    }
    std::vector<double> factors(graph.neighbours.size(), 1.0);
    for (int i = 0; i < graph.nodeCount(); ++i)
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
            if (side[i] >= 0 && side[i] == side[graph.neighbours[e]]) factors[e] = 0.5;
    return factors;
}

namespace {

// The node on a rotation axis: it moves along the axis (3D), or stays (2D).
void constrainToAxis(const CyclicCoupling::AxisNode& node, NodeClasses& classes, bool planar)
{
    NodeConstraint& constraint = classes.constraints[node.node];
    int& prescriber = classes.prescribingPatch[node.node];
    if (constraint.kind == NodeKind::prescribed) return;
    if (planar) {
        constraint = {NodeKind::prescribed, {}};
        prescriber = heldNode;
        return;
    }
    // Two planes through the axis: their intersection line is the axis.
    const Vector3 helper = std::abs(node.axis.x) < 0.9 ? Vector3{1.0, 0.0, 0.0} : Vector3{0.0, 1.0, 0.0};
    const Vector3 first = cross(node.axis, helper);
    for (const Vector3& normal : {first, cross(node.axis, first)})
        addSlidingNormal(false, constraint, prescriber, normal, false);
}

// Both nodes unknown: a takes b's planes mapped back by qᵀ, b becomes the image of a.
void shareSlidingPlanes(const CyclicCoupling::NodePair& pair, NodeClasses& classes, bool planar)
{
    NodeConstraint merged = classes.constraints[pair.a];
    int prescriber = classes.prescribingPatch[pair.a];
    const NodeConstraint& other = classes.constraints[pair.b];
    if (other.kind == NodeKind::sliding)
        for (const Vector3& normal : {other.normal, other.secondNormal})
            if (!(normal == Vector3{})) addSlidingNormal(planar, merged, prescriber, pair.q.transposed() * normal, other.mirror);
    NodeConstraint image = merged;
    image.normal = pair.q * merged.normal;
    image.secondNormal = pair.q * merged.secondNormal;
    classes.constraints[pair.a] = merged;
    classes.constraints[pair.b] = image;
    classes.prescribingPatch[pair.a] = classes.prescribingPatch[pair.b] = prescriber;
}

} // namespace

std::vector<CoupledPair> unifyCoupledClasses(const CyclicCoupling& coupling, NodeClasses& classes, bool planar,
                                             const PolyMesh& mesh, const std::string& file)
{
    for (const CyclicCoupling::AxisNode& node : coupling.axisNodes) constrainToAxis(node, classes, planar);
    std::vector<CoupledPair> unknownPairs;
    for (const CyclicCoupling::NodePair& pair : coupling.pairs) {
        const bool prescribedA = classes.constraints[pair.a].kind == NodeKind::prescribed;
        const bool prescribedB = classes.constraints[pair.b].kind == NodeKind::prescribed;
        if (prescribedA && prescribedB) continue;  // the conditions' values stand
        if (prescribedA || prescribedB) {
            const int fixedNode = prescribedA ? pair.a : pair.b;
            const int freeNode = prescribedA ? pair.b : pair.a;
            const int prescriber = classes.prescribingPatch[fixedNode];
            if (prescriber == heldNode) {
                classes.constraints[freeNode] = {NodeKind::prescribed, {}};
                classes.prescribingPatch[freeNode] = heldNode;
                continue;
            }
            throw InputError(file, 0,
                             patchPairName(mesh, pair.patchA, pair.patchB) + ": node " + std::to_string(fixedNode) +
                                 " is prescribed by patch '" + mesh.patches[prescriber].name + "' but its partner node " +
                                 std::to_string(freeNode) +
                                 " on the other side is not: the interface would open. A prescribed patch that "
                                 "touches one side of a cyclic interface must touch the other side alike");
        }
        shareSlidingPlanes(pair, classes, planar);
        if (classes.constraints[pair.a].kind == NodeKind::prescribed) continue;  // held by the planes
        const rbm::Matrix3& q = pair.q;
        unknownPairs.push_back({pair.a, pair.b, {Vector3{q(0, 0), q(0, 1), q(0, 2)}, Vector3{q(1, 0), q(1, 1), q(1, 2)},
                                                 Vector3{q(2, 0), q(2, 1), q(2, 2)}}});
    }
    return unknownPairs;
}

} // namespace rbm::motion
