#include "BenchmarkMeshes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace rbm {

namespace {

// Faces of OpenFOAM's cell models as loops of local point indices (orientation is fixed
// afterwards from the geometry, so only the cyclic order matters).
struct ShapeFaces {
    int faceCount = 0;
    std::array<int, 6> sizes{};
    std::array<std::array<int, 4>, 6> points{};
};

const ShapeFaces& shapeFaces(Label pointCount)
{
    static const ShapeFaces tetrahedron{4, {3, 3, 3, 3, 0, 0}, {{{0, 2, 1, 0}, {0, 1, 3, 0}, {1, 2, 3, 0}, {0, 3, 2, 0}}}};
    static const ShapeFaces prism{
        5, {3, 3, 4, 4, 4, 0}, {{{0, 2, 1, 0}, {3, 4, 5, 0}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}}};
    static const ShapeFaces hexahedron{
        6, {4, 4, 4, 4, 4, 4}, {{{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}}}};
    switch (pointCount) {
    case 4: return tetrahedron;
    case 6: return prism;
    case 8: return hexahedron;
    default:
        throw std::invalid_argument("assemblePolyMeshFromCells: a cell with " + std::to_string(pointCount) +
                                    " points (expected 4, 6 or 8)");
    }
}

// One face of one cell, keyed by its sorted point labels (-1 pads triangles).
struct FaceInstance {
    std::array<Label, 4> key;
    Label cell;
    Label localFace;
};

struct InternalFace {
    Label owner;
    Label neighbour;
    Label localFace;  // of the owner
};

struct BoundaryFace {
    Label patch;
    Label owner;
    Label localFace;
};

double gridCoordinate(Label i, Label n)
{
    if (i == 0) return -1.0;
    if (i == n) return 1.0;
    return -1.0 + 2.0 * static_cast<double>(i) / static_cast<double>(n);
}

void requireCellsPerSide(Label n)
{
    if (n < 8 || n % 8 != 0)
        throw std::invalid_argument("makeBoxWithHole: cells per side must be a positive multiple of 8, not " +
                                    std::to_string(n));
}

} // namespace

