// Tests of PetscSupport (motionSolvers/linearAlgebra/PetscSupport.cpp). DirectSolverDefaults:
// rbm's defaults for the direct solver: MUMPS orders 2D systems with AMF (ICNTL(7) = 2) and 3D
// ones with its own automatic choice; an option given by the user wins; the option copy lives
// only as long as the solver. PetscSupport: PETSc errors as exceptions, and the solver options
// (rbm's prefix, global options, view options) reaching the solvers.

#include "BlockRowLayout.hpp"
#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalSolver.hpp"
#include "PetscSupport.hpp"
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

namespace {

using rbm::motion::BlockSystemSolver;
using rbm::motion::LinearSolverKind;
using rbm::motion::MatrixSymmetry;

constexpr int blockSize = 3;
constexpr int nodes = 4;

// The path graph 0-1-2-3, blocks 4 I on the diagonal and -I off it (symmetric positive definite).
struct PathSystem {
    std::vector<int> rowOffsets{0, 2, 5, 8, 10};
    std::vector<int> columns{0, 1, 0, 1, 2, 1, 2, 3, 2, 3};
    std::vector<double> blocks;

    PathSystem()
    {
        for (int row = 0; row < nodes; ++row) {
            for (int position = rowOffsets[row]; position < rowOffsets[row + 1]; ++position) {
                const double diagonal = columns[position] == row ? 4.0 : -1.0;
                for (int i = 0; i < blockSize; ++i)
                    for (int j = 0; j < blockSize; ++j) blocks.push_back(i == j ? diagonal : 0.0);
            }
        }
    }
};

// x_i = (i + 1, -2 (i + 1), 0.5), b = A x by hand: b_i = 4 x_i - x_{i-1} - x_{i+1}.
std::vector<double> expectedSolution()
{
    std::vector<double> x;
    for (int i = 0; i < nodes; ++i) x.insert(x.end(), {i + 1.0, -2.0 * (i + 1), 0.5});
    return x;
}

std::vector<double> rightHandSide(const std::vector<double>& x)
{
    std::vector<double> b(x.size());
    for (int i = 0; i < nodes; ++i)
        for (int c = 0; c < blockSize; ++c) {
            double value = 4.0 * x[blockSize * i + c];
            if (i > 0) value -= x[blockSize * (i - 1) + c];
            if (i + 1 < nodes) value -= x[blockSize * (i + 1) + c];
            b[blockSize * i + c] = value;
        }
    return b;
}

bool optionSet(const char* name)
{
    PetscBool set = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, nullptr, name, &set));
    return set == PETSC_TRUE;
}

// Solves the path system with a direct solver; returns MUMPS's ICNTL(7) after the solve.
int solveAndReadOrdering(int dimension)
{
    PathSystem path;
    BlockSystemSolver system(path.rowOffsets, path.columns, blockSize, MatrixSymmetry::symmetricPositiveDefinite,
                             LinearSolverKind::direct, dimension, 1e-12, "linearized");
    EXPECT_TRUE(system.isDirect());
    system.setMatrix(path.blocks);
    const std::vector<double> expected = expectedSolution();
    std::vector<double> solution(expected.size(), 0.0);
    const BlockSystemSolver::Report report = system.solve(rightHandSide(expected), solution);
    EXPECT_TRUE(report.converged);
    for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(solution[k], expected[k], 1e-13) << k;

    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(system.ksp(), &pc));
    Mat factor = nullptr;
    RBM_CHECK_PETSC(PCFactorGetMatrix(pc, &factor));
    PetscInt ordering = -1;
    RBM_CHECK_PETSC(MatMumpsGetIcntl(factor, 7, &ordering));
    return static_cast<int>(ordering);
}

TEST(DirectSolverDefaults, PreonlyWithAMultigridPreconditionerIsNotDirect)
{
    // -rbm_<name>_pc_type gamg alone over the direct default keeps KSP preonly: one cycle, no
    // factor to back-substitute with (the reduced Newton asked PETSc for one and stopped with
    // "No method getfactoredmatrix for PC of type gamg"). The default is direct.
    PathSystem path;
    {
        const BlockSystemSolver direct(path.rowOffsets, path.columns, blockSize, MatrixSymmetry::symmetricPositiveDefinite,
                                       LinearSolverKind::direct, 2, 1e-12, "linearized");
        EXPECT_TRUE(direct.isDirect());
    }
    RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, "-rbm_linearized_pc_type", "gamg"));
    const BlockSystemSolver cycle(path.rowOffsets, path.columns, blockSize, MatrixSymmetry::symmetricPositiveDefinite,
                                  LinearSolverKind::direct, 2, 1e-12, "linearized");
    RBM_CHECK_PETSC(PetscOptionsClearValue(nullptr, "-rbm_linearized_pc_type"));
    EXPECT_FALSE(cycle.isDirect());
}

#if defined(PETSC_HAVE_MUMPS)

TEST(DirectSolverDefaults, TwoDimensionalSystemsUseAmfWhileTheSolverLives)
{
    EXPECT_EQ(solveAndReadOrdering(2), 2);
    // The copied option went with the solver: a 3D solver of the same name does not see it.
    EXPECT_FALSE(optionSet("-rbm_linearized_mat_mumps_icntl_7"));
}

