#include "RbmEnergy.hpp"

#include "ThreadCount.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rbm::motion {

namespace {

Matrix3 operator+(Matrix3 a, const Matrix3& b)
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a.m[i][j] += b.m[i][j];
    return a;
}

Matrix3 operator*(double s, Matrix3 a)
{
    for (auto& row : a.m)
        for (double& value : row) value *= s;
    return a;
}

// u vᵀ
Matrix3 outer(const Vector3& u, const Vector3& v)
{
    Matrix3 result;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) result.m[i][j] = u[i] * v[j];
    return result;
}

Vector3 unitVector(int k)
{
    Vector3 e;
    e[k] = 1.0;
    return e;
}

// Rodrigues' coefficients as functions of s = |ω|²: R = I + A(s) [ω]× + B(s) [ω]×², with
// A = sin t / t and B = (1 − cos t)/t², t = √s, and their first two s-derivatives.
// Below s = 1 the closed forms cancel badly, so the (fast converging) series is used.
struct RodriguesCoefficients {
    double a = 1.0, aS = 0.0, aSS = 0.0;
    double b = 0.5, bS = 0.0, bSS = 0.0;
};

RodriguesCoefficients rodriguesCoefficients(double s)
{
    RodriguesCoefficients c;
    if (s < 1.0) {
        // A = Σ (−1)^k s^k / (2k+1)!,  B = Σ (−1)^k s^k / (2k+2)!
        c = RodriguesCoefficients{0, 0, 0, 0, 0, 0};
        double factorialA = 1.0;  // (2k+1)!
        double factorialB = 2.0;  // (2k+2)!
        double power = 1.0;       // s^k
        double powerMinus1 = 0.0; // s^(k−1)
        double powerMinus2 = 0.0; // s^(k−2)
        for (int k = 0; k <= 12; ++k) {
            const double sign = (k % 2 == 0) ? 1.0 : -1.0;
            const double coefficientA = sign / factorialA;
            const double coefficientB = sign / factorialB;
            c.a += coefficientA * power;
            c.b += coefficientB * power;
            c.aS += k * coefficientA * powerMinus1;
            c.bS += k * coefficientB * powerMinus1;
            c.aSS += k * (k - 1) * coefficientA * powerMinus2;
            c.bSS += k * (k - 1) * coefficientB * powerMinus2;
            powerMinus2 = powerMinus1;
            powerMinus1 = (k == 0) ? 1.0 : powerMinus1 * s;
            power *= s;
            factorialA *= (2.0 * k + 2.0) * (2.0 * k + 3.0);
            factorialB *= (2.0 * k + 3.0) * (2.0 * k + 4.0);
        }
        return c;
    }
    const double t = std::sqrt(s);
    const double sine = std::sin(t);
    const double cosine = std::cos(t);
    const double t2 = s, t3 = s * t, t4 = s * s, t5 = t4 * t, t6 = t4 * s;
    c.a = sine / t;
    c.b = (1.0 - cosine) / t2;
    c.aS = (t * cosine - sine) / (2.0 * t3);
    c.bS = (t * sine - 2.0 * (1.0 - cosine)) / (2.0 * t4);
    c.aSS = (-t2 * sine - 3.0 * t * cosine + 3.0 * sine) / (4.0 * t5);
    c.bSS = (t2 * cosine - 5.0 * t * sine + 8.0 - 8.0 * cosine) / (4.0 * t6);
    return c;
}

} // namespace

Matrix3 planarRotation(double angle)
{
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    return {{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}}};
}

Matrix3 rotationFromVector(const Vector3& w)
{
    const RodriguesCoefficients c = rodriguesCoefficients(normSquared(w));
    const Matrix3 k = crossMatrix(w);
    return Matrix3::identity() + c.a * k + c.b * (k * k);
}

