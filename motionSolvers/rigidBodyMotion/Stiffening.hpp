#pragma once
// Edge stiffening near chosen patches, the RBM counterpart of OpenFOAM's
// `inverseDistance` / `quadratic inverseDistance` motion diffusivities: the weight w_ij of
// every graph edge is multiplied by
//
//     f_ij = (h_min / d_ij)^k,     d_ij = max(distance(midpoint of i–j, patches), h_min)
//
// with k = 1 (inverseDistance), 2 (quadratic inverseDistance) or any k > 0 (power k
// inverseDistance; docs/motionSolver.md has the measured choices), the distance measured in
// the reference mesh to the nearest face of the patches (2D: the nearest boundary edge in
// the plane), and h_min the shortest edge of the mesh, so that f ≤ 1 and the edges touching
// the patches keep their weight while edges far away count less: the mesh near the patches
// moves more rigidly.
//
// Distances come from a bounding-volume hierarchy over the patch faces (triangulated about
// their centres) or edges: O(log F) per edge, no O(N·F) scan. In 3D its first splits separate
// the faces by the way they face (NearestSurface::build), so that the boxes near its root are
// thin sides and not the domain they enclose. The searches read it in a compact form (boxes
// in single precision rounded outwards, two to a cache line) and give exactly the distances
// of a brute-force minimum over all primitives.

#include "CellNeighbourGraph.hpp"
#include "PlanarMesh.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <limits>
#include <span>
#include <vector>

namespace rbm::motion {

// Nearest distance from a point to a set of triangles and segments.
class NearestSurface {
public:
    void addTriangle(const Vector3& a, const Vector3& b, const Vector3& c);
    void addSegment(const Vector3& a, const Vector3& b);
    // Builds the hierarchy; call after the last add and before distance().
    void build();

    bool empty() const { return primitives_.empty(); }
    std::size_t size() const { return primitives_.size(); }
    // Euclidean distance to the nearest primitive (+∞ when there is none).
    double distance(const Vector3& point) const;
    // The same distance, to the last bit, faster for a point near the one before: `hint` is the
    // nearest primitive of an earlier query (-1: none), whose distance bounds the search from
    // the start; it receives this query's nearest primitive.
    double distance(const Vector3& point, int& hint) const;
    // The nearest point of the surface to `point` (`point` itself when there is no primitive);
    // `hint` as for distance().
    Vector3 nearestPoint(const Vector3& point, int& hint) const;

    // The indices of the primitives whose squared distance from `point` is at most
    // radius², appended to `found` in the hierarchy's order; false (and `found` left
    // incomplete) as soon as it would hold more than `limit`.
    bool primitivesWithin(const Vector3& point, double radius, std::vector<int>& found, std::size_t limit) const;
    // The squared distance from `point` to primitive `index` (0 ≤ index < size()), the very
    // number distance() takes the minimum of.
    double squaredDistanceTo(int index, const Vector3& point) const { return squaredDistance(primitives_[index], point); }

private:
    struct Primitive {
        Vector3 a, b, c;
        bool segment = false;
        bool degenerate = false;  // a triangle too thin for Ericson's regions: nearest edge
        int facing = 0;  // the axis and sign of its normal's largest component (build's first splits)
    };
    struct Box {
        Vector3 min, max;
    };
    struct Node {
        Box box;
        int first = 0;  // leaf: primitives [first, first + count); inner: children first and first + 1 (node indices)
        int count = 0;  // 0 for inner nodes
    };
    // The searches' form of the hierarchy: a child's box in single precision, rounded
    // outwards (it contains the exact box, so it prunes nothing the exact one would keep and
    // the distances are the same bits), and what it holds; two children to a 64-byte pair,
    // one cache line per inner node opened. The build's tree in double precision took two
    // or three, and with the 2.4·10⁵ primitives of the 10⁶-cell cube the searches waited on
    // memory: this form made stiffeningFactors 1.3–1.5× faster there.
    struct Slot {
        float min[3] = {0.0f, 0.0f, 0.0f}, max[3] = {0.0f, 0.0f, 0.0f};
        int first = 0;  // leaf: primitives [first, first + count); inner: the index of its pair
        int count = 0;  // 0 for inner nodes
    };
    struct alignas(64) Pair {
        Slot child[2];
    };
    double squaredDistance(const Primitive& primitive, const Vector3& point) const;
    Slot compact(const std::vector<Node>& built, int index);

    std::vector<Primitive> primitives_;
    Slot root_;                 // the whole hierarchy
    std::vector<Pair> pairs_;   // the inner nodes, depth first
};

// The faces of the given 3D patches (indices into mesh.patches), each triangulated about the
// average of its points, at positions `points`.
NearestSurface patchSurface(const PolyMesh& mesh, std::span<const Vector3> points, std::span<const Label> patches);
// The boundary edges of the given planar patches (indices into planar.patches).
NearestSurface patchSurface(const PlanarMesh& planar, std::span<const Label> planarPatches);

// The patches `stiffening auto` (the default) measures the distance to: every patch with
// faces that is a boundary of the domain of its own, i.e. whose type is not `empty`, `wedge`
// (the 2D planes), `processor`/`processorCyclic` (a cut between ranks), `cyclic`/`cyclicAMI`/
// `cyclicACMI`/`cyclicSlip` (coupled to another patch) or `symmetryPlane`/`symmetry` (a mirror:
// the mirrored domain has no boundary there, and a one-layer 3D mesh between two mirror planes
// must move as its 2D form does): moving, fixed, free and slip patches alike.
// Indices into mesh.patches, in order. `faceCounts`: per patch, its faces in the whole mesh when
// `mesh` is one rank's part (a patch with no face here may have faces on other ranks); empty:
// the mesh's own.
std::vector<Label> automaticStiffeningPatches(const PolyMesh& mesh, std::span<const Label> faceCounts = {});

// f_ij per directed edge of `graph` (same order as graph.neighbours), see the file comment.
// 2D (dimension 2) uses the x and y of the points only. exponent 0 gives all ones; 1 and 2
// are computed without std::pow (the same bits as the integer-exponent formulas).
// In 2D the midpoints of a node's edges are searched together: the primitives that can be
// nearest to any of them lie within d + 2ρ of the node (d: its distance to a primitive, ρ: the
// farthest midpoint), found once; each midpoint's distance is the minimum over those, the
// same number a search of the whole hierarchy gives (tested against brute force). In 3D each
// midpoint is searched on its own (cheaper there; Stiffening.cpp has the figures).
// `shortestEdge`: h_min when the graph is one rank's part of a larger mesh (the shortest edge
// over all ranks); NaN: the graph's own shortest edge.
std::vector<double> stiffeningFactors(const CellNeighbourGraph& graph, std::span<const Vector3> points, int dimension,
                                      const NearestSurface& surface, double exponent,
                                      double shortestEdge = std::numeric_limits<double>::quiet_NaN());
// The shortest edge of the graph (the h_min of the factors above).
double shortestGraphEdge(const CellNeighbourGraph& graph, std::span<const Vector3> points, int dimension);
// The triangles patchSurface makes of the faces of the given 3D patches, as 9 coordinates
// each (a, b, c), for a surface gathered from the parts of a decomposed mesh.
std::vector<double> patchTriangleCoordinates(const PolyMesh& mesh, std::span<const Vector3> points,
                                             std::span<const Label> patches);
// The surface of such triangles (9 coordinates each), built.
NearestSurface triangleSurface(std::span<const double> coordinates);

} // namespace rbm::motion
