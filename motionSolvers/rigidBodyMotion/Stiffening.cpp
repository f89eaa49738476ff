#include "Stiffening.hpp"

#include "ThreadCount.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string_view>

namespace rbm::motion {

namespace {

constexpr int leafSize = 4;

Vector3 closestPointOnSegment(const Vector3& p, const Vector3& a, const Vector3& b)
{
    const Vector3 ab = b - a;
    const double length2 = normSquared(ab);
    double t = length2 > 0.0 ? dot(p - a, ab) / length2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return a + t * ab;
}

double squaredPointSegment(const Vector3& p, const Vector3& a, const Vector3& b)
{
    return normSquared(p - closestPointOnSegment(p, a, b));
}

// Whether triangle abc is too thin for Ericson's regions: then its nearest point is its
// nearest edge's. A property of the triangle alone, so NearestSurface decides it once per
// primitive instead of at every query.
bool degenerateTriangle(const Vector3& a, const Vector3& b, const Vector3& c)
{
    const Vector3 ab = b - a;
    const Vector3 ac = c - a;
    return normSquared(cross(ab, ac)) <= 1e-30 * normSquared(ab) * normSquared(ac) || normSquared(ab) == 0.0 ||
           normSquared(ac) == 0.0;
}

Vector3 closestPointOnDegenerateTriangle(const Vector3& p, const Vector3& a, const Vector3& b, const Vector3& c)
{
    Vector3 best = closestPointOnSegment(p, a, b);
    for (const auto& [from, to] : {std::pair{b, c}, std::pair{c, a}}) {
        const Vector3 candidate = closestPointOnSegment(p, from, to);
        if (normSquared(p - candidate) < normSquared(p - best)) best = candidate;
    }
    return best;
}

// Closest point on the non-degenerate triangle abc to p (Ericson, Real-Time Collision
// Detection, §5.1.5).
Vector3 closestPointOnRegularTriangle(const Vector3& p, const Vector3& a, const Vector3& b, const Vector3& c)
{
    const Vector3 ab = b - a;
    const Vector3 ac = c - a;
    const Vector3 ap = p - a;
    const double d1 = dot(ab, ap);
    const double d2 = dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const Vector3 bp = p - b;
    const double d3 = dot(ab, bp);
    const double d4 = dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
    const Vector3 cp = p - c;
    const double d5 = dot(ab, cp);
    const double d6 = dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double denominator = 1.0 / (va + vb + vc);
    const double v = vb * denominator;
    const double w = vc * denominator;
    return a + v * ab + w * ac;
}

// Closest point on triangle abc to p; degenerate triangles fall back to their nearest edge.
Vector3 closestPointOnTriangle(const Vector3& p, const Vector3& a, const Vector3& b, const Vector3& c)
{
    return degenerateTriangle(a, b, c) ? closestPointOnDegenerateTriangle(p, a, b, c)
                                       : closestPointOnRegularTriangle(p, a, b, c);
}

// The squared distance from p to a box given in single precision (NearestSurface::Slot).
// A free function of this file so that the searches inline it (as a call it took a quarter
// of their time on the 10⁶-cell cube).
inline double squaredBoxDistance(const Vector3& p, const float* min, const float* max)
{
    const double gx = std::max(std::max(static_cast<double>(min[0]) - p.x, p.x - static_cast<double>(max[0])), 0.0);
    const double gy = std::max(std::max(static_cast<double>(min[1]) - p.y, p.y - static_cast<double>(max[1])), 0.0);
    const double gz = std::max(std::max(static_cast<double>(min[2]) - p.z, p.z - static_cast<double>(max[2])), 0.0);
    return gx * gx + gy * gy + gz * gz;
}

// Which way a primitive faces: the axis of its normal's largest component and that
// component's sign (0–5; a degenerate primitive: 0).
int facing(const Vector3& normal)
{
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(normal[k]) > std::abs(normal[axis])) axis = k;
    return 2 * axis + (normal[axis] < 0.0 ? 1 : 0);
}

} // namespace

void NearestSurface::addTriangle(const Vector3& a, const Vector3& b, const Vector3& c)
{
    primitives_.push_back({a, b, c, false, degenerateTriangle(a, b, c), facing(cross(b - a, c - a))});
}

void NearestSurface::addSegment(const Vector3& a, const Vector3& b)
{
    // Segments (2D) are split by position only: a curved boundary (an airfoil's) has no few
    // facings to separate, and splitting by facing makes stiffeningFactors slower there.
    primitives_.push_back({a, b, b, true, false, 0});
}

