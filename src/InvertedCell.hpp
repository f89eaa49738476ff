#pragma once
// The one definition of an inverted cell, used by every check that decides something on it:
// rbmMoveMesh's and the plugin's step verdict and exit status (StepAssessment), the
// solver's sub-step splits and untangling (RigidBodyMotionSolver), rbmCheckMesh's report
// (QualityReport) and the thesis' metrics (ThesisQuality).
//
//   2D (a cell of a pseudo-2D mesh, a polygon counter-clockwise in its plane): its signed area
//   is ≤ 0, or one of its edge triangles with apex at its area centroid has a signed area ≤ 0
//   (the side faces' pyramids of the pseudo-3D cell: a concave cell whose centroid has left it
//   across an edge keeps a positive area, but OpenFOAM's checkMesh reports "Error in face
//   pyramids" on it and flow solvers fail there);
//   3D: its volume is ≤ 0, or one of its face pyramids with apex at the cell centre has a
//   volume ≤ 0, S_f·(c_f − C)/3 with the face's area vector S_f pointing out of the cell (a
//   cell folded through itself can keep a positive volume; a pyramid still turns over).

#include "Vector3.hpp"

namespace rbm {

// `smallestEdgeTriangle`: the smallest signed area of the polygon's edge triangles over its
// centroid (any positive multiple of them, e.g. smallestEdgeTriangle in ThesisQuality.hpp).
inline bool isInvertedPolygon(double signedArea, double smallestEdgeTriangle)
{
    return signedArea <= 0.0 || smallestEdgeTriangle <= 0.0;
}

// 3 × the volume of the pyramid of a face over a cell centre: `faceArea` is the face's area
// vector as stored (pointing out of its owner); `ownerSide` is whether the cell is the owner.
inline double tripleFacePyramid(const Vector3& faceArea, const Vector3& faceCentre, const Vector3& cellCentre,
                                bool ownerSide)
{
    return ownerSide ? dot(faceArea, faceCentre - cellCentre) : dot(faceArea, cellCentre - faceCentre);
}

// `smallestPyramid`: the smallest of the cell's face pyramids (any positive multiple of their
// volumes, e.g. tripleFacePyramid).
inline bool isInvertedCell(double volume, double smallestPyramid) { return smallestPyramid <= 0.0 || volume <= 0.0; }

} // namespace rbm
