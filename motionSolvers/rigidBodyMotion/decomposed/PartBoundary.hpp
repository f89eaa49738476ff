#pragma once
// The boundary of one rank's part of a decomposed mesh, as the distributed solve sees it: the
// BoundaryDescription of the MeshPart's nodes (owned, then ghosts), the same on every rank that
// holds a node, built from each rank's own patch faces.
//
// A rank sees only the patch faces of its own cells. A point on the cut between two parts may
// lie on a wall whose faces around it are all on the other rank, and a ghost or halo node may
// be on no face this rank has. So every rank marks the patches of its own points and sums the
// unit normals of its own faces on each sliding (or unconstrained) patch at their points; the
// owners add what all holders marked (NodeExchange::addGhostsToOwners) and send the totals back
// to every copy (updateGhosts). A node is then on a patch when any rank saw it there, and its
// sliding normal is the normalised sum of the unit normals of all the patch's faces around it:
// OpenFOAM's point normal (PrimitivePatch::pointNormals), as the serial path takes it.
//
// The patches are the local mesh's, which decomposePar gives every processor in the same
// order (its own `processor` patches last, described as ignored). An unconstrained patch
// (zeroGradient, ...) that does not float becomes a sliding one with those normals
// (UnconstrainedPatches.hpp's rule); a floating one stays free.

#include "BoundaryDescription.hpp"
#include "MeshPart.hpp"
#include "NodeExchange.hpp"
#include "PolyMesh.hpp"
#include "UnconstrainedPatches.hpp"

#include <vector>

namespace rbm::motion {

// The patches every rank has: decomposePar puts each processor's own `processor` patches, which
// differ between ranks, after them. How many.
std::size_t sharedPatchCount(const PolyMesh& localMesh);

// `local`: the description of the rank's own mesh (one entry per patch of `localMesh`, whose
// points are the LocalCells' the part was built from). Collective.
BoundaryDescription partBoundaryDescription(const PolyMesh& localMesh, const BoundaryDescription& local,
                                            const MeshPart& part, const NodeExchange& exchange,
                                            const UnconstrainedPatches& unconstrained);

// Per node of the part: the value `localValues` (one per point of the rank's mesh) holds where
// a rank that has the node on patch prescribingPatch[node] evaluated it, the same on every
// copy; zero where prescribingPatch[node] < 0. Where several ranks evaluated it, their mean
// (they evaluate the same condition at the same point). Collective.
std::vector<Vector3> partPrescribedValues(const BoundaryDescription& local, const MeshPart& part,
                                          const NodeExchange& exchange, const std::vector<int>& prescribingPatch,
                                          const std::vector<Vector3>& localValues);

} // namespace rbm::motion
