#include "PlanarReducedKernels.hpp"

#include "ReadAhead.hpp"
#include "ThreadCount.hpp"

#include <cmath>
#include <stdexcept>

namespace rbm::motion {

namespace {
// The passes below stream the edge records (32 bytes each, 10 MB on the 40k-node airfoil) and
// request them this far ahead (ReadAhead.hpp); 1 to 4 KB do equally well on the airfoil
// pitching series (rbmBenchmark --cases airfoil).
constexpr std::ptrdiff_t edgeLookaheadBytes = 2048;
} // namespace

PlanarReducedKernels::PlanarReducedKernels(const RbmProblem& problem, NeighbourhoodScaling scaling)
    : problem_(problem), unknownCount_(problem.unknownNodeCount()), scaling_(scaling)
{
    if (problem.dimension() != 2) throw std::invalid_argument("PlanarReducedKernels: the problem is not planar");
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<Vector3>& x = problem.referencePoints();
    const std::vector<int>& nodes = problem.unknownNodes();
    const std::vector<int>& unknownIndex = problem.unknownIndex();
    const int m = unknownCount_;
    offsets_.assign(m + 1, 0);
    for (int a = 0; a < m; ++a)
        offsets_[a + 1] = offsets_[a] + (graph.offsets[nodes[a] + 1] - graph.offsets[nodes[a]]);
    edges_.resize(offsets_[m]);
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        for (int e = graph.offsets[i], position = offsets_[a]; e < graph.offsets[i + 1]; ++e, ++position) {
            const int j = graph.neighbours[e];
            edges_[position] = {x[j].x - x[i].x, x[j].y - x[i].y, problem.edgeWeights()[e], j,
                                unknownIndex[j] >= 0 ? unknownIndex[j] : m};
        }
    }
    // S v below takes q_back of edge a→j from j's rotation and −d, which needs the graph to be
    // symmetric: every unknown neighbour j of a has a among its neighbours.
    for (int a = 0; a < m; ++a)
        for (int position = offsets_[a]; position < offsets_[a + 1]; ++position) {
            const int b = edges_[position].compact;
            if (b == m) continue;
            bool found = false;
            for (int back = offsets_[b]; back < offsets_[b + 1] && !found; ++back) found = edges_[back].compact == a;
            if (!found) throw std::invalid_argument("PlanarReducedKernels: the graph is not symmetric");
        }
    weightedRotated_.assign(2 * edges_.size(), 0.0f);
    weightedBackRotated_.assign(2 * edges_.size(), 0.0f);
    laplacianWeight_.resize(edges_.size());
    compact_.resize(edges_.size());
    for (std::size_t position = 0; position < edges_.size(); ++position) {
        compact_[position] = edges_[position].compact;
        laplacianWeight_[position] = static_cast<float>((edges_[position].compact != m ? 2.0 : 1.0) * edges_[position].weight);
    }
    inverseCurvature_.assign(m, 0.0);
    inverseStretchCurvature_.assign(m, 0.0);
    weightedSquaredLengths_.assign(m, 0.0);
    for (int a = 0; a < m; ++a)
        for (int position = offsets_[a]; position < offsets_[a + 1]; ++position) {
            const Edge& edge = edges_[position];
            weightedSquaredLengths_[a] += edge.weight * (edge.dx * edge.dx + edge.dy * edge.dy);
        }
    nodeEnergy_.assign(m, 0.0);
    padded_.assign(2 * static_cast<std::size_t>(m) + 2, 0.0);
    turn_.assign(static_cast<std::size_t>(m) + 1, 0.0);
    stretch_.assign(static_cast<std::size_t>(m) + 1, 0.0);
}

template <typename Body>
void PlanarReducedKernels::forEachUnknownNode(Body&& body) const
{
    constexpr auto recordBytes = static_cast<std::ptrdiff_t>(sizeof(Edge));
#pragma omp parallel if (worthThreading(edges_.size()))
    {
        // One per thread: a statically scheduled thread reads its own run of nodes.
        ReadAhead ahead(edges_.data(), static_cast<std::ptrdiff_t>(edges_.size()) * recordBytes, edgeLookaheadBytes);
#pragma omp for schedule(static)
        for (int a = 0; a < unknownCount_; ++a) {
            ahead.reach(offsets_[a] * recordBytes, offsets_[a + 1] * recordBytes);
            body(a);
        }
    }
}

