// Tests of the decoupled solver (DecoupledSolver): independent of the node numbering, every node
// the best rigid fit of its neighbours, a coupled energy above the coupled minimum.

#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalSolver.hpp"
#include "PetscTestEnvironment.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "ReducedNewtonSolver.hpp"
#include "RigidMotionModes.hpp"
#include "SubStepping.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <numeric>
#include <ostream>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace rbm::motion::coreCases;

namespace rbm::motion {

namespace {

// The same mesh with its nodes renumbered by `order` (new node k is old node order[k]).
struct Renumbered {
    std::vector<Vector3> points;
    CellNeighbourGraph graph;
    std::vector<NodeConstraint> constraints;
    std::vector<Vector3> prescribed;
};

Renumbered renumber(const SquaresCase& c, const std::vector<int>& order)
{
    const int n = static_cast<int>(order.size());
    std::vector<int> newIndex(n);
    for (int k = 0; k < n; ++k) newIndex[order[k]] = k;
    Renumbered r;
    std::vector<int> cellPoints(c.mesh.cellPoints.size());
    for (std::size_t p = 0; p < cellPoints.size(); ++p) cellPoints[p] = newIndex[c.mesh.cellPoints[p]];
    r.graph = graphFromCells(n, c.mesh.cellOffsets, cellPoints);
    for (int k = 0; k < n; ++k) {
        r.points.push_back(c.mesh.points[order[k]]);
        r.constraints.push_back(c.constraints[order[k]]);
        r.prescribed.push_back(c.prescribed[order[k]]);
    }
    return r;
}

TEST(Decoupled, ResultDoesNotDependOnTheNodeNumbering)
{
    // Irregular nodes: on the regular grid every node is the centroid of its neighbours
    // and the decoupled method reduces to Laplacian smoothing, rotations play no part.
    const SquaresCase c = squaresCase(21, 4, degrees(10.0), 2.0);
    std::vector<int> order(c.mesh.points.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(42));
    const Renumbered shuffled = renumber(c, order);
    const RbmProblem original(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    const RbmProblem permuted(2, shuffled.points, shuffled.graph, shuffled.constraints, EdgeWeighting::uniform);
    for (DecoupledModel model : {DecoupledModel::nonlinear, DecoupledModel::linearized}) {
        DecoupledOptions options;
        options.model = model;
        DecoupledSolver first(original, options);
        DecoupledSolver second(permuted, options);
        const RbmResult a = first.solve(c.prescribed);
        const RbmResult b = second.solve(shuffled.prescribed);
        ASSERT_TRUE(a.converged) << a.reason;
        ASSERT_TRUE(b.converged) << b.reason;
        double largest = 0.0, moved = 0.0;
        for (std::size_t k = 0; k < order.size(); ++k) {
            largest = std::max(largest, norm(b.displacement[k] - a.displacement[order[k]]));
            moved = std::max(moved, norm(a.displacement[order[k]]));
        }
        EXPECT_GT(moved, 1.0);
        EXPECT_LT(largest, 1e-9 * 10.0) << (model == DecoupledModel::nonlinear ? "nonlinear" : "linearized");
    }
}

TEST(Decoupled, EveryNodeIsTheBestRigidFitOfItsNeighbours)
{
    // At the fixed point, each node's (p_i, R_i) is the closed-form optimum of its own F_i
    // (docs/method.md §3): R_i the best rotation of the centred neighbour vectors, then
    // p_i = mean_j (p_j − R_i (x_j − x_i)), here with uniform weights.
    const SquaresCase c = squaresCase(21, 4, degrees(10.0), 2.0);
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    DecoupledSolver solver(problem);
    const RbmResult result = solver.solve(c.prescribed);
    ASSERT_TRUE(result.converged) << result.reason;
    const auto& x = c.mesh.points;
    for (int i : problem.unknownNodes()) {
        const auto neighbours = problem.graph().neighboursOf(i);
        Vector3 referenceCentre, currentCentre;
        for (int j : neighbours) {
            referenceCentre += x[j] / static_cast<double>(neighbours.size());
            currentCentre += (x[j] + result.displacement[j]) / static_cast<double>(neighbours.size());
        }
        double crossSum = 0.0, dotSum = 0.0;
        for (int j : neighbours) {
            const Vector3 a = x[j] - referenceCentre;
            const Vector3 b = x[j] + result.displacement[j] - currentCentre;
            crossSum += a.x * b.y - a.y * b.x;
            dotSum += a.x * b.x + a.y * b.y;
        }
        const Matrix3 rotation = planarRotation(std::atan2(crossSum, dotSum));
        const Vector3 best = currentCentre - rotation * (referenceCentre - x[i]);
        ASSERT_LT(norm(best - (x[i] + result.displacement[i])), 1e-8) << "node " << i;
    }
}

TEST(Decoupled, HasAHigherCoupledEnergyThanTheCoupledMinimum)
{
    const SquaresCase c = squaresCase(21, 4, degrees(10.0), 2.0);
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    DecoupledSolver decoupled(problem);
    CoupledNewtonSolver coupled(problem);
    const double decoupledEnergy = decoupled.solve(c.prescribed).energy;
    const double coupledEnergy = coupled.solve(c.prescribed).energy;
    EXPECT_GT(decoupledEnergy, coupledEnergy * (1.0 + 1e-6));
}

} // namespace
} // namespace rbm::motion
