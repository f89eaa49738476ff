#include "LocalGlobalSolver.hpp"

#include "NodeExchange.hpp"
#include "ThreadCount.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace rbm::motion {

SingularValueDecomposition singularValueDecomposition(const Matrix3& matrix)
{
    // One-sided Jacobi (Hestenes): right-multiply A = S by plane rotations until its columns
    // are orthogonal; then A = U diag(σ), S = U diag(σ) Vᵀ with V the product of rotations.
    Matrix3 a = matrix;
    Matrix3 v = Matrix3::identity();
    constexpr std::array<std::array<int, 2>, 3> pairs{{{0, 1}, {0, 2}, {1, 2}}};
    for (int sweep = 0; sweep < 60; ++sweep) {
        bool rotated = false;
        for (const auto& [p, q] : pairs) {
            double alpha = 0.0, beta = 0.0, gamma = 0.0;
            for (int i = 0; i < 3; ++i) {
                alpha += a.m[i][p] * a.m[i][p];
                beta += a.m[i][q] * a.m[i][q];
                gamma += a.m[i][p] * a.m[i][q];
            }
            if (gamma == 0.0 || std::abs(gamma) <= 1e-15 * std::sqrt(alpha * beta)) continue;
            rotated = true;
            const double zeta = (beta - alpha) / (2.0 * gamma);
            const double t = (zeta >= 0.0 ? 1.0 : -1.0) / (std::abs(zeta) + std::sqrt(1.0 + zeta * zeta));
            const double c = 1.0 / std::sqrt(1.0 + t * t);
            const double s = c * t;
            for (int i = 0; i < 3; ++i) {
                const double ap = a.m[i][p], aq = a.m[i][q];
                a.m[i][p] = c * ap - s * aq;
                a.m[i][q] = s * ap + c * aq;
                const double vp = v.m[i][p], vq = v.m[i][q];
                v.m[i][p] = c * vp - s * vq;
                v.m[i][q] = s * vp + c * vq;
            }
        }
        if (!rotated) break;
    }
    std::array<double, 3> sigma{};
    for (int k = 0; k < 3; ++k) sigma[k] = std::sqrt(a.m[0][k] * a.m[0][k] + a.m[1][k] * a.m[1][k] + a.m[2][k] * a.m[2][k]);
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int l, int r) { return sigma[l] > sigma[r]; });

    SingularValueDecomposition result;
    std::array<Vector3, 3> columns;
    const double tiny = 1e-13 * std::max(sigma[order[0]], 1e-300);
    int rank = 0;
    for (int k = 0; k < 3; ++k) {
        const int source = order[k];
        result.singularValues[k] = sigma[source];
        for (int i = 0; i < 3; ++i) result.v.m[i][k] = v.m[i][source];
        if (sigma[source] > tiny && sigma[source] > 0.0) {
            columns[k] = Vector3{a.m[0][source], a.m[1][source], a.m[2][source]} / sigma[source];
            ++rank;
        }
    }
    // Complete U to an orthonormal basis where S is rank deficient.
    if (rank == 0) columns[0] = {1.0, 0.0, 0.0};
    if (rank <= 1) {
        const Vector3& first = columns[0];
        const Vector3 helper = std::abs(first.x) < 0.9 ? Vector3{1.0, 0.0, 0.0} : Vector3{0.0, 1.0, 0.0};
        const Vector3 second = cross(first, helper);
        columns[1] = second / norm(second);
    }
    if (rank <= 2) columns[2] = cross(columns[0], columns[1]);
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) result.u.m[i][k] = columns[k][i];
    return result;
}

