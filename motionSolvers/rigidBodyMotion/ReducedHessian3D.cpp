#include "ReducedHessian3D.hpp"

#include "NodeExchange.hpp"
#include "ThreadCount.hpp"
#include "VectorInstructions.hpp"


#include <stdexcept>

namespace rbm::motion {

namespace {

using Symmetric3 = std::array<double, 6>;  // 00 01 02 11 12 22

Vector3 times(const Symmetric3& s, const Vector3& v)
{
    return {s[0] * v.x + s[1] * v.y + s[2] * v.z, s[1] * v.x + s[3] * v.y + s[4] * v.z,
            s[2] * v.x + s[4] * v.y + s[5] * v.z};
}

// The inverses of ReducedNewtonSolver.cpp (same tests, same zero map where H is not positive):
// n nᵀ / (nᵀ H n) at mirror nodes, else H⁻¹ by cofactors if H is positive definite.
Symmetric3 axisInverse(const Symmetric3& h, const Vector3& n)
{
    const double curvature = dot(n, times(h, n));
    if (!(curvature > 0.0)) return {};
    return {n.x * n.x / curvature, n.x * n.y / curvature, n.x * n.z / curvature,
            n.y * n.y / curvature, n.y * n.z / curvature, n.z * n.z / curvature};
}

Symmetric3 symmetricInverse(const Symmetric3& h)
{
    const double m0 = h[0], m1 = h[1], m2 = h[2], m4 = h[3], m5 = h[4], m8 = h[5];
    const double c00 = m4 * m8 - m5 * m5;
    const double c01 = m5 * m2 - m1 * m8;
    const double c02 = m1 * m5 - m4 * m2;
    const double determinant = m0 * c00 + m1 * c01 + m2 * c02;
    const double scale = (m0 + m4 + m8) / 3.0;
    const double minor2 = m0 * m4 - m1 * m1;
    if (!(m0 > 0.0) || !(minor2 > 0.0) || !(determinant > 1e-12 * scale * scale * scale)) return {};
    return {c00 / determinant, c01 / determinant, c02 / determinant, (m0 * m8 - m2 * m2) / determinant,
            (m2 * m1 - m0 * m5) / determinant, (m0 * m4 - m1 * m1) / determinant};
}

Vector3 rotate(const Matrix3& r, const Vector3& v)
{
    return {r.m[0][0] * v.x + r.m[0][1] * v.y + r.m[0][2] * v.z, r.m[1][0] * v.x + r.m[1][1] * v.y + r.m[1][2] * v.z,
            r.m[2][0] * v.x + r.m[2][1] * v.y + r.m[2][2] * v.z};
}

} // namespace

ReducedHessian3D::ReducedHessian3D(const RbmProblem& problem) : problem_(problem)
{
    if (problem.dimension() != 3) throw std::invalid_argument("ReducedHessian3D: a 3D problem is needed");
    const std::size_t m = static_cast<std::size_t>(problem.unknownNodeCount());
    const std::size_t n = static_cast<std::size_t>(problem.nodeCount());
    diagonal_.assign(m, 0.0);
    position_.assign(n, AlignedDouble4{});
    for (std::size_t i = 0; i < n; ++i) {
        const Vector3& point = problem.referencePoints()[i];
        position_[i].value = Double4{point.x, point.y, point.z, 0.0};
    }
    // The per-solve arrays come with the first prepare(): not alive through the set-up and the
    // first solve's start.
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<int>& nodes = problem.unknownNodes();
    for (std::size_t a = 0; a < m; ++a) {
        const int i = nodes[a];
        double sum = 0.0;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
            sum += problem.edgeWeights()[e] * (problem.isUnknown(graph.neighbours[e]) ? 2.0 : 1.0);
        diagonal_[a] = sum;
    }
}

void ReducedHessian3D::allocateSolveData()
{
    const std::size_t m = static_cast<std::size_t>(problem_.unknownNodeCount());
    const std::size_t n = static_cast<std::size_t>(problem_.nodeCount());
    inverse_.assign(m, {});
    rotatedSum_.assign(m, Vector3{});
    ownTerm_.assign(m, Vector3{});
    // Zero at the prescribed nodes, which prepare() and apply() never write.
    nodeVector_.assign(n, AlignedDouble4{});
    nodeMap_.assign(3 * n, AlignedDouble4{});
    projected_.reserve(3 * m);
}

void ReducedHessian3D::release()
{
    std::vector<std::array<double, 6>>().swap(inverse_);
    std::vector<Vector3>().swap(rotatedSum_);
    std::vector<Vector3>().swap(ownTerm_);
    std::vector<AlignedDouble4>().swap(nodeVector_);
    std::vector<AlignedDouble4>().swap(nodeMap_);
    std::vector<double>().swap(projected_);
    rotations_ = {};
}

void ReducedHessian3D::prepare(std::span<const Vector3> displacement, std::span<const Matrix3> rotations)
{
    if (inverse_.size() != static_cast<std::size_t>(problem_.unknownNodeCount()) ||
        nodeMap_.size() != 3 * static_cast<std::size_t>(problem_.nodeCount()))
        allocateSolveData();
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const std::vector<double>& weights = problem_.edgeWeights();
    const int m = problem_.ownedUnknownCount();
    rotations_ = rotations;
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        const Matrix3& r = rotations[i];
        // H_δδ = Σ w [(q·e) I − (e qᵀ + q eᵀ)/2], q = R_i d, e = d + u_j − u_i
        Symmetric3 h{};
        Vector3 weightedSum{};
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            const Vector3 d = x[j] - x[i];
            const Vector3 edge = d + (displacement[j] - displacement[i]);
            const Vector3 q = rotate(r, d);
            const double w = weights[e];
            const double qe = dot(q, edge);
            h[0] += w * (qe - edge.x * q.x);
            h[1] -= w * 0.5 * (edge.x * q.y + q.x * edge.y);
            h[2] -= w * 0.5 * (edge.x * q.z + q.x * edge.z);
            h[3] += w * (qe - edge.y * q.y);
            h[4] -= w * 0.5 * (edge.y * q.z + q.y * edge.z);
            h[5] += w * (qe - edge.z * q.z);
            weightedSum += w * d;
        }
        rotatedSum_[a] = rotate(r, weightedSum);
        inverse_[a] = problem_.rotatesAboutNormalOnly(i) ? axisInverse(h, problem_.slidingNormal(i)) : symmetricInverse(h);
    }
}