Vector3 rotationVectorFromMatrix(const Matrix3& r)
{
    // Via the unit quaternion (Shepperd's method: pivot on the largest of 4 candidates).
    const auto& m = r.m;
    const double trace = m[0][0] + m[1][1] + m[2][2];
    double w, x, y, z;
    if (trace >= m[0][0] && trace >= m[1][1] && trace >= m[2][2]) {
        const double s = 2.0 * std::sqrt(std::max(0.0, 1.0 + trace));
        w = 0.25 * s;
        x = (m[2][1] - m[1][2]) / s;
        y = (m[0][2] - m[2][0]) / s;
        z = (m[1][0] - m[0][1]) / s;
    } else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
        const double s = 2.0 * std::sqrt(std::max(0.0, 1.0 + m[0][0] - m[1][1] - m[2][2]));
        w = (m[2][1] - m[1][2]) / s;
        x = 0.25 * s;
        y = (m[0][1] + m[1][0]) / s;
        z = (m[0][2] + m[2][0]) / s;
    } else if (m[1][1] >= m[2][2]) {
        const double s = 2.0 * std::sqrt(std::max(0.0, 1.0 + m[1][1] - m[0][0] - m[2][2]));
        w = (m[0][2] - m[2][0]) / s;
        x = (m[0][1] + m[1][0]) / s;
        y = 0.25 * s;
        z = (m[1][2] + m[2][1]) / s;
    } else {
        const double s = 2.0 * std::sqrt(std::max(0.0, 1.0 + m[2][2] - m[0][0] - m[1][1]));
        w = (m[1][0] - m[0][1]) / s;
        x = (m[0][2] + m[2][0]) / s;
        y = (m[1][2] + m[2][1]) / s;
        z = 0.25 * s;
    }
    if (w < 0.0) { w = -w; x = -x; y = -y; z = -z; }  // angle in [0, π]
    const double vectorNorm = std::sqrt(x * x + y * y + z * z);
    if (vectorNorm == 0.0) return {};
    const double angle = 2.0 * std::atan2(vectorNorm, w);
    return Vector3{x, y, z} * (angle / vectorNorm);
}

RotationDerivatives rotationDerivatives(int dimension, RotationModel model, const double* parameters)
{
    RotationDerivatives result;
    if (dimension == 2) {
        const double theta = parameters[0];
        if (model == RotationModel::smallAngle) {
            // R ≈ I + θ [e_z]× (eq 2.48: sin θ → θ, cos θ → 1), linear in θ.
            result.rotation = Matrix3::identity() + theta * crossMatrix({0, 0, 1});
            result.first[0] = crossMatrix({0, 0, 1});
        } else {
            const double c = std::cos(theta);
            const double s = std::sin(theta);
            result.rotation = {{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}}};
            result.first[0] = {{{{-s, -c, 0}, {c, -s, 0}, {0, 0, 0}}}};
            result.second[0] = {{{{-c, s, 0}, {-s, -c, 0}, {0, 0, 0}}}};
        }
        return result;
    }
    const Vector3 w{parameters[0], parameters[1], parameters[2]};
    if (model == RotationModel::smallAngle) {
        // R ≈ I + [ω]× (eq 2.92): linear, no second derivatives.
        result.rotation = Matrix3::identity() + crossMatrix(w);
        for (int k = 0; k < 3; ++k) result.first[k] = crossMatrix(unitVector(k));
        return result;
    }
    // R = I + A K + B K², K = [ω]×, K² = ω ωᵀ − s I, s = |ω|², A and B functions of s:
    //   ∂_k A = 2 A' ω_k,   ∂_kl A = 4 A'' ω_k ω_l + 2 A' δ_kl   (same for B)
    //   ∂_k K = E_k = [e_k]×,   ∂_k K² = e_k ωᵀ + ω e_kᵀ − 2 ω_k I,   ∂_kl K² = e_k e_lᵀ + e_l e_kᵀ − 2 δ_kl I
    const double s = normSquared(w);
    const RodriguesCoefficients c = rodriguesCoefficients(s);
    const Matrix3 k = crossMatrix(w);
    const Matrix3 k2 = outer(w, w) + (-s) * Matrix3::identity();
    result.rotation = Matrix3::identity() + c.a * k + c.b * k2;
    std::array<Matrix3, 3> e;
    std::array<Matrix3, 3> dk2;
    std::array<double, 3> da, db;
    for (int q = 0; q < 3; ++q) {
        const Vector3 unit = unitVector(q);
        e[q] = crossMatrix(unit);
        dk2[q] = outer(unit, w) + outer(w, unit) + (-2.0 * w[q]) * Matrix3::identity();
        da[q] = 2.0 * c.aS * w[q];
        db[q] = 2.0 * c.bS * w[q];
        result.first[q] = da[q] * k + c.a * e[q] + db[q] * k2 + c.b * dk2[q];
    }
    for (int p = 0; p < 3; ++p) {
        for (int q = p; q < 3; ++q) {
            const double delta = (p == q) ? 1.0 : 0.0;
            const double dda = 4.0 * c.aSS * w[p] * w[q] + 2.0 * c.aS * delta;
            const double ddb = 4.0 * c.bSS * w[p] * w[q] + 2.0 * c.bS * delta;
            const Vector3 ep = unitVector(p), eq = unitVector(q);
            const Matrix3 ddk2 = outer(ep, eq) + outer(eq, ep) + (-2.0 * delta) * Matrix3::identity();
            result.second[symmetricIndex(p, q)] = dda * k + da[p] * e[q] + da[q] * e[p] + ddb * k2 + db[p] * dk2[q] +
                                                  db[q] * dk2[p] + c.b * ddk2;
        }
    }
    return result;
}