namespace {

double determinant(const Matrix3& a)
{
    const auto& m = a.m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

} // namespace

bool polarRotation(const Matrix3& covariance, Matrix3& rotation)
{
    // Scaled Newton iteration X ← (ζ X + X⁻ᵀ / ζ) / 2, ζ = det(X)^(−1/3) (Higham, "Computing the
    // polar decomposition", 1986): from X = S it converges quadratically to the orthogonal polar
    // factor, which is Kabsch's U Vᵀ when det S > 0. X⁻ᵀ = cof(X) / det X, whose columns are
    // cross products of X's columns. RBM's covariances are close to a rotation times an
    // isotropic matrix (Σ w d dᵀ with w = 1/|d|² is about the identity times the neighbour
    // count / 3), so a few iterations reach rounding, against several Jacobi sweeps and the
    // sorting and completion of an SVD. A fit runs per node every time the rotations are
    // refitted, so on large 3D meshes the SVD is a visible share of a solve's profile; this
    // iteration gives the same iterations of the solve for less (rbmBenchmark's twist3D case).
    auto column = [](const Matrix3& a, int k) { return Vector3{a.m[0][k], a.m[1][k], a.m[2][k]}; };
    double scale = 0.0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) scale += covariance.m[r][c] * covariance.m[r][c];
    if (!(scale > 0.0) || !std::isfinite(scale)) return false;
    const double cubeOfMean = std::pow(scale / 3.0, 1.5);  // (|S|_F / √3)³ = |det| when S ∝ a rotation
    Matrix3 x = covariance;
    bool scaled = true;
    for (int iteration = 0; iteration < 20; ++iteration) {
        const Vector3 c0 = column(x, 0), c1 = column(x, 1), c2 = column(x, 2);
        const Vector3 f0 = cross(c1, c2), f1 = cross(c2, c0), f2 = cross(c0, c1);  // cof(X) columns
        const double det = dot(c0, f0);
        // A reflection (det ≤ 0) or a nearly singular S (planar or collinear neighbourhood): the
        // SVD, which picks one of the optimal rotations.
        if (iteration == 0 && !(det > 1e-6 * cubeOfMean)) return false;
        if (!(det > 0.0)) return false;
        const double zeta = scaled ? 1.0 / std::cbrt(det) : 1.0;
        const double inverseScale = 1.0 / (zeta * det);
        Matrix3 next;
        const Vector3 cof[3] = {f0, f1, f2};
        double change = 0.0;
        for (int k = 0; k < 3; ++k)
            for (int r = 0; r < 3; ++r) {
                next.m[r][k] = 0.5 * (zeta * x.m[r][k] + inverseScale * cof[k][r]);
                const double difference = next.m[r][k] - x.m[r][k];
                change += difference * difference;
            }
        x = next;
        // The scaling only speeds up the first, far iterations; near the factor it is ≈ 1 and
        // would spoil the quadratic convergence by its own rounding.
        if (change < 1e-4) scaled = false;
        // Quadratic convergence: the error after this step is about change / 2 of its size.
        if (iteration > 0 && change < 1e-18) {
            rotation = x;
            return true;
        }
    }
    return false;
}

Matrix3 bestRotation(const Matrix3& covariance)
{
    Matrix3 polar;
    if (polarRotation(covariance, polar)) return polar;
    SingularValueDecomposition svd = singularValueDecomposition(covariance);
    // Reflection fix: flip the direction of the smallest singular value.
    if (determinant(svd.u) * determinant(svd.v) < 0.0)
        for (int i = 0; i < 3; ++i) svd.u.m[i][2] = -svd.u.m[i][2];
    return svd.u * svd.v.transposed();
}

// ---------------------------------------------------------------------------------------

LaggedRotationIteration::LaggedRotationIteration(const RbmProblem& problem, LaplacianForm form, Options options,
                                                 std::string_view solverName)
    : problem_(problem), form_(form), options_(options)
{
    const BlockPattern& pattern = problem.blockPattern();
    const CellNeighbourGraph& graph = problem.graph();
    const double neighbourFactor = form == LaplacianForm::coupled ? 2.0 : 1.0;
    laplacian_.assign(pattern.blockCount(), 0.0);
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int i = problem.unknownNodes()[a];
        double diagonal = 0.0;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const double w = problem.edgeWeights()[e];
            diagonal += w;
            const int block = problem.edgeBlock()[e];
            if (block >= 0) {
                laplacian_[block] = -neighbourFactor * w;
                if (form == LaplacianForm::coupled) diagonal += w;  // i is also j's neighbour term
            }
        }
        laplacian_[pattern.diagonal[a]] = diagonal;
    }

    vectorSystem_ = problem.hasSlidingNodes();
    const int dim = problem.dimension();
    const int blockSize = vectorSystem_ ? dim : 1;
    system_ = std::make_unique<BlockSystemSolver>(pattern.rowOffsets, pattern.columns, blockSize,
                                                  MatrixSymmetry::symmetricPositiveDefinite, options.linearSolver,
                                                  dim, options.linearRelativeTolerance, solverName);
    if (!vectorSystem_) {
        system_->setMatrix(laplacian_);
    } else {
        std::vector<double> blocks(static_cast<std::size_t>(pattern.blockCount()) * dim * dim, 0.0);
        for (int position = 0; position < pattern.blockCount(); ++position)
            for (int q = 0; q < dim; ++q) blocks[(static_cast<std::size_t>(position) * dim + q) * dim + q] = laplacian_[position];
        problem.projectSlidingBlocks(blocks, dim);
        system_->setMatrix(blocks);
    }
}

