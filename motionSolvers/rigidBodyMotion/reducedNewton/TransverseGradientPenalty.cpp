#include "TransverseGradientPenalty.hpp"

#include "ThreadCount.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rbm::motion {

TransverseGradientPenalty::TransverseGradientPenalty(const RbmProblem& problem, double stiffness)
    : problem_(problem), stiffness_(stiffness)
{
    if (!(stiffness >= 0.0) || !std::isfinite(stiffness))
        throw std::invalid_argument("transverseStiffness must be a number ≥ 0");
    if (stiffness > 0.0 && problem.isPart())
        throw std::invalid_argument("transverseStiffness is implemented for serial problems only, not one rank's part");
}

void TransverseGradientPenalty::setDirection(const Vector3& direction)
{
    Vector3 m = direction;
    if (problem_.dimension() == 2) m.z = 0.0;
    const double length = norm(m);
    if (stiffness_ == 0.0 || !(length > 0.0)) {
        active_ = false;
        return;
    }
    m = m / length;
    // −m and m give the same E_t (a and g change sign together): the same line, nothing to do.
    if (active_ && (norm(m - direction_) < 1e-12 || norm(m + direction_) < 1e-12)) return;
    direction_ = m;
    active_ = true;
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const std::vector<double>& w = problem_.edgeWeights();
    const int n = problem_.nodeCount();
    along_.assign(graph.neighbours.size(), 0.0);
    inverseMoments_.assign(static_cast<std::size_t>(n), 0.0);
    sums_.assign(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i) {
        double moment = 0.0, lengthScale = 0.0, sum = 0.0;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            Vector3 d = x[graph.neighbours[e]] - x[i];
            if (problem_.dimension() == 2) d.z = 0.0;
            along_[e] = dot(d, m);                      // a_ij
            moment += w[e] * along_[e] * along_[e];     // A_i, (T2)
            lengthScale += w[e] * normSquared(d);
            sum += w[e] * along_[e];                    // σ_i
        }
        // A_i = 0 (every edge across m): no fit, the first sum of E_i alone.
        inverseMoments_[i] = moment > 1e-14 * lengthScale ? 1.0 / moment : 0.0;
        sums_[i] = sum;
    }
    fits_.assign(static_cast<std::size_t>(n), Vector3{});
}

void TransverseGradientPenalty::fitAll(std::span<const Vector3> field) const
{
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<double>& w = problem_.edgeWeights();
    const int n = problem_.nodeCount();
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int i = 0; i < n; ++i) {
        Vector3 b{};
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
            b += (w[e] * along_[e]) * (field[graph.neighbours[e]] - field[i]);
        fits_[i] = inverseMoments_[i] * b;  // g_i = b_i / A_i
    }
}

void TransverseGradientPenalty::addTransposed(std::span<const Vector3> field, std::span<double> y) const
{
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<double>& w = problem_.edgeWeights();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int count = problem_.unknownNodeCount();
    const int dim = problem_.dimension();
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < count; ++a) {
        const int k = nodes[a];
        // (T3): 2 Σ_j w (u_k − u_j) + Σ_j w a_kj g_j + σ_k g_k.
        Vector3 sum = sums_[k] * fits_[k];
        for (int e = graph.offsets[k]; e < graph.offsets[k + 1]; ++e) {
            const int j = graph.neighbours[e];
            sum += (2.0 * w[e]) * (field[k] - field[j]) + (w[e] * along_[e]) * fits_[j];
        }
        for (int q = 0; q < dim; ++q) y[static_cast<std::size_t>(a) * dim + q] += stiffness_ * sum[q];
    }
}

double TransverseGradientPenalty::energy(std::span<const Vector3> displacement) const
{
    if (!active_) return 0.0;
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<double>& w = problem_.edgeWeights();
    const int n = problem_.nodeCount();
    const bool planar = problem_.dimension() == 2;
    double total = 0.0;
    for (int i = 0; i < n; ++i) {
        double squares = 0.0;
        Vector3 b{};
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            Vector3 relative = displacement[graph.neighbours[e]] - displacement[i];
            if (planar) relative.z = 0.0;
            squares += w[e] * normSquared(relative);
            b += (w[e] * along_[e]) * relative;
        }
        total += squares - inverseMoments_[i] * normSquared(b);  // E_i
    }
    return 0.5 * stiffness_ * total;  // (T1)
}

void TransverseGradientPenalty::addGradient(std::span<const Vector3> displacement, std::span<double> g) const
{
    if (!active_) return;
    if (problem_.dimension() == 2) {
        field_.assign(displacement.begin(), displacement.end());
        for (Vector3& u : field_) u.z = 0.0;
        fitAll(field_);
        addTransposed(field_, g);
        return;
    }
    fitAll(displacement);
    addTransposed(displacement, g);
}

void TransverseGradientPenalty::addHessianProduct(std::span<const double> v, std::span<double> y) const
{
    if (!active_) return;
    const int dim = problem_.dimension();
    field_.assign(static_cast<std::size_t>(problem_.nodeCount()), Vector3{});
    const std::vector<int>& nodes = problem_.unknownNodes();
    for (int a = 0; a < problem_.unknownNodeCount(); ++a)
        for (int q = 0; q < dim; ++q) field_[nodes[a]][q] = v[static_cast<std::size_t>(a) * dim + q];
    fitAll(field_);
    addTransposed(field_, y);
}

Vector3 TransverseGradientPenalty::commonTranslation(const RbmProblem& problem,
                                                     std::span<const Vector3> prescribedDisplacement)
{
    double largest = 0.0;
    for (int node = 0; node < problem.nodeCount(); ++node)
        if (!problem.isUnknown(node)) largest = std::max(largest, norm(prescribedDisplacement[node]));
    if (!(largest > 0.0)) return {};
    Vector3 common{};
    bool first = true;
    for (int node = 0; node < problem.nodeCount(); ++node) {
        if (problem.isUnknown(node)) continue;
        const Vector3& u = prescribedDisplacement[node];
        if (norm(u) <= 1e-12 * largest) continue;
        if (first) {
            common = u;
            first = false;
        } else if (norm(u - common) > 1e-9 * norm(common)) {
            return {};
        }
    }
    return common;
}

Vector3 TransverseGradientPenalty::translationTowardsFixedWalls(const RbmProblem& problem,
                                                               std::span<const Vector3> prescribedDisplacement)
{
    const Vector3 common = commonTranslation(problem, prescribedDisplacement);
    if (common == Vector3{}) return {};
    Vector3 m = common;
    if (problem.dimension() == 2) m.z = 0.0;
    if (!(norm(m) > 0.0)) return {};
    m = m / norm(m);
    const double moving = 1e-12 * norm(common);
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<Vector3>& x = problem.referencePoints();
    for (int i = 0; i < problem.nodeCount(); ++i) {
        if (problem.isUnknown(i) || norm(prescribedDisplacement[i]) > moving) continue;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            if (j < i || problem.isUnknown(j) || norm(prescribedDisplacement[j]) > moving) continue;
            Vector3 d = x[j] - x[i];
            if (problem.dimension() == 2) d.z = 0.0;
            if (std::abs(dot(d, m)) > 0.01 * norm(d)) return {};
        }
    }
    return common;
}

} // namespace rbm::motion