RbmEnergy::RbmEnergy(const RbmProblem& problem, RotationModel model, std::span<const Vector3> prescribedDisplacement)
    : problem_(problem), model_(model), prescribed_(prescribedDisplacement.begin(), prescribedDisplacement.end())
{
    problem.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    if (problem.dimension() == 2)
        for (Vector3& u : prescribed_) u.z = 0.0;
}

namespace {

// The terms of edge (i → j) in centre i's rotation rows and columns of its diagonal block:
// (u_i, φ_i), (φ_i, u_i) from a_k = ∂R/∂φ_k d, and (φ_i, φ_i) = w (a_k·a_l − r·∂²R/∂φ_k∂φ_l d).
void addRotationBlocks(double* hii, int bs, int dim, int rotationCount, const std::array<Vector3, 3>& derivative,
                       const RotationDerivatives& rotation, const Vector3& r, const Vector3& d, double w,
                       bool includeCurvature)
{
    for (int k = 0; k < rotationCount; ++k) {
        for (int q = 0; q < dim; ++q) {
            hii[q * bs + dim + k] += w * derivative[k][q];
            hii[(dim + k) * bs + q] += w * derivative[k][q];
        }
        for (int l = 0; l < rotationCount; ++l) {
            const double curvature = includeCurvature ? dot(r, rotation.second[symmetricIndex(k, l)] * d) : 0.0;
            hii[(dim + k) * bs + dim + l] += w * (dot(derivative[k], derivative[l]) - curvature);
        }
    }
}

// Position of the first edge i → j with j > i (the end of i's row if there is none).
int firstEdgeAfter(const CellNeighbourGraph& graph, int i)
{
    const auto row = graph.neighboursOf(i);
    return graph.offsets[i] + static_cast<int>(std::upper_bound(row.begin(), row.end(), i) - row.begin());
}

// One pass over all edges (i → j), i unknown, computing whatever is asked for:
//   r = u_j − u_i + d − R_i d,  d = x_j − x_i,  a_k = ∂(R_i d)/∂φ_k,  C_kl = rᵀ ∂²(R_i d)/∂φ_k∂φ_l
//   E += w/2 |r|²
//   ∇: u_i −= w r,  φ_i,k −= w a_k·r,  u_j += w r            (thesis Eq1–Eq3, eqs 2.27–2.29)
//   ∇²: JᵀJ with J = [∂r/∂u_i, ∂r/∂φ_i, ∂r/∂u_j] = [−I, −a, I], plus −w C on (φ_i, φ_i)
//       (the analytic Jacobian of eqs 2.30–2.47 in node-local variables)
double evaluateSerially(const RbmProblem& problem, RotationModel model, const std::vector<Vector3>& prescribed,
                        std::span<const double> unknowns, double* gradient, double* hessian, bool includeCurvature)
{
    const int dim = problem.dimension();
    const int bs = problem.blockSize();
    const int rotationCount = problem.rotationSize();
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<Vector3>& x = problem.referencePoints();
    const std::vector<double>& weights = problem.edgeWeights();
    const std::vector<int>& unknownIndex = problem.unknownIndex();
    const BlockPattern& pattern = problem.blockPattern();
    const std::vector<int>& edgeBlock = problem.edgeBlock();
    const std::vector<int>& edgeTransposeBlock = problem.edgeTransposeBlock();
    const std::size_t blockArea = static_cast<std::size_t>(bs) * bs;

    if (gradient) std::fill(gradient, gradient + problem.unknownCount(), 0.0);
    if (hessian) std::fill(hessian, hessian + blockArea * pattern.blockCount(), 0.0);

    auto displacementOf = [&](int node) {
        const int b = unknownIndex[node];
        if (b < 0) return prescribed[node];
        const double* block = unknowns.data() + static_cast<std::size_t>(b) * bs;
        return Vector3{block[0], block[1], dim == 3 ? block[2] : 0.0};
    };

    double energy = 0.0;
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int i = problem.unknownNodes()[a];
        const double* block = unknowns.data() + static_cast<std::size_t>(a) * bs;
        const RotationDerivatives rotation = rotationDerivatives(dim, model, block + dim);
        const Vector3 ui{block[0], block[1], dim == 3 ? block[2] : 0.0};
        double* gi = gradient ? gradient + static_cast<std::size_t>(a) * bs : nullptr;
        double* hii = hessian ? hessian + blockArea * pattern.diagonal[a] : nullptr;

        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            const double w = weights[e];
            Vector3 d = x[j] - x[i];
            if (dim == 2) d.z = 0.0;
            const Vector3 rotated = rotation.rotation * d;
            const Vector3 r = displacementOf(j) - ui + (d - rotated);
            energy += 0.5 * w * normSquared(r);
            if (!gradient && !hessian) continue;

            std::array<Vector3, 3> derivative;  // a_k
            for (int k = 0; k < rotationCount; ++k) derivative[k] = rotation.first[k] * d;
            const int b = unknownIndex[j];

            if (gradient) {
                for (int q = 0; q < dim; ++q) gi[q] -= w * r[q];
                for (int k = 0; k < rotationCount; ++k) gi[dim + k] -= w * dot(derivative[k], r);
                if (b >= 0) {
                    double* gj = gradient + static_cast<std::size_t>(b) * bs;
                    for (int q = 0; q < dim; ++q) gj[q] += w * r[q];
                }
            }
            if (hessian) {
                // (u_i, u_i), (u_i, φ_i), (φ_i, u_i), (φ_i, φ_i)
                for (int q = 0; q < dim; ++q) hii[q * bs + q] += w;
                addRotationBlocks(hii, bs, dim, rotationCount, derivative, rotation, r, d, w, includeCurvature);
                if (b >= 0) {
                    double* hjj = hessian + blockArea * pattern.diagonal[b];
                    double* hij = hessian + blockArea * edgeBlock[e];
                    double* hji = hessian + blockArea * edgeTransposeBlock[e];
                    for (int q = 0; q < dim; ++q) {
                        hjj[q * bs + q] += w;
                        hij[q * bs + q] -= w;
                        hji[q * bs + q] -= w;
                    }
                    for (int k = 0; k < rotationCount; ++k) {
                        for (int q = 0; q < dim; ++q) {
                            hij[(dim + k) * bs + q] -= w * derivative[k][q];  // (φ_i, u_j)
                            hji[q * bs + dim + k] -= w * derivative[k][q];    // (u_j, φ_i)
                        }
                    }
                }
            }
        }
    }
    return energy;
}