double PlanarReducedKernels::fitAndEnergy(std::span<const Vector3> displacement, std::vector<Matrix3>& rotations)
{
    rotations.resize(problem_.nodeCount(), Matrix3::identity());
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int m = unknownCount_;
    const Edge* edges = edges_.data();
    forEachUnknownNode([&](int a) {
        const int i = nodes[a];
        const double ux = displacement[i].x, uy = displacement[i].y;
        double crossSum = 0.0, dotSum = 0.0;
        for (int position = offsets_[a]; position < offsets_[a + 1]; ++position) {
            const Edge& edge = edges[position];
            const double ex = edge.dx + displacement[edge.node].x - ux;
            const double ey = edge.dy + displacement[edge.node].y - uy;
            crossSum += edge.weight * (edge.dx * ey - edge.dy * ex);
            dotSum += edge.weight * (edge.dx * ex + edge.dy * ey);
        }
        // The planar local step (LocalGlobalSolver: bestPlanarAngle, atan2(cross, dot)), as its
        // cosine and sine directly: one square root instead of atan2, cos and sin, in a step
        // that runs for every node each time the rotations are fitted.
        const double length = std::sqrt(crossSum * crossSum + dotSum * dotSum);
        // With scaling, the fit is the similarity scale × rotation (NeighbourhoodScaling.hpp),
        // kept in rotations as the scaled matrix: ∇Ẽ and S read s R d from it unchanged.
        const double scale = scaling_.scale(length, weightedSquaredLengths_[a]);
        const double c = scale * (length > 0.0 ? dotSum / length : 1.0);
        const double s = scale * (length > 0.0 ? crossSum / length : 0.0);
        double energy = scaling_.penalty(scale, weightedSquaredLengths_[a]);
        for (int position = offsets_[a]; position < offsets_[a + 1]; ++position) {
            const Edge& edge = edges[position];
            const double rx = edge.dx + displacement[edge.node].x - ux - (c * edge.dx - s * edge.dy);
            const double ry = edge.dy + displacement[edge.node].y - uy - (s * edge.dx + c * edge.dy);
            energy += edge.weight * (rx * rx + ry * ry);
        }
        nodeEnergy_[a] = energy;
        Matrix3& r = rotations[i];
        r = Matrix3::identity();
        r.m[0][0] = c;
        r.m[0][1] = -s;
        r.m[1][0] = s;
        r.m[1][1] = c;
    });
    double sum = 0.0;
    for (int a = 0; a < m; ++a) sum += nodeEnergy_[a];
    return 0.5 * sum;
}

namespace {
// (cos, sin) per node from the rotation matrices, into cosineSine (2 per node).
void gatherCosineSine(std::span<const Matrix3> rotations, std::vector<double>& cosineSine)
{
    cosineSine.resize(2 * rotations.size());
    for (std::size_t node = 0; node < rotations.size(); ++node) {
        cosineSine[2 * node] = rotations[node].m[0][0];
        cosineSine[2 * node + 1] = rotations[node].m[1][0];
    }
}
} // namespace

void PlanarReducedKernels::gradient(std::span<const Vector3> displacement, std::span<const Matrix3> rotations,
                                    std::span<double> g) const
{
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int m = unknownCount_;
    const Edge* edges = edges_.data();
    gatherCosineSine(rotations, cosineSine_);
    const double* cs = cosineSine_.data();
    forEachUnknownNode([&](int a) {
        const int k = nodes[a];
        const double ux = displacement[k].x, uy = displacement[k].y;
        const double c = cs[2 * static_cast<std::size_t>(k)], s = cs[2 * static_cast<std::size_t>(k) + 1];
        double gx = 0.0, gy = 0.0;
        for (int position = offsets_[a]; position < offsets_[a + 1]; ++position) {
            const Edge& edge = edges[position];
            const bool unknown = edge.compact != m;
            const double both = unknown ? 2.0 : 1.0;
            // (1 + t)(u_k − u_j − d) + R_k d + t R_j d
            double tx = both * (ux - displacement[edge.node].x - edge.dx) + c * edge.dx - s * edge.dy;
            double ty = both * (uy - displacement[edge.node].y - edge.dy) + s * edge.dx + c * edge.dy;
            if (unknown) {
                const double cj = cs[2 * static_cast<std::size_t>(edge.node)], sj = cs[2 * static_cast<std::size_t>(edge.node) + 1];
                tx += cj * edge.dx - sj * edge.dy;
                ty += sj * edge.dx + cj * edge.dy;
            }
            gx += edge.weight * tx;
            gy += edge.weight * ty;
        }
        g[2 * static_cast<std::size_t>(a)] = gx;
        g[2 * static_cast<std::size_t>(a) + 1] = gy;
    });
}