void fitNodeRotations(const RbmProblem& problem, std::span<const Vector3> displacement, std::vector<Matrix3>& rotations)
{
    problem.checkNodeArray(displacement, "displacement");
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<Vector3>& x = problem.referencePoints();
    const bool planar = problem.dimension() == 2;
    rotations.resize(problem.nodeCount(), Matrix3::identity());
    const std::vector<int>& nodes = problem.unknownNodes();
    // A part fits its owned nodes (the ghosts' neighbourhoods are incomplete) and takes the
    // ghosts' rotations from their owners.
    const int fittedNodeCount = problem.ownedUnknownCount();
    // One independent fit per node (thesis' local step): threads write only their own nodes.
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < fittedNodeCount; ++a) {
        const int i = nodes[a];
        double crossSum = 0.0, dotSum = 0.0;
        Matrix3 covariance;  // Σ w e dᵀ
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            const double w = problem.edgeWeights()[e];
            Vector3 d = x[j] - x[i];
            if (planar) d.z = 0.0;
            Vector3 current = d + displacement[j] - displacement[i];
            if (planar) {
                crossSum += w * (d.x * current.y - d.y * current.x);
                dotSum += w * (d.x * current.x + d.y * current.y);
            } else {
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c) covariance.m[r][c] += w * current[r] * d[c];
            }
        }
        if (planar) {
            rotations[i] = planarRotation(bestPlanarAngle(crossSum, dotSum));
        } else if (problem.rotatesAboutNormalOnly(i)) {
            // Mirror-plane node: the best rotation about the normal n alone. Only the parts of
            // d and e normal to n turn, so it is the planar fit of those parts:
            // θ = atan2(Σ w n·(d × e), Σ w (d·e − (d·n)(e·n))), from Σ w e dᵀ.
            const Vector3& n = problem.slidingNormal(i);
            double sine = 0.0, cosine = 0.0;
            for (int r = 0; r < 3; ++r) {
                for (int c = 0; c < 3; ++c) {
                    cosine += covariance.m[r][c] * ((r == c ? 1.0 : 0.0) - n[r] * n[c]);
                    // n·(d × e) = Σ n_k ε_kcr d_c e_r
                    const int k = 3 - r - c;
                    if (r != c) sine += covariance.m[r][c] * n[k] * ((c + 1) % 3 == r ? 1.0 : -1.0);
                }
            }
            rotations[i] = rotationFromVector(bestPlanarAngle(sine, cosine) * n);
        } else {
            rotations[i] = bestRotation(covariance);
        }
    }
    if (const NodeExchange* exchange = problem.nodeExchange())
        exchange->updateGhosts({&rotations.front().m[0][0], rotations.size() * 9}, 9);
}

Vector3 rotationParameters(int dimension, const Matrix3& rotation)
{
    if (dimension == 2) return {0.0, 0.0, std::atan2(rotation.m[1][0], rotation.m[0][0])};
    return rotationVectorFromMatrix(rotation);
}

void LaggedRotationIteration::fitRotations(std::span<const Vector3> displacement, std::vector<Matrix3>& rotations) const
{
    fitNodeRotations(problem_, displacement, rotations);
}