double NearestSurface::squaredDistance(const Primitive& primitive, const Vector3& point) const
{
    if (primitive.segment) return squaredPointSegment(point, primitive.a, primitive.b);
    return normSquared(point - (primitive.degenerate
                                    ? closestPointOnDegenerateTriangle(point, primitive.a, primitive.b, primitive.c)
                                    : closestPointOnRegularTriangle(point, primitive.a, primitive.b, primitive.c)));
}

Vector3 NearestSurface::nearestPoint(const Vector3& point, int& hint) const
{
    if (primitives_.empty()) return point;
    (void)distance(point, hint);
    const Primitive& nearest = primitives_[static_cast<std::size_t>(hint)];
    return nearest.segment ? closestPointOnSegment(point, nearest.a, nearest.b)
                           : closestPointOnTriangle(point, nearest.a, nearest.b, nearest.c);
}

void NearestSurface::build()
{
    pairs_.clear();
    root_ = {};
    if (primitives_.empty()) return;
    std::vector<Node> built;
    built.reserve(2 * primitives_.size() / leafSize + 2);
    built.emplace_back();
    const int root = 0;
    // Iterative build with an explicit stack of (node, begin, end).
    struct Task {
        int node, begin, end;
    };
    std::vector<Task> stack{{root, 0, static_cast<int>(primitives_.size())}};
    auto centroid = [](const Primitive& p) { return (p.a + p.b + p.c) / 3.0; };
    while (!stack.empty()) {
        const Task task = stack.back();
        stack.pop_back();
        Box box{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                 std::numeric_limits<double>::infinity()},
                {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                 -std::numeric_limits<double>::infinity()}};
        Box centres = box;
        for (int k = task.begin; k < task.end; ++k) {
            const Primitive& p = primitives_[k];
            for (const Vector3* v : {&p.a, &p.b, &p.c}) {
                for (int d = 0; d < 3; ++d) {
                    box.min[d] = std::min(box.min[d], (*v)[d]);
                    box.max[d] = std::max(box.max[d], (*v)[d]);
                }
            }
            const Vector3 c = centroid(p);
            for (int d = 0; d < 3; ++d) {
                centres.min[d] = std::min(centres.min[d], c[d]);
                centres.max[d] = std::max(centres.max[d], c[d]);
            }
        }
        built[task.node].box = box;
        if (task.end - task.begin <= leafSize) {
            built[task.node].first = task.begin;
            built[task.node].count = task.end - task.begin;
            continue;
        }
        // Primitives facing different ways are split by the way they face first, at the
        // boundary between two facings nearest to the middle: the boxes of a closed boundary
        // split by position contain the domain (the halves of a cube's six sides are
        // half-cubes), so a search from inside prunes nothing near the root, while the sides
        // facing one way each have a thin box. The distances are the same bits either way;
        // the search is cheaper on closed 3D boundaries (rbmBenchmark's twist3D case).
        // Otherwise: at the median of the centroids along the longest axis of their box.
        const auto first = primitives_.begin() + task.begin, last = primitives_.begin() + task.end;
        auto byFacing = [](const Primitive& l, const Primitive& r) { return l.facing < r.facing; };
        const auto [fewest, most] = std::minmax_element(first, last, byFacing);
        int middle = task.begin + (task.end - task.begin) / 2;
        if (fewest->facing != most->facing) {
            std::stable_sort(first, last, byFacing);
            int best = -1;
            for (int k = task.begin + 1; k < task.end; ++k) {
                const bool boundary = primitives_[k].facing != primitives_[k - 1].facing;
                if (boundary && (best < 0 || std::abs(k - middle) < std::abs(best - middle))) best = k;
            }
            middle = best;
        } else {
            int axis = 0;
            for (int d = 1; d < 3; ++d)
                if (centres.max[d] - centres.min[d] > centres.max[axis] - centres.min[axis]) axis = d;
            std::nth_element(first, primitives_.begin() + middle, last,
                             [&](const Primitive& l, const Primitive& r) { return centroid(l)[axis] < centroid(r)[axis]; });
        }
        const int left = static_cast<int>(built.size());
        built.emplace_back();
        built.emplace_back();
        built[task.node].first = left;
        built[task.node].count = 0;
        stack.push_back({left, task.begin, middle});
        stack.push_back({left + 1, middle, task.end});
    }
    root_ = compact(built, 0);
}

