#include "MeshTopology.hpp"

#include "InputError.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace rbm {

namespace {

// Cheap structural checks without which building the topology would read out of bounds.
void requireIndexableMesh(const PolyMesh& mesh)
{
    const Label faceCount = mesh.faceCount();
    if (mesh.faceOffsets.size() != static_cast<std::size_t>(faceCount) + 1 || mesh.faceOffsets.front() != 0
        || static_cast<std::size_t>(mesh.faceOffsets.back()) != mesh.facePoints.size()) {
        throw InputError("", 0,
                         "polyMesh has " + std::to_string(faceCount) + " owner entries but "
                             + std::to_string(mesh.faceOffsets.size()) + " face offsets; expected one more offset "
                             "than faces, starting at 0 and ending at the number of face points");
    }
    if (mesh.internalFaceCount() > faceCount) {
        throw InputError("", 0,
                         "polyMesh has more neighbour entries (" + std::to_string(mesh.internalFaceCount())
                             + ") than faces (" + std::to_string(faceCount) + ")");
    }
    for (Label f = 0; f < faceCount; ++f) {
        if (mesh.faceOffsets[f + 1] < mesh.faceOffsets[f]) {
            throw InputError("", 0, "face " + std::to_string(f) + " has decreasing offsets");
        }
    }
    const Label pointCount = mesh.pointCount();
    for (std::size_t i = 0; i < mesh.facePoints.size(); ++i) {
        if (mesh.facePoints[i] < 0 || mesh.facePoints[i] >= pointCount) {
            const auto at = std::upper_bound(mesh.faceOffsets.begin(), mesh.faceOffsets.end(), static_cast<Label>(i));
            throw InputError("", 0,
                             "face " + std::to_string(at - mesh.faceOffsets.begin() - 1) + " uses point "
                                 + std::to_string(mesh.facePoints[i]) + "; expected a label in [0, "
                                 + std::to_string(pointCount) + ")");
        }
    }
    for (Label f = 0; f < faceCount; ++f) {
        if (mesh.owner[f] < 0) throw InputError("", 0, "face " + std::to_string(f) + " has a negative owner");
    }
    for (Label f = 0; f < mesh.internalFaceCount(); ++f) {
        if (mesh.neighbour[f] < 0) throw InputError("", 0, "face " + std::to_string(f) + " has a negative neighbour");
    }
}

void exclusivePrefixSum(std::vector<Label>& counts)
{
    Label running = 0;
    for (Label& c : counts) {
        const Label n = c;
        c = running;
        running += n;
    }
}

std::string faceName(Label f) { return "face " + std::to_string(f); }
std::string cellName(Label c) { return "cell " + std::to_string(c); }

// Newell's area vector of a face (exact for planar polygons, a robust average otherwise).
Vector3 areaVector(const PolyMesh& mesh, std::span<const Label> face)
{
    Vector3 sum;
    for (std::size_t i = 0; i < face.size(); ++i) {
        sum += cross(mesh.points[face[i]], mesh.points[face[(i + 1) % face.size()]]);
    }
    return 0.5 * sum;
}

} // namespace

MeshTopology buildCellFaceTopology(const PolyMesh& mesh)
{
    requireIndexableMesh(mesh);
    MeshTopology topology;
    topology.pointCount = mesh.pointCount();
    topology.cellCount = mesh.cellCount();
    const Label cellCount = topology.cellCount;
    const Label faceCount = mesh.faceCount();
    const Label internalFaceCount = mesh.internalFaceCount();

    // cell → faces: count, prefix sum, fill in face order (so each cell's list is ascending).
    std::vector<Label> cursor(static_cast<std::size_t>(cellCount) + 1, 0);
    for (Label f = 0; f < faceCount; ++f) ++cursor[mesh.owner[f]];
    for (Label f = 0; f < internalFaceCount; ++f) ++cursor[mesh.neighbour[f]];
    exclusivePrefixSum(cursor);
    topology.cellFaceOffsets = cursor;
    topology.cellFaces.resize(static_cast<std::size_t>(topology.cellFaceOffsets.back()));
    for (Label f = 0; f < faceCount; ++f) {
        topology.cellFaces[cursor[mesh.owner[f]]++] = f;
        if (f < internalFaceCount) topology.cellFaces[cursor[mesh.neighbour[f]]++] = f;
    }
    return topology;
}