namespace {

using Double4 = ReducedHessian3D::Double4;
using AlignedDouble4 = ReducedHessian3D::AlignedDouble4;

// The two edge passes of apply over unknown nodes [begin, end), written once and compiled twice
// (below): for AVX2, where a Double4 is one register, and for the baseline x86-64 (SSE2), where
// GCC keeps Double4 sums in memory and the kernel is markedly slower than scalar code (it is
// the fallback for CPUs without AVX2, not the fast path). No FMA in either (AVX2 without -mfma), so both
// round alike, lane by lane as the scalar formulas.
struct PassData {
    const int* nodes;
    const int* offsets;
    const int* neighbours;
    const double* weights;
    const AlignedDouble4* position;
    const AlignedDouble4* vector;
    AlignedDouble4* map;
    const Matrix3* rotation;  // per node
    const std::array<double, 6>* inverse;
    const Vector3* rotatedSum;
    Vector3* ownTerm;
    const double* diagonal;
    double* y;
};

// y_i = H⁻¹ axial(R_i T_i), M_i = [y_i]× R_i, y_i × c_i
[[gnu::always_inline]] inline void firstPass(const PassData& data, int begin, int end)
{
    for (int a = begin; a < end; ++a) {
        const int i = data.nodes[a];
        const Double4 xi = data.position[i].value;
        const Double4 vi = data.vector[i].value;
        // Row p of T = Σ w d (v_j − v_i)ᵀ: Σ (w d_p) (v_j − v_i).
        Double4 t0{}, t1{}, t2{};
        for (int e = data.offsets[i]; e < data.offsets[i + 1]; ++e) {
            const int j = data.neighbours[e];
            const Double4 d = data.weights[e] * (data.position[j].value - xi);
            const Double4 dv = data.vector[j].value - vi;
            t0 += d[0] * dv;
            t1 += d[1] * dv;
            t2 += d[2] * dv;
        }
        const double t[9] = {t0[0], t0[1], t0[2], t1[0], t1[1], t1[2], t2[0], t2[1], t2[2]};
        const Matrix3& r = data.rotation[i];
        // A = R T; b = axial(A)
        auto entry = [&](int p, int q) { return r.m[p][0] * t[q] + r.m[p][1] * t[3 + q] + r.m[p][2] * t[6 + q]; };
        const Vector3 b{entry(1, 2) - entry(2, 1), entry(2, 0) - entry(0, 2), entry(0, 1) - entry(1, 0)};
        const Vector3 yi = times(data.inverse[a], b);
        for (int q = 0; q < 3; ++q) {
            const Vector3 column = cross(yi, Vector3{r.m[0][q], r.m[1][q], r.m[2][q]});
            data.map[3 * static_cast<std::size_t>(i) + q].value = Double4{column.x, column.y, column.z, 0.0};
        }
        data.ownTerm[a] = cross(yi, data.rotatedSum[a]);
    }
}

// (S v)_k = D_k v_k − 2 Σ_j w v_j + y_k × c_k + Σ_j w M_j d_kj
[[gnu::always_inline]] inline void secondPass(const PassData& data, int begin, int end)
{
    for (int a = begin; a < end; ++a) {
        const int k = data.nodes[a];
        const Double4 xk = data.position[k].value;
        Double4 neighbours{}, maps{};
        for (int e = data.offsets[k]; e < data.offsets[k + 1]; ++e) {
            const int j = data.neighbours[e];
            const double w = data.weights[e];
            const Double4 d = data.position[j].value - xk;
            const AlignedDouble4* mj = data.map + 3 * static_cast<std::size_t>(j);
            neighbours += w * data.vector[j].value;
            maps += w * (mj[0].value * d[0] + mj[1].value * d[1] + mj[2].value * d[2]);
        }
        const Double4 vk = data.vector[k].value;
        const std::size_t row = static_cast<std::size_t>(a) * 3;
        for (int q = 0; q < 3; ++q)
            data.y[row + q] = data.diagonal[a] * vk[q] - 2.0 * neighbours[q] + data.ownTerm[a][q] + maps[q];
    }
}

#if defined(__x86_64__)
#define RBM_AVX2_TARGET [[gnu::target("avx2")]]
#else
#define RBM_AVX2_TARGET  // other processors: the same code twice (useAvxKernels() is false there)
#endif
RBM_AVX2_TARGET void firstPassAvx(const PassData& data, int begin, int end) { firstPass(data, begin, end); }
RBM_AVX2_TARGET void secondPassAvx(const PassData& data, int begin, int end) { secondPass(data, begin, end); }
#undef RBM_AVX2_TARGET
void firstPassBaseline(const PassData& data, int begin, int end) { firstPass(data, begin, end); }
void secondPassBaseline(const PassData& data, int begin, int end) { secondPass(data, begin, end); }

} // namespace