NearestSurface::Slot NearestSurface::compact(const std::vector<Node>& built, int index)
{
    // The box in single precision, rounded outwards: it contains the double box, so its
    // distance is never larger and no box is pruned that the exact one would keep.
    const Box& box = built[index].box;
    Slot slot;
    for (int d = 0; d < 3; ++d) {
        slot.min[d] = static_cast<float>(box.min[d]);
        if (static_cast<double>(slot.min[d]) > box.min[d]) slot.min[d] = std::nextafter(slot.min[d], -std::numeric_limits<float>::infinity());
        slot.max[d] = static_cast<float>(box.max[d]);
        if (static_cast<double>(slot.max[d]) < box.max[d]) slot.max[d] = std::nextafter(slot.max[d], std::numeric_limits<float>::infinity());
    }
    if (built[index].count > 0) {
        slot.first = built[index].first;
        slot.count = built[index].count;
        return slot;
    }
    // Depth first: a pair before its subtrees, the left subtree's pairs before the right's.
    const int pair = static_cast<int>(pairs_.size());
    pairs_.emplace_back();
    const Slot left = compact(built, built[index].first);
    const Slot right = compact(built, built[index].first + 1);
    pairs_[pair].child[0] = left;
    pairs_[pair].child[1] = right;
    slot.first = pair;
    slot.count = 0;
    return slot;
}

double NearestSurface::distance(const Vector3& point) const
{
    int hint = -1;
    return distance(point, hint);
}

double NearestSurface::distance(const Vector3& point, int& hint) const
{
    if (primitives_.empty()) return std::numeric_limits<double>::infinity();
    // The minimum over the primitives the search does not prune, which always include the
    // nearest: starting from the hint's distance (a primitive's, so ≥ the minimum) prunes
    // more and gives the same value.
    double best = std::numeric_limits<double>::infinity();
    int nearest = -1;
    if (hint >= 0 && hint < static_cast<int>(primitives_.size())) {
        best = squaredDistance(primitives_[hint], point);
        nearest = hint;
    }
    // Depth is O(log F); a small fixed stack avoids allocation per query. Each entry keeps
    // its box's squared distance, computed once when its parent is opened: a box is skipped
    // as soon as that distance is not below the best so far, when pushed or when popped.
    struct Pending {
        const Slot* slot;
        double squared;
    };
    Pending stack[128];
    int top = 0;
    stack[top++] = {&root_, squaredBoxDistance(point, root_.min, root_.max)};
    while (top > 0) {
        const Pending pending = stack[--top];
        if (pending.squared >= best) continue;
        const Slot& slot = *pending.slot;
        if (slot.count > 0) {
            for (int k = slot.first; k < slot.first + slot.count; ++k) {
                const double squared = squaredDistance(primitives_[k], point);
                nearest = squared < best ? k : nearest;
                best = std::min(best, squared);
            }
            continue;
        }
        // Visit the nearer child first (pushed last).
        const Pair& pair = pairs_[slot.first];
        const double dl = squaredBoxDistance(point, pair.child[0].min, pair.child[0].max);
        const double dr = squaredBoxDistance(point, pair.child[1].min, pair.child[1].max);
        if (top + 2 > 128) continue;  // cannot happen for a median-split tree of < 2^60 primitives
        const Pending near = dl < dr ? Pending{&pair.child[0], dl} : Pending{&pair.child[1], dr};
        const Pending far = dl < dr ? Pending{&pair.child[1], dr} : Pending{&pair.child[0], dl};
        if (far.squared < best) stack[top++] = far;
        if (near.squared < best) stack[top++] = near;
    }
    hint = nearest;
    return std::sqrt(best);
}

bool NearestSurface::primitivesWithin(const Vector3& point, double radius, std::vector<int>& found,
                                      std::size_t limit) const
{
    if (primitives_.empty()) return true;
    const double reach = radius * radius;
    const Slot* stack[128];
    int top = 0;
    stack[top++] = &root_;
    while (top > 0) {
        const Slot& slot = *stack[--top];
        if (squaredBoxDistance(point, slot.min, slot.max) > reach) continue;
        if (slot.count > 0) {
            for (int k = slot.first; k < slot.first + slot.count; ++k) {
                if (squaredDistance(primitives_[k], point) > reach) continue;
                if (found.size() >= limit) return false;
                found.push_back(k);
            }
            continue;
        }
        if (top + 2 > 128) continue;  // cannot happen for a median-split tree of < 2^60 primitives
        stack[top++] = &pairs_[slot.first].child[1];
        stack[top++] = &pairs_[slot.first].child[0];
    }
    return true;
}

