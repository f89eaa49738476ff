#pragma once
// The class of every node of the RBM problem (prescribed, sliding on a plane or a line, free),
// derived from the boundary description, in one place:
//
//   - a point on several patches: prescribed beats sliding beats free; between prescribing
//     patches the first wins (its points move with it as a group);
//   - a patch whose condition leaves its points unconstrained (zeroGradient, ...) slides on its
//     own surface unless it floats (UnconstrainedPatches.hpp);
//   - a node on two sliding planes slides on their intersection line (3D); on two lines in 2D
//     or three planes in 3D, it is held where it is;
//   - on a wedge (axisymmetric) mesh, the points on the axis slide along it;
//   - a node without neighbours (a point no cell uses) is held;
//   - the points of cyclic patches are left free here: CyclicCoupling.hpp classifies them with
//     their partners.
// In 2D the normals are those of the front plane's frame, their out-of-plane part removed.

#include "BoundaryDescription.hpp"
#include "CellNeighbourGraph.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RbmProblem.hpp"
#include "UnconstrainedPatches.hpp"

#include <vector>

namespace rbm::motion {

// prescribingPatch of a node the classification itself holds in place (conflicting slides,
// isolated nodes): prescribed with zero displacement.
inline constexpr int heldNode = -2;

struct NodeClasses {
    std::vector<NodeConstraint> constraints;  // per node of the problem
    std::vector<int> prescribingPatch;        // per node: the patch that prescribes it, heldNode, or -1
};

// Adds a sliding plane of `normal` (in the problem's frame; `planar`: a 2D problem, where the
// plane is a line) to a node's constraint: a free node slides on it, a second plane makes it
// slide on their intersection line (3D), a further one (or a second line in 2D) holds it
// (prescriber = heldNode). A prescribed node stays prescribed.
void addSlidingNormal(bool planar, NodeConstraint& constraint, int& prescriber, Vector3 normal, bool mirror);

// `twoD`: the pseudo-2D mesh the problem is solved on, or nullptr in 3D (nodes are mesh points).
NodeClasses classifyNodes(const BoundaryDescription& boundary, const PseudoTwoDMesh* twoD,
                          const CellNeighbourGraph& graph, UnconstrainedPatches& unconstrained);

// The prescribed nodes grouped by the patch that prescribes them, in node order within a
// group (CSR: group g is nodes[offsets[g] .. offsets[g+1]) ); held nodes belong to none. A
// group moves as one body along a sub-step path (BoundaryPath.hpp).
struct PrescribedGroups {
    std::vector<int> offsets{0};
    std::vector<int> nodes;
};
PrescribedGroups groupPrescribedNodes(const std::vector<int>& prescribingPatch, int patchCount);

} // namespace rbm::motion
