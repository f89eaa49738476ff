#pragma once
// A 2D polygon mesh: what the RBM solver works on for OpenFOAM's pseudo-3D cases
// (docs/method.md §6), and what the thesis' 2D quality metrics (§2.7.1) are defined on.
//
// Coordinates are in the plane's own right-handed frame (see PlaneFrame in
// PseudoTwoDExtraction.hpp): points[i].x and points[i].y are the 2D coordinates, and
// points[i].z is the plane coordinate (constant over a plane), kept so that nothing is lost.
//
// Cells are polygons in CSR form, listed counter-clockwise seen from +z, so that a valid
// cell has a positive signed area (the thesis orders nodes counter-clockwise for the
// mean-ratio and F_shape metrics, eqs 2.93 and 2.99).
//
// Edges follow OpenFOAM's face conventions one dimension down: internal edges first
// (upper-triangular: sorted by owner, then neighbour, owner < neighbour), then boundary
// edges grouped by patch. Edge e runs from edgePoints[2e] to edgePoints[2e+1] in the
// owner's counter-clockwise order, so the owner lies on its left and the normal
// (dy, -dx) points from owner to neighbour (out of the domain on boundary edges).

#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace rbm {

struct PlanarPatch {
    std::string name;
    std::string type;
    Label startEdge = 0;
    Label edgeCount = 0;
    Label polyMeshPatch = -1;   // the 3D patch this came from; -1 when it has none (e.g. a wedge axis)
};

struct PlanarMesh {
    std::vector<Vector3> points;
    std::vector<Label> cellOffsets{0};
    std::vector<Label> cellPoints;
    std::vector<Label> edgePoints;       // two per edge
    std::vector<Label> edgeOwner;        // one per edge
    std::vector<Label> edgeNeighbour;    // one per internal edge
    std::vector<PlanarPatch> patches;

    Label nodeCount() const { return static_cast<Label>(points.size()); }
    Label cellCount() const { return static_cast<Label>(cellOffsets.size()) - 1; }
    Label edgeCount() const { return static_cast<Label>(edgeOwner.size()); }
    Label internalEdgeCount() const { return static_cast<Label>(edgeNeighbour.size()); }

    std::span<const Label> cell(Label c) const
    {
        return {cellPoints.data() + cellOffsets[c], static_cast<std::size_t>(cellOffsets[c + 1] - cellOffsets[c])};
    }
    std::array<Label, 2> edge(Label e) const { return {edgePoints[2 * e], edgePoints[2 * e + 1]}; }

    // Signed area of cell c by the shoelace formula on (x, y): positive for a valid
    // (counter-clockwise) cell, negative for an inverted one.
    double signedArea(Label c) const;
    // The same for the cell with its nodes at `positions` instead of `points`.
    double signedArea(Label c, std::span<const Vector3> positions) const;
    // Index of the patch holding boundary edge e, or -1 for an internal edge.
    Label patchOfEdge(Label e) const;
};

} // namespace rbm