void ReducedHessian3D::apply(std::span<const double> v, std::span<double> y)
{
    if (inverse_.empty() && problem_.unknownNodeCount() > 0)
        throw std::logic_error("ReducedHessian3D::apply: prepare() first (the data was released)");
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int m = problem_.unknownNodeCount();
    projected_.assign(v.begin(), v.end());
    problem_.projectSliding(projected_, 3);
    // Prescribed entries of nodeVector_ and nodeMap_ stay zero.
    for (int a = 0; a < m; ++a) {
        const std::size_t k = static_cast<std::size_t>(a) * 3;
        nodeVector_[nodes[a]].value = Double4{projected_[k], projected_[k + 1], projected_[k + 2], 0.0};
    }
    const NodeExchange* exchange = problem_.nodeExchange();
    const auto asDoubles = [](std::vector<AlignedDouble4>& values) {
        return std::span<double>(reinterpret_cast<double*>(values.data()), values.size() * 4);
    };
    // A part: the ghosts' v from their owners before the first pass, their M after it; both
    // passes cover the owned rows only.
    if (exchange) exchange->updateGhosts(asDoubles(nodeVector_), 4);
    const int owned = problem_.ownedUnknownCount();
    const PassData data{nodes.data(),       graph.offsets.data(), graph.neighbours.data(), problem_.edgeWeights().data(),
                        position_.data(),   nodeVector_.data(),   nodeMap_.data(),         rotations_.data(),
                        inverse_.data(),    rotatedSum_.data(),   ownTerm_.data(),         diagonal_.data(),
                        y.data()};
    const bool threads = worthThreading(graph.neighbours.size());
    const bool avx = useAvxKernels();
    forEachThreadRange(owned, threads, [&](int begin, int end) {
        if (avx) firstPassAvx(data, begin, end);
        else firstPassBaseline(data, begin, end);
    });
    if (exchange) exchange->updateGhosts(asDoubles(nodeMap_), 12);
    std::fill(y.begin() + static_cast<std::ptrdiff_t>(owned) * 3, y.end(), 0.0);
    forEachThreadRange(owned, threads, [&](int begin, int end) {
        if (avx) secondPassAvx(data, begin, end);
        else secondPassBaseline(data, begin, end);
    });
    problem_.projectSliding(y, 3);
}

} // namespace rbm::motion