// The threaded pass (evaluateThreaded) over one problem's arrays, split into its parts.
class ThreadedPass {
public:
    ThreadedPass(const RbmProblem& problem, RotationModel model, const std::vector<Vector3>& prescribed,
                 std::span<const double> unknowns, double* gradient, double* hessian, bool includeCurvature)
        : model_(model), prescribed_(prescribed), unknowns_(unknowns), gradient_(gradient), hessian_(hessian),
          includeCurvature_(includeCurvature), dim_(problem.dimension()), bs_(problem.blockSize()),
          rotationCount_(problem.rotationSize()), unknownNodeCount_(problem.unknownNodeCount()),
          nodes_(problem.unknownNodes()), graph_(problem.graph()), x_(problem.referencePoints()),
          weights_(problem.edgeWeights()), unknownIndex_(problem.unknownIndex()), pattern_(problem.blockPattern()),
          edgeBlock_(problem.edgeBlock()), edgeTransposeBlock_(problem.edgeTransposeBlock()),
          blockArea_(static_cast<std::size_t>(bs_) * bs_)
    {
    }

    // The whole pass: fills the gradient and Hessian asked for and returns the energy.
    double run()
    {
        const int unknownNodeCount = unknownNodeCount_;
        if (hessian_) zeroHessian();
        edgeEnergy_.assign(graph_.neighbours.size(), 0.0);
        // The gradient's u_i rows need every neighbour's rotation: computed first.
        rotations_.assign(gradient_ ? static_cast<std::size_t>(unknownNodeCount) : 0, Matrix3{});
        if (gradient_) computeRotations();

#pragma omp parallel for schedule(static) if (worthThreading(graph_.neighbours.size()))
        for (int a = 0; a < unknownNodeCount; ++a) visitCentre(a);

        double energy = 0.0;
        for (int i : nodes_)
            for (int e = graph_.offsets[i]; e < graph_.offsets[i + 1]; ++e) energy += edgeEnergy_[e];
        return energy;
    }

private:
    // Zeroed by block rows; the passes below write disjoint entries of each block.
    void zeroHessian()
    {
        const int unknownNodeCount = unknownNodeCount_;
#pragma omp parallel for schedule(static) if (worthThreading(graph_.neighbours.size()))
        for (int a = 0; a < unknownNodeCount; ++a)
            std::fill(hessian_ + blockArea_ * pattern_.rowOffsets[a], hessian_ + blockArea_ * pattern_.rowOffsets[a + 1],
                      0.0);
    }

