#include "TurnedStart.hpp"

#include "LocalGlobalSolver.hpp"
#include "NodeExchange.hpp"
#include "RbmEnergy.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace rbm::motion {

bool turnedHarmonicStart(const RbmProblem& problem, LaplacianPreconditioner& preconditioner,
                         std::span<const Vector3> prescribedDisplacement, std::vector<Vector3>& u,
                         std::span<const Vector3> base)
{
    // No sliding nodes, K factorised by rbm or its 3D multigrid cycle, or a part's; every prescribed
    // node either fixed (no change) or moved by one rigid motion y = R (x − c) + c', fitted here
    // (2D: the best angle; 3D: Kabsch). x: the reference positions, or those displaced by base.
    if (!preconditioner.hasScalarSolve()) return false;
    const int dim = problem.dimension();
    const int n = problem.nodeCount();
    auto flat = [dim](Vector3 v) {
        if (dim == 2) v.z = 0.0;
        return v;
    };
    std::vector<Vector3> x = problem.referencePoints();
    std::vector<Vector3> change(prescribedDisplacement.begin(), prescribedDisplacement.end());
    if (!base.empty()) {
        for (int node = 0; node < n; ++node) {
            x[node] += flat(base[node]);
            change[node] = flat(change[node]) - flat(base[node]);
        }
    }
    prescribedDisplacement = change;  // from here on: the change since x
    auto moves = [&](int node) {
        const Vector3 d = flat(prescribedDisplacement[node]);
        return d.x != 0.0 || d.y != 0.0 || d.z != 0.0;
    };
    // The sums run over the nodes this rank owns (all nodes on one rank) and are added over the
    // ranks of a part (each node counted once), so every rank fits the same motion.
    const int owned = problem.ownedNodeCount();
    const MPI_Comm communicator = problem.isPart() ? problem.nodeExchange()->communicator() : MPI_COMM_SELF;
    std::array<double, 7> firstSums{};  // centre, moved, count
    for (int node = 0; node < owned; ++node) {
        if (problem.isUnknown(node) || !moves(node)) continue;
        const Vector3 from = flat(x[node]), to = flat(x[node] + prescribedDisplacement[node]);
        for (int k = 0; k < 3; ++k) firstSums[k] += from[k], firstSums[3 + k] += to[k];
        firstSums[6] += 1.0;
    }
    if (problem.isPart()) RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, firstSums.data(), 7, MPI_DOUBLE, MPI_SUM, communicator));
    const double count = firstSums[6];
    if (count < dim) return false;
    const Vector3 centre = Vector3{firstSums[0], firstSums[1], firstSums[2]} / count;
    const Vector3 moved = Vector3{firstSums[3], firstSums[4], firstSums[5]} / count;
    std::array<double, 11> secondSums{};  // crossSum, dotSum, covariance Σ b aᵀ (a = x − c, b = y − c')
    double size = 0.0;
    for (int node = 0; node < owned; ++node) {
        if (problem.isUnknown(node) || !moves(node)) continue;
        const Vector3 a = flat(x[node]) - centre;
        const Vector3 b = flat(x[node] + prescribedDisplacement[node]) - moved;
        secondSums[0] += a.x * b.y - a.y * b.x;
        secondSums[1] += a.x * b.x + a.y * b.y;
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 3; ++column) secondSums[2 + 3 * row + column] += b[row] * a[column];
        size = std::max(size, norm(a));
    }
    if (problem.isPart()) {
        RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, secondSums.data(), 11, MPI_DOUBLE, MPI_SUM, communicator));
        RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &size, 1, MPI_DOUBLE, MPI_MAX, communicator));
    }
    const double crossSum = secondSums[0], dotSum = secondSums[1];
    Matrix3 covariance{};
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column) covariance.m[row][column] = secondSums[2 + 3 * row + column];
    // The turn as a rotation vector ω (R = exp([ω]×)).
    Matrix3 rotation;
    Vector3 turn{};
    if (dim == 2) {
        const double angle = std::atan2(crossSum, dotSum);
        rotation = planarRotation(angle);
        turn = {0.0, 0.0, angle};
    } else {
        rotation = bestRotation(covariance);
        turn = rotationVectorFromMatrix(rotation);
        // Near a half turn the axis (and the sense of the interpolation) is ambiguous.
        if (norm(turn) > 0.99 * std::numbers::pi) return false;
    }
    int rigid = 1;  // every prescribed node of every rank on the motion (ghosts: their owners check)
    for (int node = 0; node < owned && rigid; ++node) {
        if (problem.isUnknown(node) || !moves(node)) continue;
        const Vector3 target = flat(x[node] + prescribedDisplacement[node]);
        if (norm(rotation * (flat(x[node]) - centre) + moved - target) > 1e-9 * std::max(size, 1e-300)) rigid = 0;
    }
    if (problem.isPart()) RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &rigid, 1, MPI_INT, MPI_MIN, communicator));
    if (!rigid) return false;  // not one rigid motion
    // s: harmonic, 1 on the moving nodes, 0 on the fixed ones (K s = b, b_a = Σ_moving w).
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<int>& nodes = problem.unknownNodes();
    const int m = problem.unknownNodeCount();
    std::vector<double> b(static_cast<std::size_t>(m), 0.0), share(static_cast<std::size_t>(m));
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            if (!problem.isUnknown(j) && moves(j)) b[a] += problem.edgeWeights()[e];
        }
    }
    if (!preconditioner.solveScalar(b, share)) return false;
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        const Vector3 offset = flat(x[i]) - centre;
        const Vector3 turned = rotationFromVector(share[a] * turn) * offset;
        u[i] = flat(turned + centre + share[a] * (moved - centre) - flat(problem.referencePoints()[i]));
    }
    return true;
}

} // namespace rbm::motion
