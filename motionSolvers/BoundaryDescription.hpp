#pragma once
// What a motion solver needs to know about the boundary of its mesh, whoever evaluates the
// boundary conditions: per mesh patch, the class of its points and, for sliding patches, the
// plane each point slides on. The prescribed VALUES are not part of it: they are the
// solver's pointDisplacement() at the prescribed points, written by the front door before
// every solve (rbmMoveMesh from 0/pointDisplacement's conditions, boundaryMotion/; the
// OpenFOAM plugin from OpenFOAM's own evaluation of the pointDisplacement field).
//
// Points on several patches: prescribed beats sliding beats free; between prescribing
// patches the first patch wins (its points move with it as a group: a rigid group is moved
// along its rigid motion by sub-steps).

#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <cstdint>
#include <vector>

namespace rbm::motion {

enum class BoundaryNodeClass : std::uint8_t {
    prescribed,  // displacement given by the front door before every solve
    sliding,     // unknown, held on the plane through its reference position normal to the normal
    free,        // unknown, moves like an interior node
    ignored,     // not a motion condition (empty, wedge): the 2D handling owns these points
    coupled,     // a plain cyclic patch: unknown, moves like an interior node, tied to its partner
                 // point on the neighbour patch (CyclicCoupling.hpp)
};

struct BoundaryPatchDescription {
    BoundaryNodeClass nodeClass = BoundaryNodeClass::free;
    // Mesh point labels of the patch in OpenFOAM's localPoints order (patchMeshPoints).
    std::vector<Label> meshPoints;
    // Sliding: one unit normal per entry of meshPoints; empty otherwise.
    std::vector<Vector3> slidingNormals;
    // Sliding: the plane is a mirror of the mesh (symmetry, symmetryPlane), so that in 3D a
    // point on it may turn only about the normal; false for slip-type walls.
    bool mirror = false;
};

// One entry per mesh patch, in the mesh's patch order.
using BoundaryDescription = std::vector<BoundaryPatchDescription>;

} // namespace rbm::motion
