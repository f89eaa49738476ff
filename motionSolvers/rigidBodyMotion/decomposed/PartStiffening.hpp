#pragma once
// The stiffening factors (Stiffening.hpp) of one rank's part of a decomposed mesh, equal to the
// serial ones on the same edges: the distance of each edge's midpoint to the patches is
// measured to the whole surface, gathered from every rank's own patch faces (a wall surface is
// small against the volume: about 17 MB on every rank for the 10⁶-cell cube's six sides), and
// h_min is the shortest edge over all ranks. The exact distances do not depend on the order
// of the gathered faces.

#include "CellNeighbourGraph.hpp"
#include "EdgeStiffening.hpp"
#include "MeshPart.hpp"
#include "PolyMesh.hpp"

namespace rbm::motion {

// The factors per directed edge of `graph` (the part's, on part.nodePoints()) towards the
// given patches of `localMesh` (the rank's own mesh; every rank's patches in the same order).
// The source is collective: every rank must call it with the same patches and exponent. The
// arguments must outlive it.
EdgeStiffening::FactorSource partStiffeningFactors(const PolyMesh& localMesh, const MeshPart& part,
                                                   const CellNeighbourGraph& graph);

} // namespace rbm::motion