    // Every unknown node's rotation R_i.
    void computeRotations()
    {
        const int unknownNodeCount = unknownNodeCount_;
#pragma omp parallel for schedule(static) if (worthThreading(graph_.neighbours.size()))
        for (int a = 0; a < unknownNodeCount; ++a)
            rotations_[a] =
                rotationDerivatives(dim_, model_, unknowns_.data() + static_cast<std::size_t>(a) * bs_ + dim_).rotation;
    }

    // u of a node, prescribed or unknown.
    Vector3 displacementOf(int node) const
    {
        const int b = unknownIndex_[node];
        if (b < 0) return prescribed_[node];
        const double* block = unknowns_.data() + static_cast<std::size_t>(b) * bs_;
        return Vector3{block[0], block[1], dim_ == 3 ? block[2] : 0.0};
    }

    // d = x_to − x_from (in the plane in 2D).
    Vector3 offsetOf(int from, int to) const
    {
        Vector3 d = x_[to] - x_[from];
        if (dim_ == 2) d.z = 0.0;
        return d;
    }

    // r of edge e = (i → j) with centre i's rotation.
    Vector3 residualOf(int i, int j, const Matrix3& rotation, const Vector3& ui) const
    {
        const Vector3 d = offsetOf(i, j);
        const Vector3 rotated = rotation * d;
        return displacementOf(j) - ui + (d - rotated);
    }

    // Centre a's gradient rows, its Hessian blocks and its edges' energies.
    void visitCentre(int a)
    {
        const int i = nodes_[a];
        const double* block = unknowns_.data() + static_cast<std::size_t>(a) * bs_;
        const RotationDerivatives rotation = rotationDerivatives(dim_, model_, block + dim_);
        const Vector3 ui{block[0], block[1], dim_ == 3 ? block[2] : 0.0};
        double* gi = gradient_ ? gradient_ + static_cast<std::size_t>(a) * bs_ : nullptr;
        double* hii = hessian_ ? hessian_ + blockArea_ * pattern_.diagonal[a] : nullptr;
        const int split = firstEdgeAfter(graph_, i);

        if (gi) {
            for (int k = 0; k < bs_; ++k) gi[k] = 0.0;
            for (int e = graph_.offsets[i]; e < split; ++e) addIncoming(e, i, gi);
        }
        for (int e = graph_.offsets[i]; e < graph_.offsets[i + 1]; ++e) visitEdge(e, i, ui, rotation, gi, hii);
        if (gi)
            for (int e = split; e < graph_.offsets[i + 1]; ++e) addIncoming(e, i, gi);
        if (hessian_) setDisplacementDiagonal(i, split, hii);
    }