std::vector<Vector3> LaggedRotationIteration::rightHandSide(std::span<const Vector3> prescribed,
                                                            std::span<const Matrix3> rotations) const
{
    // b_k = Σ_{j prescribed} w ū_j + Σ_j w (I − R_k) d_kj [+ Σ_{j unknown} w (I − R_j) d_kj, coupled]
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const bool planar = problem_.dimension() == 2;
    const int unknownNodeCount = problem_.unknownNodeCount();
    std::vector<Vector3> b(unknownNodeCount);
#pragma omp parallel for schedule(static) if (worthThreading(problem_.graph().neighbours.size()))
    for (int a = 0; a < unknownNodeCount; ++a) {
        const int i = problem_.unknownNodes()[a];
        Vector3 sum;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            const double w = problem_.edgeWeights()[e];
            Vector3 d = x[j] - x[i];
            if (planar) d.z = 0.0;
            sum += w * (d - rotations[i] * d);
            if (!problem_.isUnknown(j)) {
                Vector3 given = prescribed[j];
                if (planar) given.z = 0.0;
                sum += w * given;
            } else if (form_ == LaplacianForm::coupled) {
                sum += w * (d - rotations[j] * d);
            }
        }
        b[a] = sum;
    }
    return b;
}

double LaggedRotationIteration::residualNorm(std::span<const Vector3> displacement,
                                             std::span<const Vector3> rightHandSide) const
{
    const BlockPattern& pattern = problem_.blockPattern();
    const int dim = problem_.dimension();
    const int unknownNodeCount = problem_.unknownNodeCount();
    std::vector<double> rowSquares(static_cast<std::size_t>(unknownNodeCount));
#pragma omp parallel for schedule(static) if (worthThreading(problem_.graph().neighbours.size()))
    for (int a = 0; a < unknownNodeCount; ++a) {
        Vector3 r = -1.0 * rightHandSide[a];
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
            r += laplacian_[position] * displacement[problem_.unknownNodes()[pattern.columns[position]]];
        const int node = problem_.unknownNodes()[a];
        if (problem_.kind(node) == NodeKind::sliding) r -= problem_.slidingNormalPart(node, r);
        if (dim == 2) r.z = 0.0;
        rowSquares[a] = normSquared(r);
    }
    double sum = 0.0;  // in row order, whatever the thread count
    for (double square : rowSquares) sum += square;
    return std::sqrt(sum);
}

bool LaggedRotationIteration::solveDisplacements(std::span<const Vector3> rightHandSide,
                                                 std::span<const Vector3> offset, std::vector<Vector3>& displacement,
                                                 int& linearIterations, std::string& failure)
{
    const int m = problem_.unknownNodeCount();
    const int dim = problem_.dimension();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const bool useGuess = !system_->isDirect();
    auto accept = [&](const BlockSystemSolver::Report& report) {
        linearIterations += report.iterations;
        if (!report.converged) failure = "DIVERGED_LINEAR_SOLVE (Laplacian: " + report.reason + ")";
        return report.converged;
    };
    if (!vectorSystem_) {
        // The same matrix for every component.
        std::vector<double> rhs(m), solution(m);
        for (int component = 0; component < dim; ++component) {
            for (int a = 0; a < m; ++a) {
                rhs[a] = rightHandSide[a][component];
                solution[a] = displacement[nodes[a]][component];
            }
            if (!accept(system_->solve(rhs, solution, useGuess))) return false;
            for (int a = 0; a < m; ++a) displacement[nodes[a]][component] = solution[a];
        }
        return true;
    }
    // Sliding nodes: u = u0 + v, v tangential, (P K P + s(I − P)) v = P (b − K u0).
    const BlockPattern& pattern = problem_.blockPattern();
    std::vector<double> rhs(static_cast<std::size_t>(m) * dim), solution(rhs.size());
    for (int a = 0; a < m; ++a) {
        Vector3 r = rightHandSide[a];
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
            r -= laplacian_[position] * offset[pattern.columns[position]];
        for (int q = 0; q < dim; ++q) {
            rhs[static_cast<std::size_t>(a) * dim + q] = r[q];
            solution[static_cast<std::size_t>(a) * dim + q] = displacement[nodes[a]][q] - offset[a][q];
        }
    }
    problem_.projectSliding(rhs, dim);
    problem_.projectSliding(solution, dim);
    if (!accept(system_->solve(rhs, solution, useGuess))) return false;
    problem_.projectSliding(solution, dim);
    for (int a = 0; a < m; ++a)
        for (int q = 0; q < dim; ++q)
            displacement[nodes[a]][q] = offset[a][q] + solution[static_cast<std::size_t>(a) * dim + q];
    return true;
}

