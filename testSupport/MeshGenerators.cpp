#include "MeshGenerators.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <tuple>

namespace rbm {

namespace {

// Coordinate i of n equal steps from a to b, exactly a at i = 0 and exactly b at i = n.
double gridCoordinate(double a, double b, Label i, Label n)
{
    if (i == n) return b;
    const double t = static_cast<double>(i) / static_cast<double>(n);
    return a * (1.0 - t) + b * t;
}

void requirePositive(Label count, const char* what)
{
    if (count < 1) throw std::invalid_argument(std::string("mesh generator: ") + what + " must be at least 1");
}

void addFace(PolyMesh& mesh, std::initializer_list<Label> points, Label owner)
{
    mesh.addFace(std::span<const Label>(points.begin(), points.size()));
    mesh.owner.push_back(owner);
}

// ---------------------------------------------------------------------------------------
// 2D grids

struct PlanarGrid {
    std::vector<Vector3> points;   // (u, v, 0)
    std::vector<Label> cellOffsets{0};
    std::vector<Label> cellPoints;   // counter-clockwise

    void addCell(std::initializer_list<Label> points)
    {
        cellPoints.insert(cellPoints.end(), points.begin(), points.end());
        cellOffsets.push_back(static_cast<Label>(cellPoints.size()));
    }
};

PlanarGrid makePlanarGrid(Label nx, Label ny, const Vector3& min, const Vector3& max, PlanarCellKind kind)
{
    requirePositive(nx, "nx");
    requirePositive(ny, "ny");
    if (kind == PlanarCellKind::Polygons && nx % 2 != 0) {
        throw std::invalid_argument("mesh generator: PlanarCellKind::Polygons needs an even nx");
    }
    PlanarGrid grid;
    for (Label j = 0; j <= ny; ++j) {
        for (Label i = 0; i <= nx; ++i) {
            grid.points.push_back({gridCoordinate(min.x, max.x, i, nx), gridCoordinate(min.y, max.y, j, ny), 0.0});
        }
    }
    auto point = [&](Label i, Label j) { return i + (nx + 1) * j; };
    for (Label j = 0; j < ny; ++j) {
        for (Label i = 0; i < nx; ++i) {
            const Label p00 = point(i, j), p10 = point(i + 1, j), p11 = point(i + 1, j + 1), p01 = point(i, j + 1);
            const bool triangles =
                kind == PlanarCellKind::Triangles || (kind == PlanarCellKind::Mixed && i >= nx / 2);
            if (kind == PlanarCellKind::Polygons) {
                if (i % 2 == 1) continue;
                grid.addCell({p00, p10, point(i + 2, j), point(i + 2, j + 1), p11, p01});
            } else if (triangles) {
                grid.addCell({p00, p10, p11});
                grid.addCell({p00, p11, p01});
            } else {
                grid.addCell({p00, p10, p11, p01});
            }
        }
    }
    return grid;
}

// ---------------------------------------------------------------------------------------
// One-layer extrusion of a 2D grid, shared by the empty and the wedge generators.

struct ExtrusionLayout {
    std::vector<Patch> sidePatches;                                      // boundary edges go here
    std::function<Label(const Vector3&, const Vector3&)> sidePatchOf;    // index into sidePatches
    std::function<Vector3(const Vector3&)> placeFront;                  // 2D (u, v) → 3D
    std::function<Vector3(const Vector3&)> placeBack;
    std::function<bool(const Vector3&)> onAxis;                          // shared by both planes
    std::vector<Patch> planePatches;                                     // one (front then back) or two
    std::vector<Patch> trailingPatches;                                  // e.g. an empty wedge axis
};

PolyMesh extrude(const PlanarGrid& grid, const ExtrusionLayout& layout)
{
    PolyMesh mesh;
    const Label nodeCount = static_cast<Label>(grid.points.size());
    const Label cellCount = static_cast<Label>(grid.cellOffsets.size()) - 1;

    // Points: the front plane in 2D order, then the back plane (axis points only once).
    std::vector<Label> backOf(static_cast<std::size_t>(nodeCount));
    for (Label n = 0; n < nodeCount; ++n) mesh.points.push_back(layout.placeFront(grid.points[n]));
    for (Label n = 0; n < nodeCount; ++n) {
        if (layout.onAxis(grid.points[n])) {
            backOf[n] = n;
        } else {
            backOf[n] = static_cast<Label>(mesh.points.size());
            mesh.points.push_back(layout.placeBack(grid.points[n]));
        }
    }

    // Edges: every cell edge keyed by its sorted end points; two cells = internal edge.
    struct CellEdge {
        Label low, high, cell, start, end;
    };
    std::vector<CellEdge> cellEdges;
    for (Label c = 0; c < cellCount; ++c) {
        const Label begin = grid.cellOffsets[c], size = grid.cellOffsets[c + 1] - begin;
        for (Label k = 0; k < size; ++k) {
            const Label a = grid.cellPoints[begin + k], b = grid.cellPoints[begin + (k + 1) % size];
            cellEdges.push_back({std::min(a, b), std::max(a, b), c, a, b});
        }
    }
    std::sort(cellEdges.begin(), cellEdges.end(), [](const CellEdge& x, const CellEdge& y) {
        return std::tie(x.low, x.high, x.cell) < std::tie(y.low, y.high, y.cell);
    });
    struct SideFace {
        Label owner, neighbour, start, end, patch;
    };
    std::vector<SideFace> internal, boundary;
    for (std::size_t k = 0; k < cellEdges.size();) {
        const CellEdge& e = cellEdges[k];
        if (k + 1 < cellEdges.size() && cellEdges[k + 1].low == e.low && cellEdges[k + 1].high == e.high) {
            if (k + 2 < cellEdges.size() && cellEdges[k + 2].low == e.low && cellEdges[k + 2].high == e.high) {
                throw std::logic_error("mesh generator: a 2D edge is shared by more than two cells");
            }
            internal.push_back({e.cell, cellEdges[k + 1].cell, e.start, e.end, -1});
            k += 2;
        } else {
            boundary.push_back({e.cell, -1, e.start, e.end, layout.sidePatchOf(grid.points[e.start], grid.points[e.end])});
            k += 1;
        }
    }
    std::sort(internal.begin(), internal.end(),
              [](const SideFace& x, const SideFace& y) { return std::tie(x.owner, x.neighbour) < std::tie(y.owner, y.neighbour); });
    std::stable_sort(boundary.begin(), boundary.end(), [](const SideFace& x, const SideFace& y) {
        return std::tie(x.patch, x.owner) < std::tie(y.patch, y.owner);
    });

    // Side face of 2D edge start → end (owner's counter-clockwise order): (a, b, b', a')
    // has its normal (b - a) × normal pointing out of the owner; points shared on the
    // axis appear once, and a face whose edge lies on the axis has collapsed away.
    std::vector<Label> facePoints;
    auto addSideFace = [&](const SideFace& side) {
        const bool startOnAxis = backOf[side.start] == side.start, endOnAxis = backOf[side.end] == side.end;
        if (startOnAxis && endOnAxis) return false;
        facePoints.clear();
        facePoints.push_back(side.start);
        facePoints.push_back(side.end);
        if (!endOnAxis) facePoints.push_back(backOf[side.end]);
        if (!startOnAxis) facePoints.push_back(backOf[side.start]);
        mesh.addFace(facePoints);
        mesh.owner.push_back(side.owner);
        return true;
    };
    for (const SideFace& side : internal) {
        if (!addSideFace(side)) throw std::logic_error("mesh generator: an internal edge lies on the wedge axis");
        mesh.neighbour.push_back(side.neighbour);
    }

    auto openPatch = [&](const Patch& prototype) {
        Patch patch = prototype;
        patch.startFace = mesh.faceCount();
        patch.faceCount = 0;
        mesh.patches.push_back(patch);
    };
    auto closePatch = [&]() { mesh.patches.back().faceCount = mesh.faceCount() - mesh.patches.back().startFace; };

    std::size_t next = 0;
    for (std::size_t p = 0; p < layout.sidePatches.size(); ++p) {
        openPatch(layout.sidePatches[p]);
        for (; next < boundary.size() && boundary[next].patch == static_cast<Label>(p); ++next) addSideFace(boundary[next]);
        closePatch();
    }
    if (next != boundary.size()) throw std::logic_error("mesh generator: a boundary edge has no side patch");

    // Front faces: the cell polygon reversed (outward normal −w); back faces: the polygon
    // on the back points (outward normal +w).
    auto addPlaneFaces = [&](bool front) {
        for (Label c = 0; c < cellCount; ++c) {
            facePoints.clear();
            for (Label k = grid.cellOffsets[c]; k < grid.cellOffsets[c + 1]; ++k) {
                const Label n = grid.cellPoints[k];
                facePoints.push_back(front ? n : backOf[n]);
            }
            if (front) std::reverse(facePoints.begin(), facePoints.end());
            mesh.addFace(facePoints);
            mesh.owner.push_back(c);
        }
    };
    openPatch(layout.planePatches.front());
    addPlaneFaces(true);
    if (layout.planePatches.size() == 2) {
        closePatch();
        openPatch(layout.planePatches.back());
    }
    addPlaneFaces(false);
    closePatch();
    for (const Patch& patch : layout.trailingPatches) {
        openPatch(patch);
        closePatch();
    }
    return mesh;
}

Patch makePatch(std::string name, std::string type)
{
    Patch patch;
    patch.name = std::move(name);
    patch.type = std::move(type);
    return patch;
}

// left / right / bottom / top by which box side both end points lie on.
Label boxSideOf(const Vector3& a, const Vector3& b, const Vector3& min, const Vector3& max)
{
    if (a.x == min.x && b.x == min.x) return 0;
    if (a.x == max.x && b.x == max.x) return 1;
    if (a.y == min.y && b.y == min.y) return 2;
    if (a.y == max.y && b.y == max.y) return 3;
    throw std::logic_error("mesh generator: a boundary edge is on no side of the box");
}

} // namespace

PolyMesh makeHexBox(Label nx, Label ny, Label nz, const Vector3& min, const Vector3& max,
                    const std::array<BoxPatch, 6>& sides)
{
    requirePositive(nx, "nx");
    requirePositive(ny, "ny");
    requirePositive(nz, "nz");
    PolyMesh mesh;
    for (Label k = 0; k <= nz; ++k) {
        for (Label j = 0; j <= ny; ++j) {
            for (Label i = 0; i <= nx; ++i) {
                mesh.points.push_back({gridCoordinate(min.x, max.x, i, nx), gridCoordinate(min.y, max.y, j, ny),
                                       gridCoordinate(min.z, max.z, k, nz)});
            }
        }
    }
    auto point = [&](Label i, Label j, Label k) { return i + (nx + 1) * (j + (ny + 1) * k); };
    auto cell = [&](Label i, Label j, Label k) { return i + nx * (j + ny * k); };
    // The face in plane i (x), j (y) or k (z) at cell position (i, j, k), its normal along
    // +x, +y or +z, or reversed.
    auto addXFace = [&](Label i, Label j, Label k, Label owner, bool positive) {
        if (positive) addFace(mesh, {point(i, j, k), point(i, j + 1, k), point(i, j + 1, k + 1), point(i, j, k + 1)}, owner);
        else addFace(mesh, {point(i, j, k), point(i, j, k + 1), point(i, j + 1, k + 1), point(i, j + 1, k)}, owner);
    };
    auto addYFace = [&](Label i, Label j, Label k, Label owner, bool positive) {
        if (positive) addFace(mesh, {point(i, j, k), point(i, j, k + 1), point(i + 1, j, k + 1), point(i + 1, j, k)}, owner);
        else addFace(mesh, {point(i, j, k), point(i + 1, j, k), point(i + 1, j, k + 1), point(i, j, k + 1)}, owner);
    };
    auto addZFace = [&](Label i, Label j, Label k, Label owner, bool positive) {
        if (positive) addFace(mesh, {point(i, j, k), point(i + 1, j, k), point(i + 1, j + 1, k), point(i, j + 1, k)}, owner);
        else addFace(mesh, {point(i, j, k), point(i, j + 1, k), point(i + 1, j + 1, k), point(i + 1, j, k)}, owner);
    };

    // Internal faces, upper-triangular: per owner, its x (c+1), y (c+nx), z (c+nx·ny) neighbours.
    for (Label k = 0; k < nz; ++k) {
        for (Label j = 0; j < ny; ++j) {
            for (Label i = 0; i < nx; ++i) {
                const Label c = cell(i, j, k);
                if (i + 1 < nx) { addXFace(i + 1, j, k, c, true); mesh.neighbour.push_back(cell(i + 1, j, k)); }
                if (j + 1 < ny) { addYFace(i, j + 1, k, c, true); mesh.neighbour.push_back(cell(i, j + 1, k)); }
                if (k + 1 < nz) { addZFace(i, j, k + 1, c, true); mesh.neighbour.push_back(cell(i, j, k + 1)); }
            }
        }
    }

    auto addSide = [&](int side) {
        switch (side) {
        case 0: for (Label k = 0; k < nz; ++k) for (Label j = 0; j < ny; ++j) addXFace(0, j, k, cell(0, j, k), false); break;
        case 1: for (Label k = 0; k < nz; ++k) for (Label j = 0; j < ny; ++j) addXFace(nx, j, k, cell(nx - 1, j, k), true); break;
        case 2: for (Label k = 0; k < nz; ++k) for (Label i = 0; i < nx; ++i) addYFace(i, 0, k, cell(i, 0, k), false); break;
        case 3: for (Label k = 0; k < nz; ++k) for (Label i = 0; i < nx; ++i) addYFace(i, ny, k, cell(i, ny - 1, k), true); break;
        case 4: for (Label j = 0; j < ny; ++j) for (Label i = 0; i < nx; ++i) addZFace(i, j, 0, cell(i, j, 0), false); break;
        case 5: for (Label j = 0; j < ny; ++j) for (Label i = 0; i < nx; ++i) addZFace(i, j, nz, cell(i, j, nz - 1), true); break;
        default: break;
        }
    };
    std::array<bool, 6> done{};
    for (int s = 0; s < 6; ++s) {
        if (done[s]) continue;
        Patch patch = makePatch(sides[s].name, sides[s].type);
        patch.startFace = mesh.faceCount();
        for (int t = s; t < 6; ++t) {
            if (!done[t] && sides[t].name == sides[s].name) {
                addSide(t);
                done[t] = true;
            }
        }
        patch.faceCount = mesh.faceCount() - patch.startFace;
        mesh.patches.push_back(std::move(patch));
    }
    return mesh;
}

PolyMesh makeExtruded2D(Label nx, Label ny, const Vector3& min, const Vector3& max, PlanarCellKind kind,
                        const ExtrusionOptions& options)
{
    if (options.normalAxis < 0 || options.normalAxis > 2) {
        throw std::invalid_argument("makeExtruded2D: normalAxis must be 0 (x), 1 (y) or 2 (z)");
    }
    const PlanarGrid grid = makePlanarGrid(nx, ny, min, max, kind);
    const int axis = options.normalAxis;
    auto place = [axis](double u, double v, double w) -> Vector3 {
        if (axis == 0) return {w, u, v};
        if (axis == 1) return {v, w, u};
        return {u, v, w};
    };
    ExtrusionLayout layout;
    layout.sidePatches = {makePatch("left", "patch"), makePatch("right", "patch"), makePatch("bottom", "patch"),
                          makePatch("top", "patch")};
    layout.sidePatchOf = [min, max](const Vector3& a, const Vector3& b) { return boxSideOf(a, b, min, max); };
    layout.placeFront = [place, min](const Vector3& p) { return place(p.x, p.y, min.z); };
    layout.placeBack = [place, max](const Vector3& p) { return place(p.x, p.y, max.z); };
    layout.onAxis = [](const Vector3&) { return false; };
    if (options.separateFrontAndBackPatches) {
        layout.planePatches = {makePatch("front", "empty"), makePatch("back", "empty")};
    } else {
        layout.planePatches = {makePatch("frontAndBack", "empty")};
    }
    return extrude(grid, layout);
}

PolyMesh makeWedge2D(Label nx, Label ny, const Vector3& min, const Vector3& max, double wedgeAngleDegrees,
                     PlanarCellKind kind)
{
    if (min.y < 0.0 || max.y <= min.y) throw std::invalid_argument("makeWedge2D: need 0 <= min.y < max.y (radius)");
    if (!(wedgeAngleDegrees > 0.0 && wedgeAngleDegrees < 180.0)) {
        throw std::invalid_argument("makeWedge2D: the wedge angle must be in (0, 180) degrees");
    }
    const PlanarGrid grid = makePlanarGrid(nx, ny, min, max, kind);
    const double halfAngle = 0.5 * wedgeAngleDegrees * std::numbers::pi / 180.0;
    const bool touchesAxis = min.y == 0.0;
    auto rotate = [](const Vector3& p, double phi) -> Vector3 { return {p.x, p.y * std::cos(phi), p.y * std::sin(phi)}; };

    ExtrusionLayout layout;
    layout.sidePatches = {makePatch("left", "patch"), makePatch("right", "patch")};
    if (!touchesAxis) layout.sidePatches.push_back(makePatch("bottom", "patch"));
    layout.sidePatches.push_back(makePatch("top", "patch"));
    layout.sidePatchOf = [min, max, touchesAxis](const Vector3& a, const Vector3& b) {
        // Without a "bottom" patch "top" is index 2; edges on the axis (bottom) collapse
        // away in extrude() and never become faces, so their index does not matter.
        const Label side = boxSideOf(a, b, min, max);
        return touchesAxis && side >= 2 ? Label{2} : side;
    };
    layout.placeFront = [rotate, halfAngle](const Vector3& p) { return rotate(p, -halfAngle); };
    layout.placeBack = [rotate, halfAngle](const Vector3& p) { return rotate(p, halfAngle); };
    layout.onAxis = [](const Vector3& p) { return p.y == 0.0; };
    layout.planePatches = {makePatch("front", "wedge"), makePatch("back", "wedge")};
    if (touchesAxis) layout.trailingPatches = {makePatch("axis", "empty")};
    return extrude(grid, layout);
}

} // namespace rbm