PolyMesh assemblePolyMeshFromCells(std::vector<Vector3> points, std::span<const Label> cellOffsets,
                                   std::span<const Label> cellPoints, std::vector<Patch> patches,
                                   const std::function<Label(const Vector3& faceCentre)>& patchOfBoundaryFace)
{
    const Label cellCount = static_cast<Label>(cellOffsets.size()) - 1;
    auto pointsOf = [&](Label cell) {
        return cellPoints.subspan(cellOffsets[cell], static_cast<std::size_t>(cellOffsets[cell + 1] - cellOffsets[cell]));
    };

    std::vector<FaceInstance> instances;
    std::vector<Vector3> cellCentres(cellCount);
    std::size_t instanceCount = 0;
    for (Label cell = 0; cell < cellCount; ++cell) instanceCount += shapeFaces(static_cast<Label>(pointsOf(cell).size())).faceCount;
    instances.reserve(instanceCount);
    for (Label cell = 0; cell < cellCount; ++cell) {
        const auto cellPointLabels = pointsOf(cell);
        const ShapeFaces& shape = shapeFaces(static_cast<Label>(cellPointLabels.size()));
        Vector3 centre;
        for (Label p : cellPointLabels) centre += points[p];
        cellCentres[cell] = centre / static_cast<double>(cellPointLabels.size());
        for (int f = 0; f < shape.faceCount; ++f) {
            FaceInstance instance{{-1, -1, -1, -1}, cell, f};
            for (int k = 0; k < shape.sizes[f]; ++k) instance.key[k] = cellPointLabels[shape.points[f][k]];
            // The key has at most 4 labels: a small insertion sort (std::sort over a bounded
            // prefix of a std::array trips GCC 12's -Warray-bounds, a false positive).
            for (int k = 1; k < shape.sizes[f]; ++k)
                for (int m = k; m > 0 && instance.key[m - 1] > instance.key[m]; --m) std::swap(instance.key[m - 1], instance.key[m]);
            instances.push_back(instance);
        }
    }
    std::sort(instances.begin(), instances.end(),
              [](const FaceInstance& a, const FaceInstance& b) { return a.key < b.key; });

    std::vector<InternalFace> internalFaces;
    std::vector<BoundaryFace> boundaryFaces;
    internalFaces.reserve(instances.size() / 2);
    auto faceCentre = [&](Label cell, Label localFace) {
        const auto cellPointLabels = pointsOf(cell);
        const ShapeFaces& shape = shapeFaces(static_cast<Label>(cellPointLabels.size()));
        Vector3 centre;
        for (int k = 0; k < shape.sizes[localFace]; ++k) centre += points[cellPointLabels[shape.points[localFace][k]]];
        return centre / static_cast<double>(shape.sizes[localFace]);
    };
    for (std::size_t k = 0; k < instances.size();) {
        std::size_t end = k + 1;
        while (end < instances.size() && instances[end].key == instances[k].key) ++end;
        if (end - k > 2)
            throw std::invalid_argument("assemblePolyMeshFromCells: a face is shared by more than two cells");
        if (end - k == 2) {
            const FaceInstance& a = instances[k];
            const FaceInstance& b = instances[k + 1];
            if (a.cell < b.cell) internalFaces.push_back({a.cell, b.cell, a.localFace});
            else internalFaces.push_back({b.cell, a.cell, b.localFace});
        } else {
            const FaceInstance& a = instances[k];
            const Label patch = patchOfBoundaryFace(faceCentre(a.cell, a.localFace));
            if (patch < 0 || patch >= static_cast<Label>(patches.size()))
                throw std::invalid_argument("assemblePolyMeshFromCells: boundary face classified into patch " +
                                            std::to_string(patch) + " of " + std::to_string(patches.size()));
            boundaryFaces.push_back({patch, a.cell, a.localFace});
        }
        k = end;
    }
    std::vector<FaceInstance>().swap(instances);
    std::sort(internalFaces.begin(), internalFaces.end(), [](const InternalFace& a, const InternalFace& b) {
        return a.owner != b.owner ? a.owner < b.owner : a.neighbour < b.neighbour;
    });
    std::sort(boundaryFaces.begin(), boundaryFaces.end(), [](const BoundaryFace& a, const BoundaryFace& b) {
        if (a.patch != b.patch) return a.patch < b.patch;
        return a.owner != b.owner ? a.owner < b.owner : a.localFace < b.localFace;
    });

    PolyMesh mesh;
    mesh.points = std::move(points);
    const std::size_t faceCount = internalFaces.size() + boundaryFaces.size();
    mesh.faceOffsets.reserve(faceCount + 1);
    mesh.facePoints.reserve(faceCount * 4);
    mesh.owner.reserve(faceCount);
    mesh.neighbour.reserve(internalFaces.size());
    // Appends the face loop oriented out of `cell` (normal by Newell's method).
    std::array<Label, 4> loop{};
    auto addFace = [&](Label cell, Label localFace) {
        const auto cellPointLabels = pointsOf(cell);
        const ShapeFaces& shape = shapeFaces(static_cast<Label>(cellPointLabels.size()));
        const int size = shape.sizes[localFace];
        Vector3 normal;
        Vector3 centre;
        for (int k = 0; k < size; ++k) {
            loop[k] = cellPointLabels[shape.points[localFace][k]];
            centre += mesh.points[loop[k]];
        }
        centre /= static_cast<double>(size);
        for (int k = 0; k < size; ++k) normal += cross(mesh.points[loop[k]], mesh.points[loop[(k + 1) % size]]);
        if (dot(normal, centre - cellCentres[cell]) < 0.0) std::reverse(loop.begin(), loop.begin() + size);
        mesh.addFace(std::span<const Label>(loop.data(), static_cast<std::size_t>(size)));
        mesh.owner.push_back(cell);
    };
    for (const InternalFace& face : internalFaces) {
        addFace(face.owner, face.localFace);
        mesh.neighbour.push_back(face.neighbour);
    }
    std::vector<Label> patchFaceCounts(patches.size(), 0);
    for (const BoundaryFace& face : boundaryFaces) {
        addFace(face.owner, face.localFace);
        ++patchFaceCounts[face.patch];
    }
    Label start = static_cast<Label>(internalFaces.size());
    for (std::size_t p = 0; p < patches.size(); ++p) {
        patches[p].startFace = start;
        patches[p].faceCount = patchFaceCounts[p];
        start += patchFaceCounts[p];
    }
    mesh.patches = std::move(patches);
    return mesh;
}

bool isPlanarCellKind(HoleMeshCellKind kind)
{
    return kind == HoleMeshCellKind::quadrilaterals || kind == HoleMeshCellKind::triangles;
}

double boxWithHoleNodeCount(Label cellsPerSide, HoleMeshCellKind kind)
{
    const double n = cellsPerSide;
    const double holeInterior = n / 4.0 - 1.0;   // points strictly inside the hole, per side
    if (isPlanarCellKind(kind)) return (n + 1.0) * (n + 1.0) - holeInterior * holeInterior;
    return (n + 1.0) * (n + 1.0) * (n + 1.0) - holeInterior * holeInterior * holeInterior;
}

Label boxWithHoleCellsPerSide(double targetNodes, HoleMeshCellKind kind)
{
    Label best = 8;
    for (Label n = 8;; n += 8) {
        if (std::abs(boxWithHoleNodeCount(n, kind) - targetNodes) < std::abs(boxWithHoleNodeCount(best, kind) - targetNodes))
            best = n;
        if (boxWithHoleNodeCount(n, kind) > targetNodes) break;
    }
    return best;
}

