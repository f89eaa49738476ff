#pragma once
// Face centres and area vectors, cell centres and volumes of a PolyMesh, computed with
// exactly OpenFOAM v1912's algorithms so that every derived measure (non-orthogonality,
// skewness, volumes) agrees with checkMesh to round-off:
//
//  - faces (primitiveMeshTools::makeFaceCentresAndAreas, primitiveMeshFaceCentresAndAreas.C):
//    a triangle directly; any other face is split into triangles (p_i, p_i+1, c) about the
//    average c of its points; area vector = sum of the triangle area vectors, centre = the
//    triangle centroids weighted by the triangle area *magnitudes*. A face whose summed
//    triangle area is below ROOTVSMALL (1e-150) gets the point average and a zero area.
//  - cells (primitiveMeshTools::makeCellCentresAndVols, primitiveMeshCellCentresAndVols.C):
//    the estimated centre is the average of the cell's face centres; the cell is split into
//    one pyramid per face with that apex; volume = sum of the signed pyramid volumes, centre
//    = pyramid centroids (3/4 face centre + 1/4 apex) weighted by the signed volumes. When
//    |volume| <= VSMALL (1e-300) the centre falls back to the estimate.
//
// Conventions: face area vectors follow the right-hand rule on the point order (owner to
// neighbour, outward on boundary faces); a cell whose faces point inward gets a negative
// volume. Storage is reused between calls (no reallocation when the mesh size is
// unchanged), so computing the geometry of every time step allocates nothing.

#include "PolyMesh.hpp"

#include <span>
#include <vector>

namespace rbm {

struct MeshGeometry {
    std::vector<Vector3> faceCentres;            // one per face
    std::vector<Vector3> faceAreas;              // one per face: unit normal times area
    std::vector<Vector3> cellCentres;            // one per cell
    std::vector<double> cellVolumes;             // one per cell, signed
    std::vector<Vector3> estimatedCellCentres;   // one per cell: average of its face centres (pyramid apex)
};

// Fills faceCentres and faceAreas (resized to mesh.faceCount()) from `points`, which
// replace mesh.points (same count), so moved positions need no PolyMesh copy.
void computeFaceCentresAndAreas(const PolyMesh& mesh, std::span<const Vector3> points,
                                std::vector<Vector3>& faceCentres, std::vector<Vector3>& faceAreas);

// Fills the cell centres, volumes and estimated centres (resized to cellCount) from the
// face centres and areas.
void computeCellCentresAndVolumes(const PolyMesh& mesh, Label cellCount, std::span<const Vector3> faceCentres,
                                  std::span<const Vector3> faceAreas, std::vector<Vector3>& estimatedCellCentres,
                                  std::vector<Vector3>& cellCentres, std::vector<double>& cellVolumes);

// Both steps, for the points `points` (mesh.points or moved positions).
void updateMeshGeometry(const PolyMesh& mesh, std::span<const Vector3> points, MeshGeometry& geometry);

MeshGeometry computeMeshGeometry(const PolyMesh& mesh, std::span<const Vector3> points);
inline MeshGeometry computeMeshGeometry(const PolyMesh& mesh) { return computeMeshGeometry(mesh, mesh.points); }

} // namespace rbm
