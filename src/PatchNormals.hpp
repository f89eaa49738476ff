#pragma once
// Normals of faces and of a patch's points, with OpenFOAM's definitions, so that a plane or
// surface rbm keeps is the one OpenFOAM's own conditions see.

#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <span>
#include <vector>

namespace rbm {

// OpenFOAM face::areaNormal: a triangle directly, otherwise the sum of the triangles
// (p_i, p_i+1, centre) about the point average. Its length is the face's area.
Vector3 faceAreaNormal(std::span<const Label> face, std::span<const Vector3> points);

// face::unitNormal: faceAreaNormal / (|faceAreaNormal| + VSMALL).
Vector3 faceUnitNormal(std::span<const Label> face, std::span<const Vector3> points);

// Unit normal per patch point (OpenFOAM PrimitivePatch::pointNormals): the normalised sum of the
// unit normals of the patch faces using the point. `meshPoints` from patchMeshPoints; `points`
// are all mesh point positions.
std::vector<Vector3> patchPointNormals(const PolyMesh& mesh, Label patchIndex, std::span<const Label> meshPoints,
                                       std::span<const Vector3> points);

} // namespace rbm