PolyMesh makeBoxWithHole(Label n, HoleMeshCellKind kind)
{
    requireCellsPerSide(n);
    const bool planar = isPlanarCellKind(kind);
    const Label holeBegin = 3 * n / 8;   // hole cells: [holeBegin, holeEnd) in every direction
    const Label holeEnd = 5 * n / 8;
    const Label layers = planar ? 1 : n;
    const double thickness = 2.0 / static_cast<double>(n);
    auto pointInHole = [&](Label i, Label j, Label k) {
        const bool inside = i > holeBegin && i < holeEnd && j > holeBegin && j < holeEnd;
        return planar ? inside : inside && k > holeBegin && k < holeEnd;
    };
    auto cellInHole = [&](Label i, Label j, Label k) {
        const bool inside = i >= holeBegin && i < holeEnd && j >= holeBegin && j < holeEnd;
        return planar ? inside : inside && k >= holeBegin && k < holeEnd;
    };

    const std::size_t side = static_cast<std::size_t>(n) + 1;
    std::vector<Label> pointLabel(side * side * static_cast<std::size_t>(layers + 1), -1);
    std::vector<Vector3> points;
    points.reserve(static_cast<std::size_t>(boxWithHoleNodeCount(n, kind)) * (planar ? 2 : 1));
    for (Label k = 0; k <= layers; ++k)
        for (Label j = 0; j <= n; ++j)
            for (Label i = 0; i <= n; ++i) {
                if (pointInHole(i, j, k)) continue;
                pointLabel[(static_cast<std::size_t>(k) * side + j) * side + i] = static_cast<Label>(points.size());
                const double z = planar ? (k == 0 ? 0.0 : thickness) : gridCoordinate(k, n);
                points.push_back({gridCoordinate(i, n), gridCoordinate(j, n), z});
            }
    auto label = [&](Label i, Label j, Label k) { return pointLabel[(static_cast<std::size_t>(k) * side + j) * side + i]; };

    std::vector<Label> cellOffsets{0};
    std::vector<Label> cellPoints;
    auto addCell = [&](std::initializer_list<Label> cellPointLabels) {
        cellPoints.insert(cellPoints.end(), cellPointLabels.begin(), cellPointLabels.end());
        cellOffsets.push_back(static_cast<Label>(cellPoints.size()));
    };
    for (Label k = 0; k < layers; ++k)
        for (Label j = 0; j < n; ++j)
            for (Label i = 0; i < n; ++i) {
                if (cellInHole(i, j, k)) continue;
                // Corner (a, b, c) of the grid cube.
                auto v = [&](Label a, Label b, Label c) { return label(i + a, j + b, k + c); };
                switch (kind) {
                case HoleMeshCellKind::quadrilaterals:
                case HoleMeshCellKind::hexahedra:
                    addCell({v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0), v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)});
                    break;
                case HoleMeshCellKind::triangles:
                    addCell({v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 0, 1), v(1, 0, 1), v(1, 1, 1)});
                    addCell({v(0, 0, 0), v(1, 1, 0), v(0, 1, 0), v(0, 0, 1), v(1, 1, 1), v(0, 1, 1)});
                    break;
                case HoleMeshCellKind::tetrahedra: {
                    // Kuhn: one tetrahedron per order of the axes along the path (0,0,0) -> (1,1,1).
                    static constexpr std::array<std::array<int, 3>, 6> orders{
                        {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
                    for (const auto& order : orders) {
                        std::array<Label, 3> corner{0, 0, 0};
                        const Label first = v(0, 0, 0);
                        corner[order[0]] = 1;
                        const Label second = v(corner[0], corner[1], corner[2]);
                        corner[order[1]] = 1;
                        const Label third = v(corner[0], corner[1], corner[2]);
                        addCell({first, second, third, v(1, 1, 1)});
                    }
                    break;
                }
                }
            }

    std::vector<Patch> patches{{"inner", "wall", {}, 0, 0, {}}, {"outer", "patch", {}, 0, 0, {}}};
    if (planar) patches.push_back({"frontAndBack", "empty", {}, 0, 0, {}});
    const double tolerance = 0.25 / static_cast<double>(n);
    auto patchOf = [&](const Vector3& centre) -> Label {
        if (planar && (std::abs(centre.z) < tolerance || std::abs(centre.z - thickness) < tolerance)) return 2;
        double extent = std::max(std::abs(centre.x), std::abs(centre.y));
        if (!planar) extent = std::max(extent, std::abs(centre.z));
        return extent > 1.0 - tolerance ? 1 : 0;
    };
    return assemblePolyMeshFromCells(std::move(points), cellOffsets, cellPoints, std::move(patches), patchOf);
}

} // namespace rbm