namespace {

// Anderson mixing (type II) for a fixed-point map u ← G(u): the next point is the
// combination of the last few images G(u) that best cancels the last few residuals
// f = G(u) − u in the least-squares sense (Walker & Ni 2011).
class AndersonMixing {
public:
    explicit AndersonMixing(int depth) : depth_(depth) {}

    void clear()
    {
        differenceF_.clear();
        differenceG_.clear();
        previousF_.clear();
    }

    // Records (f, g) of the current point; returns true and the mixed point when there is
    // history to mix with.
    bool mix(const std::vector<double>& f, const std::vector<double>& g, std::vector<double>& mixed)
    {
        const std::size_t size = f.size();
        if (!previousF_.empty()) {
            std::vector<double> deltaF(size), deltaG(size);
            for (std::size_t k = 0; k < size; ++k) {
                deltaF[k] = f[k] - previousF_[k];
                deltaG[k] = g[k] - previousG_[k];
            }
            differenceF_.push_back(std::move(deltaF));
            differenceG_.push_back(std::move(deltaG));
            if (static_cast<int>(differenceF_.size()) > depth_) {
                differenceF_.erase(differenceF_.begin());
                differenceG_.erase(differenceG_.begin());
            }
        }
        previousF_ = f;
        previousG_ = g;
        const int p = static_cast<int>(differenceF_.size());
        if (p == 0) return false;
        // γ = argmin |f − ΔF γ| through the (slightly regularised) normal equations.
        std::vector<std::vector<double>> normal(p, std::vector<double>(p + 1, 0.0));
        for (int r = 0; r < p; ++r) {
            for (int s = 0; s < p; ++s) {
                double sum = 0.0;
                for (std::size_t k = 0; k < size; ++k) sum += differenceF_[r][k] * differenceF_[s][k];
                normal[r][s] = sum;
            }
            double sum = 0.0;
            for (std::size_t k = 0; k < size; ++k) sum += differenceF_[r][k] * f[k];
            normal[r][p] = sum;
            normal[r][r] *= 1.0 + 1e-10;
        }
        for (int column = 0; column < p; ++column) {
            int pivot = column;
            for (int r = column + 1; r < p; ++r)
                if (std::abs(normal[r][column]) > std::abs(normal[pivot][column])) pivot = r;
            std::swap(normal[pivot], normal[column]);
            if (!(std::abs(normal[column][column]) > 0.0)) return false;
            for (int r = column + 1; r < p; ++r) {
                const double factor = normal[r][column] / normal[column][column];
                for (int s = column; s <= p; ++s) normal[r][s] -= factor * normal[column][s];
            }
        }
        std::vector<double> gamma(p);
        for (int r = p - 1; r >= 0; --r) {
            double value = normal[r][p];
            for (int s = r + 1; s < p; ++s) value -= normal[r][s] * gamma[s];
            gamma[r] = value / normal[r][r];
        }
        mixed = g;
        for (int s = 0; s < p; ++s)
            for (std::size_t k = 0; k < size; ++k) mixed[k] -= gamma[s] * differenceG_[s][k];
        return true;
    }

private:
    int depth_;
    std::vector<std::vector<double>> differenceF_, differenceG_;
    std::vector<double> previousF_, previousG_;
};

// Sliding offsets c n of the unknown nodes (compact numbering).
std::vector<Vector3> compactSlidingOffset(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement)
{
    const int m = problem.unknownNodeCount();
    const int dim = problem.dimension();
    std::vector<Vector3> offset(m);
    std::vector<double> flat(static_cast<std::size_t>(m) * dim);
    problem.slidingOffset(prescribedDisplacement, flat, dim);
    for (int a = 0; a < m; ++a)
        for (int q = 0; q < dim; ++q) offset[a][q] = flat[static_cast<std::size_t>(a) * dim + q];
    return offset;
}

// All nodes' displacements with the prescribed ones filled in and the unknown ones zero.
std::vector<Vector3> prescribedPart(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement)
{
    const int n = problem.nodeCount();
    std::vector<Vector3> u(n);
    for (int node = 0; node < n; ++node) {
        if (problem.isUnknown(node)) continue;
        u[node] = prescribedDisplacement[node];
        if (problem.dimension() == 2) u[node].z = 0.0;
    }
    return u;
}

// The initial guess's unknown displacements, sliding nodes put back on their planes (lines).
void applyInitialGuess(const RbmProblem& problem, const RbmState& initialGuess, std::span<const Vector3> offset,
                       std::vector<Vector3>& u)
{
    problem.checkNodeArray(initialGuess.displacement, "initial guess displacement");
    const std::vector<int>& nodes = problem.unknownNodes();
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        Vector3 guess = initialGuess.displacement[nodes[a]];
        if (problem.dimension() == 2) guess.z = 0.0;
        if (problem.kind(nodes[a]) == NodeKind::sliding)
            guess = offset[a] + (guess - problem.slidingNormalPart(nodes[a], guess));
        u[nodes[a]] = guess;
    }
}

