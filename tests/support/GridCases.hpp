#pragma once
// Small test problems of the motion solvers: a jittered structured grid with fixed, prescribed,
// sliding and free nodes (2D or 3D), and large motions of its top.

#include "RbmProblem.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

namespace rbm::motion {

// A jittered structured grid of n^d cells over [0,1]^d (2D: quadrilaterals), its cell-neighbour
// graph built from the cells, and node classes: the bottom (y = 0 in 2D, z = 0 in 3D) fixed,
// the top prescribed, the left side (x = 0) sliding on its plane (a mirror in 3D when asked),
// the right side (x = 1) sliding but no mirror, everything else free.
struct GridCase {
    int dimension = 3;
    std::vector<Vector3> points;
    std::unique_ptr<RbmProblem> problem;
    std::vector<Vector3> prescribed;
};

// The cell-neighbour graph of cells given as point lists: neighbours = points sharing a cell.
inline CellNeighbourGraph graphOfCells(int nodeCount, const std::vector<std::vector<int>>& cells)
{
    std::vector<std::vector<int>> neighbours(nodeCount);
    for (const std::vector<int>& cell : cells)
        for (int a : cell)
            for (int b : cell)
                if (a != b) neighbours[a].push_back(b);
    CellNeighbourGraph graph;
    graph.offsets.assign(1, 0);
    for (std::vector<int>& list : neighbours) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        graph.neighbours.insert(graph.neighbours.end(), list.begin(), list.end());
        graph.offsets.push_back(static_cast<Label>(graph.neighbours.size()));
    }
    return graph;
}

inline GridCase gridCase(int dimension, int n, bool mirror, unsigned seed)
{
    GridCase c;
    c.dimension = dimension;
    const int layers = dimension == 3 ? n + 1 : 1;
    auto index = [&](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> jitter(-0.2 / n, 0.2 / n);
    for (int k = 0; k < layers; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                Vector3 p{double(i) / n, double(j) / n, dimension == 3 ? double(k) / n : 0.0};
                const bool interior = i > 0 && i < n && j > 0 && j < n && (dimension == 2 || (k > 0 && k < n));
                if (interior) {
                    p.x += jitter(random);
                    p.y += jitter(random);
                    if (dimension == 3) p.z += jitter(random);
                }
                c.points.push_back(p);
            }
    const int nodeCount = static_cast<int>(c.points.size());
    std::vector<std::vector<int>> cells;
    for (int k = 0; k < (dimension == 3 ? n : 1); ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                std::vector<int>& cell = cells.emplace_back();
                for (int dk = 0; dk < (dimension == 3 ? 2 : 1); ++dk)
                    for (int dj = 0; dj < 2; ++dj)
                        for (int di = 0; di < 2; ++di) cell.push_back(index(i + di, j + dj, k + dk));
            }
    CellNeighbourGraph graph = graphOfCells(nodeCount, cells);

    std::vector<NodeConstraint> constraints(nodeCount);
    c.prescribed.assign(nodeCount, Vector3{});
    for (int node = 0; node < nodeCount; ++node) {
        const Vector3& p = c.points[node];
        const double height = dimension == 3 ? p.z : p.y;
        if (height == 0.0 || height == 1.0) {
            constraints[node].kind = NodeKind::prescribed;
            if (height == 1.0) {  // the top: turned 8° about the vertical through (0.5, 0.5) and shifted
                const double angle = 8.0 * 3.14159265358979 / 180.0;
                const double dx = p.x - 0.5, dy = dimension == 3 ? p.y - 0.5 : 0.0;
                c.prescribed[node] = dimension == 3
                                         ? Vector3{std::cos(angle) * dx - std::sin(angle) * dy - dx + 0.05,
                                                   std::sin(angle) * dx + std::cos(angle) * dy - dy, 0.03}
                                         : Vector3{0.1 * (1.0 + dx), 0.04 * dx, 0.0};
            }
        } else if (p.x == 0.0) {
            constraints[node] = {NodeKind::sliding, Vector3{-2.0, 0.0, 0.0}, mirror};
            c.prescribed[node] = {0.01, 0.0, 0.0};  // the plane itself moves by 0.01 along its normal
        } else if (p.x == 1.0) {
            constraints[node] = {NodeKind::sliding, Vector3{1.0, 0.0, 0.0}, false};
        }
    }
    c.problem = std::make_unique<RbmProblem>(dimension, c.points, std::move(graph), constraints,
                                             EdgeWeighting::inverseDistanceSquared);
    return c;
}

inline double largestDifference(const std::vector<Vector3>& a, const std::vector<Vector3>& b)
{
    double largest = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) largest = std::max(largest, norm(a[k] - b[k]));
    return largest;
}

// A large deformation of gridCase's top: turned 40° (2D: sheared by 0.3 and turned 25°), so
// that the exact rotations matter.
inline std::vector<Vector3> largeTopMotion(const GridCase& c)
{
    std::vector<Vector3> prescribed = c.prescribed;
    for (int node = 0; node < c.problem->nodeCount(); ++node) {
        const Vector3& p = c.points[node];
        const double height = c.dimension == 3 ? p.z : p.y;
        if (height != 1.0) continue;
        const double angle = (c.dimension == 3 ? 40.0 : 25.0) * 3.14159265358979 / 180.0;
        const double dx = p.x - 0.5, dy = c.dimension == 3 ? p.y - 0.5 : p.y - 1.0;
        prescribed[node] = {std::cos(angle) * dx - std::sin(angle) * dy - dx + (c.dimension == 2 ? 0.3 : 0.05),
                            std::sin(angle) * dx + std::cos(angle) * dy - dy, c.dimension == 3 ? 0.03 : 0.0};
    }
    return prescribed;
}

// P (K ⊗ I) P z on compact displacement vectors, K's values on problem.blockPattern().
inline std::vector<double> projectedLaplacianTimes(const RbmProblem& problem, const std::vector<double>& laplacian,
                                                   std::vector<double> z)
{
    const int dim = problem.dimension();
    const BlockPattern& pattern = problem.blockPattern();
    problem.projectSliding(z, dim);
    std::vector<double> y(z.size(), 0.0);
    for (int a = 0; a < problem.unknownNodeCount(); ++a)
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
            for (int q = 0; q < dim; ++q)
                y[static_cast<std::size_t>(a) * dim + q] +=
                    laplacian[position] * z[static_cast<std::size_t>(pattern.columns[position]) * dim + q];
    problem.projectSliding(y, dim);
    return y;
}

} // namespace rbm::motion
