#pragma once
// Plain `cyclic` patches in the RBM problem (docs/motionSolver.md, "Cyclic patches"): the point
// pairs of each periodic interface (src/CyclicPairs.hpp) as pairs of the problem's nodes, tied
// by u_b = q u_a (RbmProblem's coupled pairs), with node classes that agree across the pair.
//
//   - 2D (a pseudo-3D mesh solved on its front plane): the pairs of the front plane's points,
//     q in the plane's frame; a transform that turns the plane or carries the front plane onto
//     the back one is refused.
//   - Both nodes of a pair unknown: each gets the sliding planes of both, the other's mapped
//     by q (a slip wall on one side of the interface is its image on the other), so that the
//     pair and plane projections commute (RbmProblem::setCoupledPairs). Both prescribed: the
//     conditions' values stand. One prescribed by a patch, the other not: refused, naming the
//     patches (the interface would open); one held by the classification: both held.
//   - A node that is its own partner (on the axis of a rotational cyclic) moves along the axis
//     (3D; held where it also slides on a wall), or stays (2D: the axis is normal to the plane).

#include "CyclicPairs.hpp"
#include "Rotation.hpp"
#include "NodeClasses.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RbmProblem.hpp"

#include <span>
#include <string>
#include <vector>

namespace rbm::motion {

struct CyclicCoupling {
    struct NodePair {
        int a = -1;  // node of patch A's point
        int b = -1;  // node of its partner on patch B
        rbm::Matrix3 q = rbm::Matrix3::identity();  // u_b = q u_a, in the problem's frame
        Label patchA = -1;
        Label patchB = -1;
    };
    std::vector<NodePair> pairs;
    struct AxisNode {
        int node = -1;
        Vector3 axis{};  // unit, in the problem's frame
        Label patch = -1;
    };
    std::vector<AxisNode> axisNodes;

    bool empty() const { return pairs.empty() && axisNodes.empty(); }
};

// The node pairs of `pairings` (points of `mesh`) in the problem's numbering: mesh points in 3D,
// the front plane's nodes of `twoD` in 2D. Throws rbm::InputError naming `file` and the patches
// for a transform the 2D solve cannot take, or a point with partners on two interfaces.
CyclicCoupling coupleCyclicNodes(const PolyMesh& mesh, std::span<const CyclicPatchPairing> pairings,
                                 const PseudoTwoDMesh* twoD, const std::string& file);

// Edge weight factors (RbmProblem::setEdgeWeightFactors, one per directed graph edge): 1/2 on
// every edge between two points of the same cyclic side, 1 elsewhere; empty without pairs. Such
// an edge lies in the interface, and its image on the other side is the same edge of the whole
// periodic mesh: halved, the two count once, as in that mesh.
std::vector<double> interfaceEdgeFactors(const CyclicCoupling& coupling, const CellNeighbourGraph& graph);

// Makes the classes of every pair agree (the header comment) and returns the pairs whose nodes
// are both unknown, for RbmProblem::setCoupledPairs. `planar`: a 2D problem. Throws
// rbm::InputError naming `file` and the patches where one node of a pair is prescribed by a
// patch and the other is not.
std::vector<CoupledPair> unifyCoupledClasses(const CyclicCoupling& coupling, NodeClasses& classes, bool planar,
                                             const PolyMesh& mesh, const std::string& file);

} // namespace rbm::motion