// The unknown nodes' displacements as one flat vector (compact numbering, dimension values a node) and back.
class CompactLayout {
public:
    CompactLayout(const RbmProblem& problem, std::span<const Vector3> offset)
        : problem_(problem), nodes_(problem.unknownNodes()), m_(problem.unknownNodeCount()),
          dim_(problem.dimension()), offset_(offset)
    {
    }

    std::size_t size() const { return static_cast<std::size_t>(m_) * dim_; }
    int nodeCount() const { return m_; }
    const std::vector<int>& nodes() const { return nodes_; }

    void flatten(const std::vector<Vector3>& displacement, std::vector<double>& flat) const
    {
        flat.resize(size());
        for (int a = 0; a < m_; ++a)
            for (int q = 0; q < dim_; ++q) flat[static_cast<std::size_t>(a) * dim_ + q] = displacement[nodes_[a]][q];
    }

    void unflatten(const std::vector<double>& flat, std::vector<Vector3>& displacement) const
    {
        for (int a = 0; a < m_; ++a) {
            Vector3& value = displacement[nodes_[a]];
            for (int q = 0; q < dim_; ++q) value[q] = flat[static_cast<std::size_t>(a) * dim_ + q];
            if (problem_.kind(nodes_[a]) == NodeKind::sliding)  // back onto the plane (line) exactly
                value -= problem_.slidingNormalPart(nodes_[a], value - offset_[a]);
        }
    }

private:
    const RbmProblem& problem_;
    const std::vector<int>& nodes_;
    int m_;
    int dim_;
    std::span<const Vector3> offset_;
};

// The coupled energy of the displacements with the fitted rotations. Per-edge terms computed
// by the threads, summed in edge order (the same sum for any thread count).
double coupledEnergy(const RbmProblem& problem, const std::vector<Vector3>& displacement,
                     const std::vector<Matrix3>& fitted, std::vector<double>& edgeTerms)
{
    const int m = problem.unknownNodeCount();
    const int dim = problem.dimension();
    const std::vector<int>& nodes = problem.unknownNodes();
    const CellNeighbourGraph& graph = problem.graph();
#pragma omp parallel for schedule(static) if (worthThreading(problem.graph().neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            Vector3 d = problem.referencePoints()[j] - problem.referencePoints()[i];
            if (dim == 2) d.z = 0.0;
            edgeTerms[e] = problem.edgeWeights()[e] * normSquared(displacement[j] - displacement[i] + d - fitted[i] * d);
        }
    }
    double sum = 0.0;
    for (int i : nodes)
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) sum += edgeTerms[e];
    return 0.5 * sum;
}

// What the accelerated iteration carries from one pass to the next.
struct AcceleratedState {
    AcceleratedState(const RbmProblem& problem, int depth)
        : mixing(std::max(0, depth)), edgeTerms(problem.graph().neighbours.size())
    {
    }

    AndersonMixing mixing;
    std::vector<double> edgeTerms;
    std::vector<Vector3> mixed, fallback;  // fallback: the plain step of the last accepted point
    std::vector<double> flatU, flatG, f, flatMixed;
    std::vector<Matrix3> mixedRotations;
    double currentEnergy = 0.0;
    double previousResidual = std::numeric_limits<double>::infinity();
    bool candidate = false;  // decoupled: u is an accelerated point still to be checked
    int accelerated = 0;
};