std::vector<Label> automaticStiffeningPatches(const PolyMesh& mesh, std::span<const Label> faceCounts)
{
    static const std::array<std::string_view, 10> notABoundary{
        "empty",  "wedge",     "processor",  "processorCyclic", "cyclic",
        "cyclicAMI", "cyclicACMI", "cyclicSlip", "symmetryPlane", "symmetry"};
    std::vector<Label> patches;
    for (Label p = 0; p < static_cast<Label>(mesh.patches.size()); ++p) {
        const Patch& patch = mesh.patches[p];
        if ((faceCounts.empty() ? patch.faceCount : faceCounts[p]) == 0) continue;
        if (std::find(notABoundary.begin(), notABoundary.end(), patch.type) != notABoundary.end()) continue;
        patches.push_back(p);
    }
    return patches;
}

std::vector<double> patchTriangleCoordinates(const PolyMesh& mesh, std::span<const Vector3> points,
                                             std::span<const Label> patches)
{
    std::vector<double> coordinates;
    auto add = [&](const Vector3& a, const Vector3& b, const Vector3& c) {
        for (const Vector3* v : {&a, &b, &c}) coordinates.insert(coordinates.end(), {v->x, v->y, v->z});
    };
    for (Label patchIndex : patches) {
        const Patch& patch = mesh.patches[patchIndex];
        for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
            const auto face = mesh.face(f);
            if (face.size() == 3) {
                add(points[face[0]], points[face[1]], points[face[2]]);
                continue;
            }
            Vector3 centre;
            for (Label p : face) centre += points[p];
            centre /= static_cast<double>(face.size());
            for (std::size_t k = 0; k < face.size(); ++k) add(points[face[k]], points[face[(k + 1) % face.size()]], centre);
        }
    }
    return coordinates;
}

NearestSurface triangleSurface(std::span<const double> c)
{
    NearestSurface surface;
    for (std::size_t k = 0; k + 9 <= c.size(); k += 9)
        surface.addTriangle({c[k], c[k + 1], c[k + 2]}, {c[k + 3], c[k + 4], c[k + 5]}, {c[k + 6], c[k + 7], c[k + 8]});
    surface.build();
    return surface;
}

NearestSurface patchSurface(const PolyMesh& mesh, std::span<const Vector3> points, std::span<const Label> patches)
{
    return triangleSurface(patchTriangleCoordinates(mesh, points, patches));
}

NearestSurface patchSurface(const PlanarMesh& planar, std::span<const Label> planarPatches)
{
    NearestSurface surface;
    for (Label patchIndex : planarPatches) {
        const PlanarPatch& patch = planar.patches[patchIndex];
        for (Label e = patch.startEdge; e < patch.startEdge + patch.edgeCount; ++e) {
            const auto [a, b] = planar.edge(e);
            Vector3 pa = planar.points[a];
            Vector3 pb = planar.points[b];
            pa.z = pb.z = 0.0;
            surface.addSegment(pa, pb);
        }
    }
    surface.build();
    return surface;
}

double shortestGraphEdge(const CellNeighbourGraph& graph, std::span<const Vector3> points, int dimension)
{
    auto position = [&](Label node) {
        Vector3 p = points[node];
        if (dimension == 2) p.z = 0.0;
        return p;
    };
    const Label nodeCount = graph.nodeCount();
    // A minimum does not depend on the order it is taken in.
    double shortest = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) reduction(min : shortest) if (worthThreading(graph.neighbours.size()))
    for (Label i = 0; i < nodeCount; ++i)
        for (Label e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
            shortest = std::min(shortest, norm(position(graph.neighbours[e]) - position(i)));
    return shortest;
}