void PlanarReducedKernels::prepareHessian(std::span<const Vector3> displacement, std::span<const Matrix3> rotations)
{
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int m = unknownCount_;
    const Edge* edges = edges_.data();
    float* weighted = weightedRotated_.data();
    float* weightedBack = weightedBackRotated_.data();
    gatherCosineSine(rotations, cosineSine_);
    const double* cs = cosineSine_.data();
    forEachUnknownNode([&](int a) {
        const int i = nodes[a];
        const double ux = displacement[i].x, uy = displacement[i].y;
        const double c = cs[2 * static_cast<std::size_t>(i)], s = cs[2 * static_cast<std::size_t>(i) + 1];
        double curvature = 0.0;
        for (int position = offsets_[a]; position < offsets_[a + 1]; ++position) {
            const Edge& edge = edges[position];
            const double qx = c * edge.dx - s * edge.dy;
            const double qy = s * edge.dx + c * edge.dy;
            const double ex = edge.dx + displacement[edge.node].x - ux;
            const double ey = edge.dy + displacement[edge.node].y - uy;
            curvature += edge.weight * (qx * ex + qy * ey);
            // w q and w q_back, q_back = R_j d_ji = −R_j d (zero for a prescribed j): once per
            // Newton step instead of once per CG iteration.
            weighted[2 * static_cast<std::size_t>(position)] = static_cast<float>(edge.weight * qx);
            weighted[2 * static_cast<std::size_t>(position) + 1] = static_cast<float>(edge.weight * qy);
            double backX = 0.0, backY = 0.0;
            if (edge.compact != m) {
                const double cj = cs[2 * static_cast<std::size_t>(edge.node)], sj = cs[2 * static_cast<std::size_t>(edge.node) + 1];
                backX = -(cj * edge.dx - sj * edge.dy);
                backY = -(sj * edge.dx + cj * edge.dy);
            }
            weightedBack[2 * static_cast<std::size_t>(position)] = static_cast<float>(edge.weight * backX);
            weightedBack[2 * static_cast<std::size_t>(position) + 1] = static_cast<float>(edge.weight * backY);
        }
        // At a best fit H_δδ ≥ 0; where it is not positive the node's turn is left out (S = K
        // there), which keeps S positive definite and the step a descent direction.
        inverseCurvature_[a] = curvature > 0.0 ? 1.0 / curvature : 0.0;
        inverseStretchCurvature_[a] = scaling_.inverseScaledCurvature(std::hypot(c, s), weightedSquaredLengths_[a]);
    });
}

void PlanarReducedKernels::applyHessian(std::span<const double> v, std::span<double> y)
{
    const int m = unknownCount_;
    if (v.size() != 2 * static_cast<std::size_t>(m) || y.size() != v.size())
        throw std::invalid_argument("PlanarReducedKernels: applyHessian with vectors of the wrong size");
    double* padded = padded_.data();  // the zero slot m stays zero
    for (std::size_t k = 0; k < v.size(); ++k) padded[k] = v[k];
    // Rigid neighbourhoods (the default) skip the scales' terms: S v is CG's inner loop.
    if (scaling_.rigid()) applyHessianPasses<false>(y);
    else applyHessianPasses<true>(y);
}

template <bool scaled>
void PlanarReducedKernels::applyHessianPasses(std::span<double> y)
{
    const int m = unknownCount_;
    const double* padded = padded_.data();
    const int* compact = compact_.data();
    const float* weighted = weightedRotated_.data();
    const float* weightedBack = weightedBackRotated_.data();
    const float* laplacianWeight = laplacianWeight_.data();
    const int* offsets = offsets_.data();
    double* turn = turn_.data();        // the zero slot m stays zero
    double* stretch = stretch_.data();  // the scales' change per node; the zero slot m stays zero
#pragma omp parallel for schedule(static) if (worthThreading(compact_.size()))
    for (int a = 0; a < m; ++a) {
        const double vx = padded[2 * a], vy = padded[2 * a + 1];
        double b = 0.0, along = 0.0;
        for (int position = offsets[a]; position < offsets[a + 1]; ++position) {
            const double* vj = padded + 2 * static_cast<std::size_t>(compact[position]);
            const float* wq = weighted + 2 * static_cast<std::size_t>(position);
            b += wq[0] * (vj[1] - vy) - wq[1] * (vj[0] - vx);
            if constexpr (scaled) along += wq[0] * (vj[0] - vx) + wq[1] * (vj[1] - vy);
        }
        turn[a] = inverseCurvature_[a] * b;
        if constexpr (scaled) stretch[a] = inverseStretchCurvature_[a] * along;
    }
#pragma omp parallel for schedule(static) if (worthThreading(compact_.size()))
    for (int a = 0; a < m; ++a) {
        const double vx = padded[2 * a], vy = padded[2 * a + 1];
        const double ya = turn[a];
        double sx = 0.0, sy = 0.0;
        for (int position = offsets[a]; position < offsets[a + 1]; ++position) {
            const int j = compact[position];
            const double* vj = padded + 2 * static_cast<std::size_t>(j);
            const float* wq = weighted + 2 * static_cast<std::size_t>(position);
            const float* wqBack = weightedBack + 2 * static_cast<std::size_t>(position);
            const double yj = turn[j];
            // (1 + t)(v_a − v_j) + y_a ẑ × q − t y_j ẑ × q_back, ẑ × q = (−q_y, q_x), all times
            // w; the zero slot and the zero w q_back make the last term vanish for a
            // prescribed neighbour.
            sx += laplacianWeight[position] * (vx - vj[0]) - ya * wq[1] + yj * wqBack[1];
            sy += laplacianWeight[position] * (vy - vj[1]) + ya * wq[0] - yj * wqBack[0];
            if constexpr (scaled) {  // the scales' terms z_a q − t z_j q_back (s w R d kept)
                sx += stretch[a] * wq[0] - stretch[j] * wqBack[0];
                sy += stretch[a] * wq[1] - stretch[j] * wqBack[1];
            }
        }
        y[2 * static_cast<std::size_t>(a)] = sx;
        y[2 * static_cast<std::size_t>(a) + 1] = sy;
    }
}

} // namespace rbm::motion