// The plain step's squared residual ‖G(u) − u‖² and the largest node move.
struct PlainStep {
    double residual;
    double change;
};

// Measures the plain step g = G(u); leaves f = G(u) − u and the flat u, g in the state.
PlainStep measurePlainStep(const CompactLayout& layout, const std::vector<Vector3>& u, const std::vector<Vector3>& g,
                           AcceleratedState& state)
{
    layout.flatten(u, state.flatU);
    layout.flatten(g, state.flatG);
    const std::size_t size = layout.size();
    state.f.resize(size);
    double residual = 0.0;
    for (std::size_t k = 0; k < size; ++k) {
        state.f[k] = state.flatG[k] - state.flatU[k];
        residual += state.f[k] * state.f[k];
    }
    double change = 0.0;
    const std::vector<int>& nodes = layout.nodes();
    for (int a = 0; a < layout.nodeCount(); ++a) change = std::max(change, norm(g[nodes[a]] - u[nodes[a]]));
    return {residual, change};
}

// The reason text of a converged iteration.
std::string convergedReason(double change, int iteration, int accelerated)
{
    std::ostringstream reason;
    reason << "CONVERGED_DISPLACEMENT_CHANGE (" << change << " after " << iteration << " iterations";
    if (accelerated > 0) reason << ", " << accelerated << " accelerated";
    reason << ")";
    return reason.str();
}

// Moves u to the Anderson-mixed point if the safeguard takes it, else to the plain step g.
void advance(const LaggedRotationIteration& iteration, const RbmProblem& problem, LaplacianForm form, int depth,
             const CompactLayout& layout, const std::vector<Vector3>& g, std::vector<Vector3>& u,
             std::vector<Matrix3>& rotations, AcceleratedState& state)
{
    bool tookAcceleration = false;
    if (depth > 0 && state.mixing.mix(state.f, state.flatG, state.flatMixed)) {
        state.mixed = g;
        layout.unflatten(state.flatMixed, state.mixed);
        iteration.fitRotations(state.mixed, state.mixedRotations);
        if (form == LaplacianForm::coupled) {
            const double mixedEnergy = coupledEnergy(problem, state.mixed, state.mixedRotations, state.edgeTerms);
            if (mixedEnergy < state.currentEnergy) {
                state.currentEnergy = mixedEnergy;
                tookAcceleration = true;
            }
        } else {
            state.fallback = g;
            state.candidate = true;
            tookAcceleration = true;
        }
        if (tookAcceleration) {
            u.swap(state.mixed);
            rotations.swap(state.mixedRotations);
            ++state.accelerated;
        } else {
            state.mixing.clear();
        }
    }
    if (!tookAcceleration) {
        u = g;
        iteration.fitRotations(u, rotations);
        if (form == LaplacianForm::coupled) state.currentEnergy = coupledEnergy(problem, u, rotations, state.edgeTerms);
    }
}

// The result's displacement, rotation parameters and exact energy at the final iterate.
void finishResult(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                  const std::vector<Vector3>& u, const std::vector<Matrix3>& rotations, RbmResult& result)
{
    result.displacement = u;
    result.rotation.assign(problem.nodeCount(), Vector3{});
    for (int node : problem.unknownNodes()) result.rotation[node] = rotationParameters(problem.dimension(), rotations[node]);
    std::vector<double> unknowns(problem.unknownCount());
    packUnknowns(problem, result, unknowns);
    result.energy = RbmEnergy(problem, RotationModel::exact, prescribedDisplacement).value(unknowns);
}

} // namespace