std::vector<double> stiffeningFactors(const CellNeighbourGraph& graph, std::span<const Vector3> points, int dimension,
                                      const NearestSurface& surface, double exponent, double shortestEdge)
{
    std::vector<double> factors(graph.neighbours.size(), 1.0);
    if (exponent == 0.0 || surface.empty()) return factors;
    auto position = [&](Label node) {
        Vector3 p = points[node];
        if (dimension == 2) p.z = 0.0;
        return p;
    };
    const Label nodeCount = graph.nodeCount();
    const double shortest = std::isnan(shortestEdge) ? shortestGraphEdge(graph, points, dimension) : shortestEdge;
    if (!(shortest > 0.0) || !std::isfinite(shortest)) return factors;
    // Each edge pair i < j is set by row i, in both directions: every factor has one writer.
    auto setFactor = [&](Label i, Label e, double distanceToSurface) {
        const Label j = graph.neighbours[e];
        const double d = std::max(distanceToSurface, shortest);
        const double ratio = shortest / d;
        const double factor = exponent == 1.0   ? ratio
                              : exponent == 2.0 ? ratio * ratio
                                                : std::pow(ratio, exponent);
        factors[e] = factor;
        // The reverse edge j → i.
        const auto row = graph.neighboursOf(j);
        const auto found = std::lower_bound(row.begin(), row.end(), i);
        factors[graph.offsets[j] + (found - row.begin())] = factor;
    };
    // The midpoints m of node i's edges lie within ρ (the farthest one's distance) of p_i. If
    // primitive h is at distance d_h from p_i, each m has a primitive within d_h + ρ, and its
    // nearest primitive lies within that of m, so within d_h + 2ρ of p_i: the candidates,
    // found with one search per node instead of one per edge. The radius is widened by 1e-9
    // of itself and of the coordinates, far more than the rounding of the distances, so
    // that none is dropped. The minimum over the candidates is the minimum over all
    // primitives, the same number the hierarchy's search gives. Far from the patches a node
    // sees many primitives within that radius: above `candidateLimit` its edges are searched
    // one by one, starting from the last nearest primitive (consecutive midpoints are close).
    // The result is the same bits as a search per edge. Near the patches the candidate lists
    // are short and the searches cheap; far from them a node sees many primitives, and the
    // limit keeps it from testing them all (limits from 8 to 48 do about equally well on the
    // airfoil; the cost of the whole: docs/motionSolver.md, "Default stiffening").
    // A node farther than 4ρ from its hint's primitive does not look for candidates: the
    // sphere of radius d_h + 2ρ cuts a surface in a disc of radius about 2√(d_h ρ), which
    // holds more than the limit there, so collecting candidates up to the limit would be
    // wasted work.
    // In 3D no node collects candidates: a node's 13 midpoints (a hexahedral mesh's) times
    // up to 24 triangles cost more than 13 searches of the compact hierarchy, each bounded by
    // the last nearest triangle; on the 10⁶-cell cube the factors took 5.1–5.9 s without
    // candidates against 6.1–8.5 s with them (three alternating runs on a loaded machine).
    // In 2D the candidates still win (the airfoil's 818 segments: 0.036–0.042 s against
    // 0.044–0.062 s searching each edge).
    const bool collectCandidates = dimension == 2;
    constexpr std::size_t candidateLimit = 24;
    constexpr double candidateReach = 4.0;
#pragma omp parallel if (worthThreading(graph.neighbours.size()))
    {
    int hint = -1;
    std::vector<int> candidates;
    candidates.reserve(candidateLimit);
#pragma omp for schedule(static)
    for (Label i = 0; i < nodeCount; ++i) {
        const Vector3 pi = position(i);
        double reach = 0.0;
        bool setsAny = false;
        for (Label e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const Label j = graph.neighbours[e];
            if (j < i) continue;
            setsAny = true;
            reach = std::max(reach, norm(0.5 * (pi + position(j)) - pi));
        }
        if (!setsAny) continue;   // every edge of i was set by an earlier row
        bool few = false;
        if (collectCandidates) {
            const double fromHint =
                hint >= 0 ? std::sqrt(surface.squaredDistanceTo(hint, pi)) : surface.distance(pi, hint);
            const double radius = fromHint + 2.0 * reach;
            const double scale = std::max({std::abs(pi.x), std::abs(pi.y), std::abs(pi.z), radius});
            candidates.clear();
            few = fromHint <= candidateReach * reach &&
                  surface.primitivesWithin(pi, radius * (1.0 + 1e-9) + 1e-9 * scale, candidates, candidateLimit);
        }
        for (Label e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const Label j = graph.neighbours[e];
            if (j < i) continue;  // set both directions from the i < j one: exactly symmetric
            const Vector3 midpoint = 0.5 * (pi + position(j));
            if (!few) {
                setFactor(i, e, surface.distance(midpoint, hint));
                continue;
            }
            double best = std::numeric_limits<double>::infinity();
            for (const int k : candidates) {
                const double squared = surface.squaredDistanceTo(k, midpoint);
                hint = squared < best ? k : hint;
                best = std::min(best, squared);
            }
            setFactor(i, e, std::sqrt(best));
        }
    }
    }
    return factors;
}

} // namespace rbm::motion
