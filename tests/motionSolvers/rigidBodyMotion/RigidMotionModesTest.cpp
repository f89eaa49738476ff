// Tests of the rigid motion modes (RigidMotionModes).

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

TEST(RigidMotionModes, AreOrthonormalAndCostNoEnergyAwayFromPrescribedNodes)
{
    // The sliding cases, and a 3D box large enough to have nodes away from its boundary.
    const TestMesh box = structuredGrid(6, 6, 6, 1.0, {0.0, 0.0, 0.0});
    const RbmProblem boxProblem(3, box.points, box.graph, prescribeBoundary(box), EdgeWeighting::inverseDistanceSquared);
    for (const auto& [dimension, mirror] : {std::pair{2, false}, {3, false}, {3, true}, {0, false}}) {
        const SlidingCase c = slidingCase(dimension == 0 ? 3 : dimension, 0.0, 0.0, EdgeWeighting::inverseDistanceSquared, mirror);
        const RbmProblem& problem = dimension == 0 ? boxProblem : *c.problem;
        const std::vector<std::vector<double>> modes = rigidMotionModes(problem);
        // Sliding nodes remove the normal translation; a mirror plane also the rotations about
        // in-plane axes. Whatever is left is orthonormal.
        const std::size_t expected = problem.dimension() == 2 ? 3 : 6;
        EXPECT_EQ(modes.size(), expected) << dimension << "D" << mirror;
        for (std::size_t a = 0; a < modes.size(); ++a)
            for (std::size_t b = 0; b < modes.size(); ++b) {
                double product = 0.0;
                for (std::size_t k = 0; k < modes[a].size(); ++k) product += modes[a][k] * modes[b][k];
                EXPECT_NEAR(product, a == b ? 1.0 : 0.0, 1e-12);
            }
        // H m = 0 in every row away from prescribed and sliding nodes: a rigid motion of the
        // unknown nodes strains only the edges to prescribed (fixed) nodes, and the sliding
        // constraint cut the modes' normal parts at the plane.
        const int bs = problem.blockSize();
        const std::vector<Vector3> zero(problem.nodeCount());
        const RbmEnergy energy(problem, RotationModel::smallAngle, zero);
        const BlockPattern& pattern = problem.blockPattern();
        std::vector<double> blocks(static_cast<std::size_t>(pattern.blockCount()) * bs * bs);
        energy.hessian(std::vector<double>(problem.unknownCount(), 0.0), blocks);
        problem.projectSlidingBlocks(blocks, bs);
        const CellNeighbourGraph& graph = problem.graph();
        int interiorRows = 0;
        for (const std::vector<double>& mode : modes) {
            for (int a = 0; a < pattern.rowCount(); ++a) {
                const int node = problem.unknownNodes()[a];
                bool nearPrescribed = problem.kind(node) == NodeKind::sliding;
                for (int e = graph.offsets[node]; e < graph.offsets[node + 1]; ++e)
                    nearPrescribed = nearPrescribed || problem.kind(graph.neighbours[e]) != NodeKind::free;
                if (nearPrescribed) continue;
                ++interiorRows;
                for (int p = 0; p < bs; ++p) {
                    double row = 0.0;
                    for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
                        for (int q = 0; q < bs; ++q)
                            row += blocks[(static_cast<std::size_t>(position) * bs + p) * bs + q] *
                                   mode[static_cast<std::size_t>(pattern.columns[position]) * bs + q];
                    EXPECT_NEAR(row, 0.0, 1e-9) << dimension << "D row " << a;
                }
            }
        }
        if (dimension != 3) {
            EXPECT_GT(interiorRows, 0);  // the small sliding boxes have none
        }
    }
}

} // namespace
} // namespace rbm::motion