RbmResult LaggedRotationIteration::run(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    problem_.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    if (problem_.unknownNodeCount() == 0) return prescribedOnlyResult(problem_, prescribedDisplacement);
    const int n = problem_.nodeCount();
    const std::vector<Vector3> offset = compactSlidingOffset(problem_, prescribedDisplacement);

    RbmResult result;
    std::vector<Vector3> u = prescribedPart(problem_, prescribedDisplacement);
    std::vector<Matrix3> rotations(n, Matrix3::identity());
    if (initialGuess) {
        applyInitialGuess(problem_, *initialGuess, offset, u);
    } else {
        // Harmonic start: the global step with every rotation the identity.
        std::string failure;
        if (!solveDisplacements(rightHandSide(prescribedDisplacement, rotations), offset, u, result.linearIterations,
                                failure)) {
            result.reason = failure;
            result.displacement = u;
            result.rotation.assign(n, Vector3{});
            return result;
        }
    }

    const std::vector<Vector3> b = iterate(prescribedDisplacement, offset, u, rotations, result);
    result.residualNorm = residualNorm(u, b);
    finishResult(problem_, prescribedDisplacement, u, rotations, result);
    return result;
}

std::vector<Vector3> LaggedRotationIteration::iterate(std::span<const Vector3> prescribedDisplacement,
                                                      std::span<const Vector3> offset, std::vector<Vector3>& u,
                                                      std::vector<Matrix3>& rotations, RbmResult& result)
{
    // The iteration u ← G(u) = global(local(u)), accelerated by Anderson mixing (Peng et al.
    // 2018, "Anderson acceleration for geometry optimization and physics simulation").
    // Safeguards: for the coupled form an accelerated point is taken only if it lowers the
    // energy (the plain step always does); for the decoupled form, which minimises no common
    // energy, only if its residual turns out smaller than the one before. Otherwise the
    // plain step is taken and the history cleared.
    const double tolerance = options_.displacementTolerance * problem_.minimumEdgeLength();
    const CompactLayout layout(problem_, offset);
    AcceleratedState state(problem_, options_.accelerationDepth);
    std::vector<Vector3> b, g(problem_.nodeCount());
    fitRotations(u, rotations);
    state.currentEnergy =
        form_ == LaplacianForm::coupled ? coupledEnergy(problem_, u, rotations, state.edgeTerms) : 0.0;
    result.converged = false;
    int iteration = 0;
    for (;;) {
        b = rightHandSide(prescribedDisplacement, rotations);
        if (iteration >= options_.maximumIterations) {
            std::ostringstream reason;
            reason << "DIVERGED_MAXIMUM_ITERATIONS (" << iteration << ")";
            result.reason = reason.str();
            break;
        }
        g = u;
        std::string failure;
        if (!solveDisplacements(b, offset, g, result.linearIterations, failure)) {
            result.reason = failure;
            break;
        }
        ++iteration;
        const PlainStep step = measurePlainStep(layout, u, g, state);
        if (!std::isfinite(step.change)) {
            result.reason = "DIVERGED_NAN";
            break;
        }
        if (state.candidate && !(step.residual < state.previousResidual)) {
            // Decoupled safeguard: the accelerated point did worse; back to the plain step.
            u = state.fallback;
            fitRotations(u, rotations);
            state.mixing.clear();
            state.candidate = false;
            continue;
        }
        state.candidate = false;
        if (step.change <= tolerance) {
            u = g;  // the plain step from a converged point
            fitRotations(u, rotations);
            b = rightHandSide(prescribedDisplacement, rotations);
            result.converged = true;
            result.reason = convergedReason(step.change, iteration, state.accelerated);
            break;
        }
        state.previousResidual = step.residual;
        advance(*this, problem_, form_, options_.accelerationDepth, layout, g, u, rotations, state);
    }
    result.iterations = iteration;
    return b;
}

// ---------------------------------------------------------------------------------------

namespace {

LaggedRotationIteration::Options iterationOptions(const LocalGlobalOptions& options)
{
    LaggedRotationIteration::Options result;
    result.linearSolver = options.linearSolver;
    result.linearRelativeTolerance = options.linearRelativeTolerance;
    result.maximumIterations = options.maximumIterations;
    result.displacementTolerance = options.displacementTolerance;
    result.accelerationDepth = options.accelerationDepth;
    return result;
}

} // namespace

LocalGlobalSolver::LocalGlobalSolver(const RbmProblem& problem, LocalGlobalOptions options)
    : problem_(problem), iteration_(problem, LaplacianForm::coupled, iterationOptions(options), "laplacian")
{}

RbmResult LocalGlobalSolver::solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    return iteration_.run(prescribedDisplacement, initialGuess);
}

} // namespace rbm::motion
