// Tests of makeRbmSolver: each combination of options gives the solver of its variant, and the
// options reach it (a variant chosen by name must not silently become another).
#include "RbmSolverSelection.hpp"

#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "InputError.hpp"
#include "LocalGlobalThenNewton.hpp"
#include "MeshGenerators.hpp"
#include "PetscTestEnvironment.hpp"
#include "ReducedNewtonSolver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rbm::motion {
namespace {

// A 4 × 4 × 4 hex box, xMin held, xMax prescribed, the rest free.
struct BoxProblem {
    PolyMesh mesh = makeHexBox(4, 4, 4, {0, 0, 0}, {1, 1, 1});
    std::unique_ptr<RbmProblem> problem;
    BoxProblem()
    {
        auto graph = std::make_shared<const CellNeighbourGraph>(buildCellNeighbourGraph(mesh));
        std::vector<NodeConstraint> constraints(mesh.points.size());
        for (std::size_t p = 0; p < mesh.points.size(); ++p)
            if (mesh.points[p].x < 1e-12 || mesh.points[p].x > 1 - 1e-12) constraints[p].kind = NodeKind::prescribed;
        problem = std::make_unique<RbmProblem>(3, mesh.points, graph, constraints, EdgeWeighting::inverseDistanceSquared);
    }
    // xMax turned by 10° about the z axis through (1, 0.5, 0.5).
    std::vector<Vector3> target() const
    {
        const double angle = 10.0 * std::numbers::pi / 180.0;
        std::vector<Vector3> u(mesh.points.size());
        for (std::size_t p = 0; p < u.size(); ++p) {
            if (mesh.points[p].x < 1 - 1e-12) continue;
            const Vector3 r = mesh.points[p] - Vector3{1, 0.5, 0.5};
            u[p] = Vector3{std::cos(angle) * r.x - std::sin(angle) * r.y, std::sin(angle) * r.x + std::cos(angle) * r.y,
                           r.z} -
                   r;
        }
        return u;
    }
};

RigidBodyMotionOptions optionsOf(const std::string& text)
{
    return RigidBodyMotionOptions::read(io::Dictionary::parseText(text, "dynamicMeshDict"));
}

TEST(RbmSolverSelection, EachVariantGetsItsSolver)
{
    const BoxProblem box;
    const RbmProblem& problem = *box.problem;
    EXPECT_TRUE(dynamic_cast<ReducedNewtonSolver*>(makeRbmSolver(problem, RigidBodyMotionOptions{}).get()));
    EXPECT_TRUE(dynamic_cast<CoupledNewtonSolver*>(makeRbmSolver(problem, optionsOf("algorithm newton;")).get()));
    EXPECT_TRUE(dynamic_cast<LocalGlobalThenNewton*>(makeRbmSolver(problem, optionsOf("algorithm localGlobal;")).get()));
    EXPECT_TRUE(dynamic_cast<CoupledLinearizedSolver*>(makeRbmSolver(problem, optionsOf("formulation linearized;")).get()));
    EXPECT_TRUE(dynamic_cast<DecoupledSolver*>(makeRbmSolver(problem, optionsOf("coupling decoupled;")).get()));
    EXPECT_TRUE(dynamic_cast<DecoupledSolver*>(
        makeRbmSolver(problem, optionsOf("coupling decoupled; formulation linearized;")).get()));
}

TEST(RbmSolverSelection, ScalingIsReadAndRefusedWhereItIsNotImplemented)
{
    // auto (the default): a scale of stiffness 0.3 for the default solver in 2D, rigid in 3D and
    // for the variants.
    EXPECT_TRUE(optionsOf("").automaticScaling);
    EXPECT_TRUE(optionsOf("scaling auto;").automaticScaling);
    EXPECT_EQ(effectiveScaling(optionsOf(""), 2).stiffness, 0.3);
    EXPECT_TRUE(effectiveScaling(optionsOf(""), 3).rigid());
    EXPECT_TRUE(effectiveScaling(optionsOf("algorithm newton;"), 2).rigid());
    EXPECT_TRUE(effectiveScaling(optionsOf("formulation linearized;"), 2).rigid());
    EXPECT_FALSE(optionsOf("scaling rigid;").automaticScaling);
    EXPECT_TRUE(effectiveScaling(optionsOf("scaling rigid;"), 2).rigid());
    EXPECT_EQ(effectiveScaling(optionsOf("scaling similar;"), 2).stiffness, 0.0);
    EXPECT_EQ(effectiveScaling(optionsOf("scaling 2.5;"), 2).stiffness, 2.5);
    EXPECT_NE(optionsOf("scaling similar;").describe().find("scaling similar"), std::string::npos);
    EXPECT_NE(optionsOf("scaling rigid;").describe().find("scaling rigid"), std::string::npos);
    EXPECT_EQ(optionsOf("").describe().find("scaling"), std::string::npos);
    EXPECT_NO_THROW(optionsOf("algorithm newton;\nscaling rigid;"));
    auto errorOf = [](const std::string& text) {
        try {
            optionsOf(text);
        } catch (const InputError& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(errorOf("scaling -1;").find("'scaling' must be auto, rigid, similar or a number"), std::string::npos);
    EXPECT_NE(errorOf("scaling loose;").find("invalid value 'loose'"), std::string::npos);
    // The thesis' variants fit rotations only: a scaling they would ignore is an error.
    EXPECT_NE(errorOf("algorithm newton;\nscaling similar;").find("needs the default solver"), std::string::npos);
    EXPECT_NE(errorOf("algorithm newton;\nscaling similar;").find(":2: "), std::string::npos);
    // 3D: the kernels fit rotations only; the error names the entry's line.
    const BoxProblem box;
    try {
        makeRbmSolver(*box.problem, optionsOf("\nscaling similar;"));
        ADD_FAILURE() << "scaling in 3D was accepted";
    } catch (const InputError& error) {
        EXPECT_EQ(error.line(), 2);
        EXPECT_NE(std::string(error.what()).find("planar"), std::string::npos);
    }
}

TEST(RbmSolverSelection, TheNonlinearAlgorithmsReachTheSameMinimumAndMaxIterationsReachesThem)
{
    const BoxProblem box;
    const std::vector<Vector3> target = box.target();
    const RbmResult reduced = makeRbmSolver(*box.problem, RigidBodyMotionOptions{})->solve(target);
    const RbmResult newton = makeRbmSolver(*box.problem, optionsOf("algorithm newton;"))->solve(target);
    ASSERT_TRUE(reduced.converged) << reduced.reason;
    ASSERT_TRUE(newton.converged) << newton.reason;
    double largest = 0.0;
    for (std::size_t p = 0; p < target.size(); ++p)
        largest = std::max(largest, norm(reduced.displacement[p] - newton.displacement[p]));
    EXPECT_LT(largest, 1e-6);   // reduced Newton stops at 1e-6 of each node's shortest edge (0.25)

    // One local/global iteration does not converge: Newton takes over and finishes.
    const RbmResult handedOver =
        makeRbmSolver(*box.problem, optionsOf("algorithm localGlobal; maxIterations 1;"))->solve(target);
    EXPECT_TRUE(handedOver.converged) << handedOver.reason;
    EXPECT_NE(handedOver.reason.find("local/global stalled"), std::string::npos) << handedOver.reason;
    const RbmResult capped = makeRbmSolver(*box.problem, optionsOf("algorithm newton; maxIterations 1;"))->solve(target);
    EXPECT_FALSE(capped.converged) << capped.reason;
    EXPECT_EQ(capped.iterations, 1);
}

} // namespace
} // namespace rbm::motion