    // +w r of the edge j → i of an unknown neighbour j (centre j's u_j-term of ∇).
    void addIncoming(int e, int i, double* gi) const
    {
        const int j = graph_.neighbours[e];
        const int b = unknownIndex_[j];
        if (b < 0) return;
        const double* blockJ = unknowns_.data() + static_cast<std::size_t>(b) * bs_;
        const Vector3 uj{blockJ[0], blockJ[1], dim_ == 3 ? blockJ[2] : 0.0};
        const double w = weights_[e];   // w_ji = w_ij (RbmProblem::edgeWeights)
        const Vector3 r = residualOf(j, i, rotations_[b], uj);
        for (int q = 0; q < dim_; ++q) gi[q] += w * r[q];
    }

    // Edge e = (i → j): its energy, its terms in centre i's gradient rows and the Hessian entries it owns.
    void visitEdge(int e, int i, const Vector3& ui, const RotationDerivatives& rotation, double* gi, double* hii)
    {
        const int j = graph_.neighbours[e];
        const double w = weights_[e];
        const Vector3 d = offsetOf(i, j);
        const Vector3 r = residualOf(i, j, rotation.rotation, ui);
        edgeEnergy_[e] = 0.5 * w * normSquared(r);
        if (!gradient_ && !hessian_) return;

        std::array<Vector3, 3> derivative;  // a_k
        for (int k = 0; k < rotationCount_; ++k) derivative[k] = rotation.first[k] * d;
        const int b = unknownIndex_[j];

        if (gradient_) {
            for (int q = 0; q < dim_; ++q) gi[q] -= w * r[q];
            for (int k = 0; k < rotationCount_; ++k) gi[dim_ + k] -= w * dot(derivative[k], r);
        }
        if (hessian_) {
            // (u_i, φ_i), (φ_i, u_i), (φ_i, φ_i); the (u_i, u_i) diagonal is gathered below.
            addRotationBlocks(hii, bs_, dim_, rotationCount_, derivative, rotation, r, d, w, includeCurvature_);
            if (b >= 0) setOffDiagonalBlocks(e, w, derivative);
        }
    }

    // Entries only this edge writes: (φ_i, u_j) of block (i, j), (u_j, φ_i) of
    // block (j, i). The (u, u) diagonal of block (i, j) sums −w of both
    // directions (w_ij = w_ji); with two terms the order does not matter.
    void setOffDiagonalBlocks(int e, double w, const std::array<Vector3, 3>& derivative)
    {
        double* hij = hessian_ + blockArea_ * edgeBlock_[e];
        double* hji = hessian_ + blockArea_ * edgeTransposeBlock_[e];
        for (int q = 0; q < dim_; ++q) hij[q * bs_ + q] = (0.0 - w) - w;
        for (int k = 0; k < rotationCount_; ++k) {
            for (int q = 0; q < dim_; ++q) {
                hij[(dim_ + k) * bs_ + q] = 0.0 - w * derivative[k][q];
                hji[q * bs_ + dim_ + k] = 0.0 - w * derivative[k][q];
            }
        }
    }

    // (u_i, u_i) diagonal: w of the edges j → i of unknown j < i, then of i's own
    // edges, then of unknown j > i.
    void setDisplacementDiagonal(int i, int split, double* hii) const
    {
        double diagonal = 0.0;
        for (int e = graph_.offsets[i]; e < split; ++e)
            if (unknownIndex_[graph_.neighbours[e]] >= 0) diagonal += weights_[e];   // w_ji = w_ij
        for (int e = graph_.offsets[i]; e < graph_.offsets[i + 1]; ++e) diagonal += weights_[e];
        for (int e = split; e < graph_.offsets[i + 1]; ++e)
            if (unknownIndex_[graph_.neighbours[e]] >= 0) diagonal += weights_[e];
        for (int q = 0; q < dim_; ++q) hii[q * bs_ + q] = diagonal;
    }

    RotationModel model_;
    const std::vector<Vector3>& prescribed_;
    std::span<const double> unknowns_;
    double* gradient_;
    double* hessian_;
    bool includeCurvature_;
    int dim_;
    int bs_;
    int rotationCount_;
    int unknownNodeCount_;
    const std::vector<int>& nodes_;
    const CellNeighbourGraph& graph_;
    const std::vector<Vector3>& x_;
    const std::vector<double>& weights_;
    const std::vector<int>& unknownIndex_;
    const BlockPattern& pattern_;
    const std::vector<int>& edgeBlock_;
    const std::vector<int>& edgeTransposeBlock_;
    std::size_t blockArea_;
    std::vector<double> edgeEnergy_;
    std::vector<Matrix3> rotations_;
};