MeshTopology buildMeshTopology(const PolyMesh& mesh)
{
    MeshTopology topology = buildCellFaceTopology(mesh);
    const Label cellCount = topology.cellCount;

    // cell → unique points: a per-point stamp of the last cell that listed it removes
    // duplicates without a set; every face is visited by its owner and its neighbour.
    std::vector<Label> lastCell(static_cast<std::size_t>(topology.pointCount), -1);
    topology.cellPointOffsets.assign(1, 0);
    topology.cellPointOffsets.reserve(static_cast<std::size_t>(cellCount) + 1);
    topology.cellPoints.reserve(mesh.facePoints.size() / 2 + 16);
    for (Label c = 0; c < cellCount; ++c) {
        const auto begin = topology.cellPoints.size();
        for (Label f : topology.facesOf(c)) {
            for (Label p : mesh.face(f)) {
                if (lastCell[p] != c) {
                    lastCell[p] = c;
                    topology.cellPoints.push_back(p);
                }
            }
        }
        std::sort(topology.cellPoints.begin() + static_cast<std::ptrdiff_t>(begin), topology.cellPoints.end());
        topology.cellPointOffsets.push_back(static_cast<Label>(topology.cellPoints.size()));
    }

    // point → cells: counting sort of the cell → points lists (ascending cells per point).
    std::vector<Label> pointCursor(static_cast<std::size_t>(topology.pointCount) + 1, 0);
    for (Label p : topology.cellPoints) ++pointCursor[p];
    exclusivePrefixSum(pointCursor);
    topology.pointCellOffsets = pointCursor;
    topology.pointCells.resize(topology.cellPoints.size());
    for (Label c = 0; c < cellCount; ++c) {
        for (Label p : topology.pointsOf(c)) topology.pointCells[pointCursor[p]++] = c;
    }
    return topology;
}

void appendOutwardFace(const PolyMesh& mesh, Label face, Label cell, std::vector<Label>& out)
{
    const auto points = mesh.face(face);
    if (mesh.owner[face] == cell) {
        out.insert(out.end(), points.begin(), points.end());
    } else {
        out.insert(out.end(), points.rbegin(), points.rend());
    }
}

std::vector<std::string> checkPolyMeshOrdering(const PolyMesh& mesh, const TopologyCheckOptions& options)
{
    MeshTopology topology;
    return checkPolyMeshOrdering(mesh, options, topology);
}

namespace {

// The problems found, the first options.maxMessages of them as messages.
struct Problems {
    const TopologyCheckOptions& options;
    std::vector<std::string> messages;
    std::size_t count = 0;

    // Counts a problem; keeps its message while there is room.
    void report(std::string message)
    {
        ++count;
        if (messages.size() < options.maxMessages) messages.push_back(std::move(message));
    }

