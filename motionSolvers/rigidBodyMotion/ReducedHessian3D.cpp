#include "ReducedHessian3D.hpp"

#include "ThreadCount.hpp"

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

Vector3 rotate(const std::array<double, 9>& r, const Vector3& v)
{
    return {r[0] * v.x + r[1] * v.y + r[2] * v.z, r[3] * v.x + r[4] * v.y + r[5] * v.z,
            r[6] * v.x + r[7] * v.y + r[8] * v.z};
}

} // namespace

ReducedHessian3D::ReducedHessian3D(const RbmProblem& problem) : problem_(problem)
{
    if (problem.dimension() != 3) throw std::invalid_argument("ReducedHessian3D: a 3D problem is needed");
    const std::size_t m = static_cast<std::size_t>(problem.unknownNodeCount());
    const std::size_t n = static_cast<std::size_t>(problem.nodeCount());
    rotation_.assign(m, {});
    inverse_.assign(m, {});
    rotatedSum_.assign(m, Vector3{});
    diagonal_.assign(m, 0.0);
    ownTerm_.assign(m, Vector3{});
    nodeVector_.assign(n, Vector3{});
    nodeMap_.assign(n, {});
    projected_.reserve(3 * m);
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

void ReducedHessian3D::prepare(std::span<const Vector3> displacement, std::span<const Matrix3> rotations)
{
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const std::vector<double>& weights = problem_.edgeWeights();
    const int m = problem_.unknownNodeCount();
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        std::array<double, 9>& r = rotation_[a];
        for (int p = 0; p < 3; ++p)
            for (int q = 0; q < 3; ++q) r[3 * p + q] = rotations[i].m[p][q];
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

void ReducedHessian3D::apply(std::span<const double> v, std::span<double> y)
{
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const std::vector<double>& weights = problem_.edgeWeights();
    const int m = problem_.unknownNodeCount();
    projected_.assign(v.begin(), v.end());
    problem_.projectSliding(projected_, 3);
    // Prescribed entries of nodeVector_ and nodeMap_ stay zero.
    for (int a = 0; a < m; ++a) {
        const std::size_t k = static_cast<std::size_t>(a) * 3;
        nodeVector_[nodes[a]] = Vector3{projected_[k], projected_[k + 1], projected_[k + 2]};
    }
    // y_i = H⁻¹ axial(R_i T_i), M_i = [y_i]× R_i, y_i × c_i
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        const Vector3 xi = x[i];
        const Vector3 vi = nodeVector_[i];
        double t[9] = {};  // T = Σ w d (v_j − v_i)ᵀ, row-major
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            const double w = weights[e];
            const Vector3 d = w * (x[j] - xi);
            const Vector3 dv = nodeVector_[j] - vi;
            t[0] += d.x * dv.x, t[1] += d.x * dv.y, t[2] += d.x * dv.z;
            t[3] += d.y * dv.x, t[4] += d.y * dv.y, t[5] += d.y * dv.z;
            t[6] += d.z * dv.x, t[7] += d.z * dv.y, t[8] += d.z * dv.z;
        }
        const std::array<double, 9>& r = rotation_[a];
        // A = R T; b = axial(A)
        auto entry = [&](int p, int q) { return r[3 * p] * t[q] + r[3 * p + 1] * t[3 + q] + r[3 * p + 2] * t[6 + q]; };
        const Vector3 b{entry(1, 2) - entry(2, 1), entry(2, 0) - entry(0, 2), entry(0, 1) - entry(1, 0)};
        const Vector3 yi = times(inverse_[a], b);
        std::array<double, 9>& map = nodeMap_[i];
        for (int q = 0; q < 3; ++q) {
            const Vector3 column = cross(yi, Vector3{r[q], r[3 + q], r[6 + q]});
            map[q] = column.x, map[3 + q] = column.y, map[6 + q] = column.z;
        }
        ownTerm_[a] = cross(yi, rotatedSum_[a]);
    }
    // (S v)_k = D_k v_k − 2 Σ_j w v_j + y_k × c_k + Σ_j w M_j d_kj
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int k = nodes[a];
        const Vector3 xk = x[k];
        Vector3 neighbours{}, maps{};
        for (int e = graph.offsets[k]; e < graph.offsets[k + 1]; ++e) {
            const int j = graph.neighbours[e];
            const double w = weights[e];
            neighbours += w * nodeVector_[j];
            maps += w * rotate(nodeMap_[j], x[j] - xk);
        }
        const Vector3 sum = diagonal_[a] * nodeVector_[k] - 2.0 * neighbours + ownTerm_[a] + maps;
        const std::size_t row = static_cast<std::size_t>(a) * 3;
        y[row] = sum.x, y[row + 1] = sum.y, y[row + 2] = sum.z;
    }
    problem_.projectSliding(y, 3);
}

} // namespace rbm::motion