// The same pass shared out over threads (ThreadCount.hpp), bitwise equal to it for any
// thread count: every sum is formed in the serial pass's order — centres ascending, each
// centre's edges in order. The terms an edge gives the other end (u_j of ∇, the u_j
// diagonal and the (i, j), (j, i) blocks of ∇²) are gathered by that end instead of
// scattered: an entry of centre i's row receives the terms of the centres j < i, then i's
// own, then those of j > i, as the serial pass adds them (with w_ji = w_ij,
// RbmProblem::edgeWeights). The energy is the ordered sum of per-edge terms. Gathering
// forms each residual at both ends, about twice the serial arithmetic for ∇: it pays only
// when the work really is shared (tests/system/ThreadDeterminismTest.cpp compares both).
double evaluateThreaded(const RbmProblem& problem, RotationModel model, const std::vector<Vector3>& prescribed,
                        std::span<const double> unknowns, double* gradient, double* hessian, bool includeCurvature)
{
    return ThreadedPass(problem, model, prescribed, unknowns, gradient, hessian, includeCurvature).run();
}

double evaluate(const RbmProblem& problem, RotationModel model, const std::vector<Vector3>& prescribed,
                std::span<const double> unknowns, double* gradient, double* hessian, bool includeCurvature = true)
{
    if (static_cast<int>(unknowns.size()) != problem.unknownCount())
        throw std::invalid_argument("RBM energy: the unknown vector has " + std::to_string(unknowns.size()) +
                                    " entries, expected " + std::to_string(problem.unknownCount()));
    if (worthThreading(problem.graph().neighbours.size()) && threadsAvailable() > 1)
        return evaluateThreaded(problem, model, prescribed, unknowns, gradient, hessian, includeCurvature);
    return evaluateSerially(problem, model, prescribed, unknowns, gradient, hessian, includeCurvature);
}

} // namespace

double RbmEnergy::value(std::span<const double> unknowns) const
{
    return evaluate(problem_, model_, prescribed_, unknowns, nullptr, nullptr);
}

double RbmEnergy::gradient(std::span<const double> unknowns, std::span<double> gradientOut) const
{
    if (static_cast<int>(gradientOut.size()) != problem_.unknownCount())
        throw std::invalid_argument("RBM energy: gradient array has the wrong size");
    return evaluate(problem_, model_, prescribed_, unknowns, gradientOut.data(), nullptr);
}

void RbmEnergy::hessian(std::span<const double> unknowns, std::span<double> blockValues, bool includeCurvature) const
{
    const std::size_t expected = static_cast<std::size_t>(problem_.blockPattern().blockCount()) *
                                 problem_.blockSize() * problem_.blockSize();
    if (blockValues.size() != expected) throw std::invalid_argument("RBM energy: Hessian array has the wrong size");
    evaluate(problem_, model_, prescribed_, unknowns, nullptr, blockValues.data(), includeCurvature);
}

double RbmEnergy::projectedGradientNorm(std::span<const double> unknowns) const
{
    std::vector<double> g(unknowns.size());
    gradient(unknowns, g);
    problem_.projectSliding(g);
    double sum = 0.0;
    for (double value : g) sum += value * value;
    return std::sqrt(sum);
}

double RbmEnergy::gradientRoundoffNorm(std::span<const double> unknowns) const
{
    const RbmState state = unpackUnknowns(problem_, prescribed_, unknowns);
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const bool planar = problem_.dimension() == 2;
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int unknownNodeCount = problem_.unknownNodeCount();
    std::vector<double> magnitudes(static_cast<std::size_t>(unknownNodeCount));
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < unknownNodeCount; ++a) {
        const int i = nodes[a];
        double magnitude = 0.0;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            Vector3 d = x[j] - x[i];
            if (planar) d.z = 0.0;
            magnitude += problem_.edgeWeights()[e] * (norm(state.displacement[i]) + norm(state.displacement[j]) + norm(d));
        }
        magnitudes[a] = magnitude;
    }
    double sum = 0.0;  // in node order, whatever the thread count
    for (double magnitude : magnitudes) sum += problem_.dimension() * magnitude * magnitude;
    return std::numeric_limits<double>::epsilon() * std::sqrt(sum);
}

} // namespace rbm::motion
