#include "ProjectedLaplacianFactor.hpp"

#include <cmath>

namespace rbm::motion {

namespace {

// A unit vector orthogonal to the unit vector n (3D).
Vector3 orthogonalTo(const Vector3& n)
{
    const Vector3 axis = std::abs(n.x) < 0.9 ? Vector3{1.0, 0.0, 0.0} : Vector3{0.0, 1.0, 0.0};
    const Vector3 t = cross(n, axis);
    return t / norm(t);
}

} // namespace

ProjectedLaplacianFactor::ProjectedLaplacianFactor(const RbmProblem& problem, std::span<const double> laplacian,
                                                   FactorPrecision precision)
    : dimension_(problem.dimension()), nodeCount_(problem.unknownNodeCount())
{
    const int dim = dimension_;
    const int m = nodeCount_;
    const std::vector<int>& nodes = problem.unknownNodes();
    frame_.resize(m);
    admissible_.assign(m, dim);
    for (int a = 0; a < m; ++a) {
        const int node = nodes[a];
        std::array<Vector3, 3>& q = frame_[a];
        q = {Vector3{1, 0, 0}, Vector3{0, 1, 0}, Vector3{0, 0, 1}};
        if (problem.kind(node) != NodeKind::sliding) continue;
        const Vector3 n = problem.slidingNormal(node);
        if (dim == 2) {
            q = {Vector3{-n.y, n.x, 0.0}, Vector3{n.x, n.y, 0.0}, Vector3{0, 0, 1}};
            admissible_[a] = 1;
        } else if (problem.slidesOnLine(node)) {
            const Vector3 second = problem.secondSlidingNormal(node);
            q = {cross(n, second), n, second};
            admissible_[a] = 1;
        } else {
            const Vector3 t = orthogonalTo(n);
            q = {t, cross(n, t), n};
            admissible_[a] = 2;
        }
    }

    // Rows a·dim + i: the entries K_ab (q_a,i · q_b,j) between admissible directions, and the
    // identity on the normal ones.
    const BlockPattern& pattern = problem.blockPattern();
    std::vector<int> rowOffsets{0}, columns;
    std::vector<double> values;
    rowOffsets.reserve(static_cast<std::size_t>(m) * dim + 1);
    columns.reserve(pattern.columns.size() * dim);
    values.reserve(pattern.columns.size() * dim);
    for (int a = 0; a < m; ++a) {
        for (int i = 0; i < dim; ++i) {
            if (i >= admissible_[a]) {
                columns.push_back(a * dim + i);
                values.push_back(1.0);
                rowOffsets.push_back(static_cast<int>(columns.size()));
                continue;
            }
            for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position) {
                const int b = pattern.columns[position];
                const bool bothCartesian = admissible_[a] == dim && admissible_[b] == dim;
                for (int j = 0; j < admissible_[b]; ++j) {
                    if (bothCartesian && i != j) continue;   // K ⊗ I: no coupling of components
                    double projection = 0.0;
                    for (int k = 0; k < dim; ++k) projection += frame_[a][i][k] * frame_[b][j][k];
                    if (projection == 0.0) continue;
                    columns.push_back(b * dim + j);
                    values.push_back(laplacian[position] * projection);
                }
            }
            rowOffsets.push_back(static_cast<int>(columns.size()));
        }
    }
    factor_ = std::make_unique<SparseCholesky>(m * dim, rowOffsets, columns, values, precision);
    local_.resize(static_cast<std::size_t>(m) * dim);
}

void ProjectedLaplacianFactor::solve(std::span<const double> r, std::span<double> z) const
{
    const int dim = dimension_;
    for (int a = 0; a < nodeCount_; ++a) {
        const double* in = r.data() + static_cast<std::size_t>(a) * dim;
        double* out = local_.data() + static_cast<std::size_t>(a) * dim;
        for (int i = 0; i < dim; ++i) {
            double value = 0.0;
            if (i < admissible_[a])
                for (int k = 0; k < dim; ++k) value += frame_[a][i][k] * in[k];
            out[i] = value;
        }
    }
    factor_->solve(local_, local_, 1);
    for (int a = 0; a < nodeCount_; ++a) {
        const double* in = local_.data() + static_cast<std::size_t>(a) * dim;
        double* out = z.data() + static_cast<std::size_t>(a) * dim;
        for (int k = 0; k < dim; ++k) {
            double value = 0.0;
            for (int i = 0; i < admissible_[a]; ++i) value += frame_[a][i][k] * in[i];
            out[k] = value;
        }
    }
}

} // namespace rbm::motion
