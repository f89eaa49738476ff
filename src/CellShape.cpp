#include "CellShape.hpp"

#include <algorithm>
#include <array>

namespace rbm {

namespace {

// The outward-oriented faces of a cell that might be a standard shape: at most 6 faces of
// at most 4 points, in fixed-size storage (no allocation per cell).
struct SmallCell {
    std::array<std::array<Label, 4>, 6> faces{};
    std::array<int, 6> sizes{};
    int faceCount = 0;
};

bool contains(const Label* begin, int size, Label value) { return std::find(begin, begin + size, value) != begin + size; }

// Fills `cell` with the outward faces, or returns false when a face has more than 4 points.
bool loadSmallCell(const PolyMesh& mesh, const MeshTopology& topology, Label c, SmallCell& cell)
{
    const auto faces = topology.facesOf(c);
    cell.faceCount = static_cast<int>(faces.size());
    for (int i = 0; i < cell.faceCount; ++i) {
        const Label f = faces[i];
        const auto points = mesh.face(f);
        if (points.size() < 3 || points.size() > 4) return false;
        const int n = static_cast<int>(points.size());
        cell.sizes[i] = n;
        const bool owned = mesh.owner[f] == c;
        for (int k = 0; k < n; ++k) cell.faces[i][k] = owned ? points[k] : points[n - 1 - k];
    }
    return true;
}

// For every point of `base`, the point joined to it by an edge that leaves the base.
// Fails when a base point has no such edge or more than one (then the cell is not a prism
// or hexahedron whatever its counts say).
bool findOppositePoints(const SmallCell& cell, const Label* base, int baseSize, Label* opposite)
{
    std::fill(opposite, opposite + baseSize, Label{-1});
    auto record = [&](Label from, Label to) {
        const int i = static_cast<int>(std::find(base, base + baseSize, from) - base);
        if (i == baseSize || contains(base, baseSize, to)) return true;
        if (opposite[i] != -1 && opposite[i] != to) return false;
        opposite[i] = to;
        return true;
    };
    for (int f = 0; f < cell.faceCount; ++f) {
        const int n = cell.sizes[f];
        for (int k = 0; k < n; ++k) {
            const Label p = cell.faces[f][k];
            const Label q = cell.faces[f][(k + 1) % n];
            if (!record(p, q) || !record(q, p)) return false;
        }
    }
    for (int i = 0; i < baseSize; ++i) {
        if (opposite[i] == -1) return false;
        for (int j = 0; j < i; ++j) {
            if (opposite[j] == opposite[i]) return false;
        }
    }
    return true;
}

// Every side face must be {base i, base i+1, opposite i+1, opposite i} for some i, and the
// remaining face must be the opposites: then the cell really is the extruded base.
bool sideFacesMatch(const SmallCell& cell, const Label* base, const Label* opposite, int baseSize, int baseFace)
{
    int sideCount = 0;
    int topCount = 0;
    for (int f = 0; f < cell.faceCount; ++f) {
        if (f == baseFace) continue;
        const Label* face = cell.faces[f].data();
        const int n = cell.sizes[f];
        if (n == baseSize && std::all_of(opposite, opposite + baseSize, [&](Label p) { return contains(face, n, p); })) {
            ++topCount;
            continue;
        }
        if (n != 4) return false;
        bool matched = false;
        for (int i = 0; i < baseSize && !matched; ++i) {
            const int j = (i + 1) % baseSize;
            matched = contains(face, 4, base[i]) && contains(face, 4, base[j]) && contains(face, 4, opposite[i])
                      && contains(face, 4, opposite[j]);
        }
        if (!matched) return false;
        ++sideCount;
    }
    return sideCount == baseSize && topCount == 1;
}

// Recognises a standard shape and writes its VTK-ordered nodes; returns Polyhedron otherwise.
CellShape orderStandardCell(const PolyMesh& mesh, const MeshTopology& topology, Label c, std::array<Label, 8>& nodes)
{
    const auto faces = topology.facesOf(c);
    const auto points = topology.pointsOf(c);
    if (faces.size() < 4 || faces.size() > 6) return CellShape::Polyhedron;
    SmallCell cell;
    if (!loadSmallCell(mesh, topology, c, cell)) return CellShape::Polyhedron;
    const int triangles = static_cast<int>(std::count(cell.sizes.begin(), cell.sizes.begin() + cell.faceCount, 3));
    const int quads = cell.faceCount - triangles;
    const std::size_t pointCount = points.size();
    auto firstFaceOfSize = [&](int size) {
        return static_cast<int>(std::find(cell.sizes.begin(), cell.sizes.begin() + cell.faceCount, size)
                                - cell.sizes.begin());
    };
    auto apexOutside = [&](const Label* base, int baseSize) {
        for (Label p : points) {
            if (!contains(base, baseSize, p)) return p;
        }
        return Label{-1};
    };

    if (cell.faceCount == 4 && triangles == 4 && pointCount == 4) {
        // VTK_TETRA: an outward face reversed points at the apex.
        const auto& base = cell.faces[0];
        nodes = {base[0], base[2], base[1], apexOutside(base.data(), 3)};
        return CellShape::Tetrahedron;
    }
    if (cell.faceCount == 5 && triangles == 4 && quads == 1 && pointCount == 5) {
        // VTK_PYRAMID: the outward base reversed has its normal towards the apex.
        const auto& base = cell.faces[firstFaceOfSize(4)];
        const Label apex = apexOutside(base.data(), 4);
        for (int f = 0; f < cell.faceCount; ++f) {
            if (cell.sizes[f] == 3 && !contains(cell.faces[f].data(), 3, apex)) return CellShape::Polyhedron;
        }
        nodes = {base[0], base[3], base[2], base[1], apex};
        return CellShape::Pyramid;
    }
    if (cell.faceCount == 5 && triangles == 2 && quads == 3 && pointCount == 6) {
        // VTK_WEDGE: triangle (0,1,2) outward, i.e. its normal points away from (3,4,5).
        const int baseFace = firstFaceOfSize(3);
        const auto& base = cell.faces[baseFace];
        std::array<Label, 3> opposite{};
        if (!findOppositePoints(cell, base.data(), 3, opposite.data())) return CellShape::Polyhedron;
        if (!sideFacesMatch(cell, base.data(), opposite.data(), 3, baseFace)) return CellShape::Polyhedron;
        nodes = {base[0], base[1], base[2], opposite[0], opposite[1], opposite[2]};
        return CellShape::Prism;
    }
    if (cell.faceCount == 6 && quads == 6 && pointCount == 8) {
        // VTK_HEXAHEDRON: the outward base reversed has its normal towards the top face.
        const auto& outward = cell.faces[0];
        const std::array<Label, 4> base{outward[0], outward[3], outward[2], outward[1]};
        std::array<Label, 4> opposite{};
        if (!findOppositePoints(cell, base.data(), 4, opposite.data())) return CellShape::Polyhedron;
        if (!sideFacesMatch(cell, base.data(), opposite.data(), 4, 0)) return CellShape::Polyhedron;
        nodes = {base[0], base[1], base[2], base[3], opposite[0], opposite[1], opposite[2], opposite[3]};
        return CellShape::Hexahedron;
    }
    return CellShape::Polyhedron;
}

} // namespace

std::string_view cellShapeName(CellShape shape)
{
    switch (shape) {
    case CellShape::Tetrahedron: return "tetrahedron";
    case CellShape::Pyramid: return "pyramid";
    case CellShape::Prism: return "prism";
    case CellShape::Hexahedron: return "hexahedron";
    case CellShape::Polyhedron: return "polyhedron";
    }
    return "unknown";
}

std::string_view polygonShapeName(PolygonShape shape)
{
    switch (shape) {
    case PolygonShape::Triangle: return "triangle";
    case PolygonShape::Quadrilateral: return "quadrilateral";
    case PolygonShape::Polygon: return "polygon";
    }
    return "unknown";
}

PolygonShape polygonShape(std::size_t pointCount)
{
    if (pointCount == 3) return PolygonShape::Triangle;
    if (pointCount == 4) return PolygonShape::Quadrilateral;
    return PolygonShape::Polygon;
}

VtkCellType vtkPolygonType(std::size_t pointCount)
{
    if (pointCount == 3) return VtkCellType::Triangle;
    if (pointCount == 4) return VtkCellType::Quad;
    return VtkCellType::Polygon;
}

CellShape cellShape(const PolyMesh& mesh, const MeshTopology& topology, Label cell)
{
    std::array<Label, 8> nodes{};
    return orderStandardCell(mesh, topology, cell, nodes);
}

VtkCellType appendVtkCell(const PolyMesh& mesh, const MeshTopology& topology, Label cell,
                          std::vector<Label>& connectivity, std::vector<Label>& faceStream)
{
    std::array<Label, 8> nodes{};
    const CellShape shape = orderStandardCell(mesh, topology, cell, nodes);
    auto appendNodes = [&](std::size_t count) {
        connectivity.insert(connectivity.end(), nodes.begin(), nodes.begin() + static_cast<std::ptrdiff_t>(count));
    };
    switch (shape) {
    case CellShape::Tetrahedron: appendNodes(4); return VtkCellType::Tetra;
    case CellShape::Pyramid: appendNodes(5); return VtkCellType::Pyramid;
    case CellShape::Prism: appendNodes(6); return VtkCellType::Wedge;
    case CellShape::Hexahedron: appendNodes(8); return VtkCellType::Hexahedron;
    case CellShape::Polyhedron: break;
    }
    const auto points = topology.pointsOf(cell);
    connectivity.insert(connectivity.end(), points.begin(), points.end());
    const auto faces = topology.facesOf(cell);
    faceStream.push_back(static_cast<Label>(faces.size()));
    for (Label f : faces) {
        faceStream.push_back(static_cast<Label>(mesh.face(f).size()));
        appendOutwardFace(mesh, f, cell, faceStream);
    }
    return VtkCellType::Polyhedron;
}

std::vector<Label> countCellShapes(const PolyMesh& mesh, const MeshTopology& topology)
{
    std::vector<Label> counts(5, 0);
    for (Label c = 0; c < topology.cellCount; ++c) ++counts[static_cast<std::size_t>(cellShape(mesh, topology, c))];
    return counts;
}

} // namespace rbm