    // The messages, with a last one counting those left out.
    std::vector<std::string> finish()
    {
        if (count > messages.size()) {
            messages.push_back("... and " + std::to_string(count - messages.size()) + " more problems");
        }
        return messages;
    }
};

// Faces: at least 3 points, no point twice.
void checkFaces(const PolyMesh& mesh, Problems& problems)
{
    for (Label f = 0; f < mesh.faceCount(); ++f) {
        const auto face = mesh.face(f);
        if (face.size() < 3) {
            problems.report(faceName(f) + " has " + std::to_string(face.size()) + " points; expected at least 3");
            continue;
        }
        for (std::size_t i = 0; i < face.size(); ++i) {
            if (std::find(face.begin() + static_cast<std::ptrdiff_t>(i) + 1, face.end(), face[i]) != face.end()) {
                problems.report(faceName(f) + " uses point " + std::to_string(face[i]) + " more than once");
                break;
            }
        }
    }
}

// Internal faces: owner < neighbour, upper-triangular order.
void checkInternalFaceOrder(const PolyMesh& mesh, Problems& problems)
{
    for (Label f = 0; f < mesh.internalFaceCount(); ++f) {
        if (mesh.owner[f] >= mesh.neighbour[f]) {
            problems.report(faceName(f) + " has owner " + std::to_string(mesh.owner[f]) + " and neighbour "
                            + std::to_string(mesh.neighbour[f]) + "; expected owner < neighbour");
        }
        if (f > 0) {
            const std::pair previous{mesh.owner[f - 1], mesh.neighbour[f - 1]};
            const std::pair current{mesh.owner[f], mesh.neighbour[f]};
            if (current < previous) {
                problems.report(faceName(f) + " (owner " + std::to_string(current.first) + ", neighbour "
                                + std::to_string(current.second) + ") comes after face " + std::to_string(f - 1)
                                + " (owner " + std::to_string(previous.first) + ", neighbour "
                                + std::to_string(previous.second)
                                + "); internal faces must be sorted by owner, then neighbour (upper-triangular order)");
            }
        }
    }
}

// Patches: contiguous after the internal faces, covering every boundary face.
void checkPatches(const PolyMesh& mesh, Problems& problems)
{
    Label expectedStart = mesh.internalFaceCount();
    for (const Patch& patch : mesh.patches) {
        if (patch.faceCount < 0) {
            problems.report("patch '" + patch.name + "' has a negative number of faces");
        } else if (patch.startFace != expectedStart) {
            problems.report("patch '" + patch.name + "' starts at face " + std::to_string(patch.startFace) + "; expected "
                            + std::to_string(expectedStart)
                            + " (patches must follow each other after the internal faces)");
        }
        expectedStart = patch.startFace + std::max<Label>(patch.faceCount, 0);
    }
    if (expectedStart != mesh.faceCount()) {
        problems.report("the patches end at face " + std::to_string(expectedStart) + " but the mesh has "
                        + std::to_string(mesh.faceCount())
                        + " faces; every boundary face must belong to exactly one patch");
    }
}

// Directed edge a→b of one cell as the key a·2³² + b: the points are checked to be in
// [0, 2³¹) before, so the keys sort as the pairs (a, b) do, and sorting and searching
// 64-bit integers (one comparison each) is cheaper than sorting pairs. The messages are
// those of the pairs (malformedCaseTest); the check's share of a run is in
// docs/rbmMoveMesh.md, "Where a one-step run's time goes".
std::uint64_t edgeKey(Label a, Label b)
{
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Whether cell c is closed and consistently oriented: every directed edge of its outward
// faces once, and its reverse too. `edges` and `outward` are reused buffers.
bool checkCellClosed(const PolyMesh& mesh, Label c, std::span<const Label> faces, std::vector<std::uint64_t>& edges,
                     std::vector<Label>& outward, Problems& problems)
{
    edges.clear();
    for (Label f : faces) {
        outward.clear();
        appendOutwardFace(mesh, f, c, outward);
        for (std::size_t i = 0; i < outward.size(); ++i) {
            edges.push_back(edgeKey(outward[i], outward[(i + 1) % outward.size()]));
        }
    }
    std::sort(edges.begin(), edges.end());
    bool closed = true;
    for (std::size_t i = 0; i < edges.size() && closed; ++i) {
        const Label first = static_cast<Label>(edges[i] >> 32);
        const Label second = static_cast<Label>(edges[i] & 0xffffffffu);
        const bool repeated = i + 1 < edges.size() && edges[i] == edges[i + 1];
        const bool reversePresent = std::binary_search(edges.begin(), edges.end(), edgeKey(second, first));
        if (repeated || !reversePresent) {
            problems.report(cellName(c) + " is not closed or not consistently oriented: its edge "
                            + std::to_string(first) + "-" + std::to_string(second)
                            + (repeated ? " is used twice in the same direction"
                                        : " has no matching reversed edge on another of its faces")
                            + " (faces must point out of their owner and into their neighbour)");
            closed = false;
        }
    }
    return closed;
}

// Cell c's volume must be positive.
void checkCellVolume(const PolyMesh& mesh, const MeshTopology& topology, Label c, Problems& problems)
{
    // Volume by the divergence theorem about the cell's first point: positive when the
    // outward orientation really points outward.
    const Vector3 origin = mesh.points[topology.pointsOf(c).front()];
    double sixVolume = 0.0;
    for (Label f : topology.facesOf(c)) {
        const auto face = mesh.face(f);
        Vector3 centre;
        for (Label p : face) centre += mesh.points[p];
        centre /= static_cast<double>(face.size());
        const double sign = mesh.owner[f] == c ? 1.0 : -1.0;
        sixVolume += 2.0 * sign * dot(centre - origin, areaVector(mesh, face));
    }
    if (!(sixVolume > 0.0)) {
        problems.report(cellName(c) + " has volume " + std::to_string(sixVolume / 6.0)
                        + "; expected a positive volume (face normals must point from owner to neighbour and out of "
                          "the domain)");
    }
}

// Cells: at least 4 faces, closed and consistently oriented, and (if asked) of positive volume.
void checkCells(const PolyMesh& mesh, const MeshTopology& topology, Problems& problems)
{
    std::vector<std::uint64_t> edges;   // reused
    std::vector<Label> outward;
    for (Label c = 0; c < topology.cellCount; ++c) {
        const auto faces = topology.facesOf(c);
        if (faces.size() < 4) {
            problems.report(cellName(c) + " has " + std::to_string(faces.size()) + " faces; expected at least 4");
            continue;
        }
        const bool closed = checkCellClosed(mesh, c, faces, edges, outward, problems);
        if (!closed || !problems.options.checkCellVolumes) continue;
        checkCellVolume(mesh, topology, c, problems);
    }
}

} // namespace

std::vector<std::string> checkPolyMeshOrdering(const PolyMesh& mesh, const TopologyCheckOptions& options,
                                               MeshTopology& builtTopology)
{
    Problems problems{options, {}, 0};
    try {
        requireIndexableMesh(mesh);
    } catch (const InputError& error) {
        problems.report(error.message());
        return problems.finish();
    }
    checkFaces(mesh, problems);
    checkInternalFaceOrder(mesh, problems);
    checkPatches(mesh, problems);
    if (problems.count > 0) return problems.finish();   // the cell checks below assume sane faces

    builtTopology = buildMeshTopology(mesh);
    checkCells(mesh, builtTopology, problems);
    return problems.finish();
}

void validateTopology(const PolyMesh& mesh, const std::string& file, const TopologyCheckOptions& options)
{
    const auto messages = checkPolyMeshOrdering(mesh, options);
    if (messages.empty()) return;
    std::string text = "invalid polyMesh topology:";
    for (const auto& message : messages) text += "\n  " + message;
    throw InputError(file, 0, text);
}

} // namespace rbm