TEST(DirectSolverDefaults, ThreeDimensionalSystemsKeepMumpsAutomaticChoice)
{
    EXPECT_EQ(solveAndReadOrdering(3), 7);
}

TEST(DirectSolverDefaults, AGivenOrderingWins)
{
    RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_7", "0"));
    EXPECT_EQ(solveAndReadOrdering(2), 0);
    RBM_CHECK_PETSC(PetscOptionsClearValue(nullptr, "-mat_mumps_icntl_7"));

    RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, "-rbm_linearized_mat_mumps_icntl_7", "6"));
    EXPECT_EQ(solveAndReadOrdering(2), 6);
    EXPECT_TRUE(optionSet("-rbm_linearized_mat_mumps_icntl_7"));  // the user's, left alone
    RBM_CHECK_PETSC(PetscOptionsClearValue(nullptr, "-rbm_linearized_mat_mumps_icntl_7"));
}

#endif

} // namespace

namespace rbm::motion {

namespace {

TEST(PetscSupport, CheckPetscTurnsAnErrorIntoAnExceptionWithPetscsMessage)
{
    PetscKsp ksp;
    RBM_CHECK_PETSC(KSPCreate(PETSC_COMM_SELF, ksp.out()));
    try {
        RBM_CHECK_PETSC(KSPSetType(ksp, "noSuchKrylovMethod"));
        FAIL() << "no exception";
    } catch (const PetscException& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("KSPSetType(ksp, \"noSuchKrylovMethod\")"), std::string::npos) << message;
        EXPECT_NE(message.find("Unable to find requested KSP type noSuchKrylovMethod"), std::string::npos) << message;
        EXPECT_NE(error.code(), 0);
    }
}

// Sets PETSc options for one test and removes them afterwards.
class ScopedOptions {
public:
    explicit ScopedOptions(std::vector<std::pair<std::string, std::string>> options) : options_(std::move(options))
    {
        for (const auto& [name, value] : options_)
            RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()));
    }
    ~ScopedOptions()
    {
        for (const auto& option : options_) (void)PetscOptionsClearValue(nullptr, option.first.c_str());
    }

private:
    std::vector<std::pair<std::string, std::string>> options_;
};

TEST(PetscSupport, SolverOptionsWithTheRbmPrefixOverrideTheDefaults)
{
    // 2D defaults to a direct factorisation (0 Krylov iterations); the options ask for CG.
    const SquaresCase c = squaresCase(21, 4, degrees(10.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    CoupledLinearizedSolver direct(problem);
    const RbmResult byDirect = direct.solve(c.prescribed);
    EXPECT_EQ(byDirect.linearIterations, 0);
    const ScopedOptions options({{"-rbm_linearized_ksp_type", "cg"}, {"-rbm_linearized_pc_type", "jacobi"},
                                 {"-rbm_linearized_ksp_rtol", "1e-13"}});
    CoupledLinearizedSolver iterative(problem);
    const RbmResult byIterative = iterative.solve(c.prescribed);
    ASSERT_TRUE(byIterative.converged) << byIterative.reason;
    EXPECT_GT(byIterative.linearIterations, 10);
    for (std::size_t node = 0; node < c.mesh.points.size(); ++node)
        ASSERT_LT(norm(byIterative.displacement[node] - byDirect.displacement[node]), 1e-8);
}

TEST(PetscSupport, GlobalSolverOptionsAreHonoured)
{
    const SquaresCase c = squaresCase(21, 4, degrees(10.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    const ScopedOptions options({{"-ksp_type", "cg"}, {"-pc_type", "icc"}});
    LocalGlobalSolver solver(problem);
    const RbmResult result = solver.solve(c.prescribed);
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_GT(result.linearIterations, result.iterations);  // Krylov iterations in every Laplacian solve
}

TEST(PetscSupport, GlobalViewOptionsReachTheSolversAndSpecificOnesWin)
{
    // -snes_converged_reason is looked up at solve time under the solver's prefix.
    const SquaresCase c = squaresCase(11, 2, degrees(10.0));
    const RbmProblem problem(2, c.mesh.points, c.mesh.graph, c.constraints, EdgeWeighting::uniform);
    std::string printed;
    {
        const ScopedOptions options({{"-snes_converged_reason", ""}, {"-ksp_converged_reason", ""},
                                     {"-rbm_linearized_ksp_converged_reason", "::failed"}});
        CoupledNewtonSolver solver(problem);
        ::testing::internal::CaptureStdout();
        const RbmResult result = solver.solve(c.prescribed);
        printed = ::testing::internal::GetCapturedStdout();
        ASSERT_TRUE(result.converged) << result.reason;
    }
    EXPECT_NE(printed.find("Nonlinear rbm_newton_ solve converged"), std::string::npos) << printed;
    EXPECT_NE(printed.find("Linear rbm_newton_ solve converged"), std::string::npos) << printed;
    EXPECT_EQ(printed.find("Linear rbm_linearized_ solve"), std::string::npos) << printed;  // only failures
    // The copies under rbm_newton_ leave with the solver.
    PetscBool left = PETSC_TRUE;
    RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, nullptr, "-rbm_newton_snes_converged_reason", &left));
    EXPECT_EQ(left, PETSC_FALSE);
}

} // namespace
} // namespace rbm::motion
