#pragma once
// The point pairs of OpenFOAM's plain `cyclic` patches: a patch A and its neighbour patch B
// are one periodic interface, B the image of A under a fixed transform,
//   x_B = R (x_A − c) + c + t      (translational: R = I, t the separation; rotational: R the
//                                   rotation about the axis through c, t = 0),
// so a point of A and its partner on B must move together, u_B = R u_A, for the two sides to
// stay the same interface (docs/motionSolver.md, "Cyclic patches").
//
// OpenFOAM orders the faces of the two halves alike (face i of A is the image of face i of B,
// its points in reverse order), and rbm relies on that: each point of A's face i is paired
// with the point of B's face i nearest to its image, which must lie within 1e-4 of that
// face's shortest edge (OpenFOAM's default matchTolerance). The rotation angle is measured
// from the matched face centres (OpenFOAM v1912 does not write it, OpenFOAM 13 only once its
// own matching has run), and a translation without a transform given is the mean offset of
// the face centres; either way every point must then find its partner, or the patch is
// refused with an error naming it.
//
// io/CyclicPatchEntries.hpp reads the specifications from constant/polyMesh/boundary.

#include "PolyMesh.hpp"
#include "Rotation.hpp"
#include "Vector3.hpp"

#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rbm {

enum class CyclicTransformKind {
    translational,  // translational, coincidentFullMatch, none (a zero separation)
    rotational,     // rotationAxis and rotationCentre given
    unspecified,    // unknown, unspecified, noOrdering or no entry: tried as a translation
};

// What the boundary file says about one `cyclic` patch.
struct CyclicPatchSpec {
    Label patch = -1;  // index into PolyMesh::patches
    std::string neighbourPatch;
    CyclicTransformKind transform = CyclicTransformKind::unspecified;
    Vector3 rotationAxis{};    // rotational only (any length > 0)
    Vector3 rotationCentre{};  // rotational only
};

// One periodic interface: patch A (the lower patch index of the two) and its neighbour B.
struct CyclicPatchPairing {
    Label patchA = -1;
    Label patchB = -1;
    Matrix3 rotation = Matrix3::identity();  // R: u_B = R u_A
    Vector3 centre{};                        // c (rotational)
    Vector3 separation{};                    // t (translational)
    // (point of A, its partner on B), every point of A once, in the order A's faces meet them.
    // A point on the rotation axis can be its own partner.
    std::vector<std::pair<Label, Label>> points;
};

// The pairings of every cyclic patch of `specs` (one entry per `cyclic` patch of the mesh; each
// must name an existing cyclic neighbour that names it back), at the reference positions
// `points`. Throws rbm::InputError naming `file` and the patch: a neighbour that is missing, not
// cyclic or not reciprocal, face counts or face sizes that differ, a point with no partner, a
// point with two partners.
std::vector<CyclicPatchPairing> pairCyclicPatches(const PolyMesh& mesh, std::span<const Vector3> points,
                                                  std::span<const CyclicPatchSpec> specs, const std::string& file);

} // namespace rbm
