// K of one rank's part in single precision (SinglePrecisionPartLaplacian) against the whole
// problem's K in double: CTest runs this program under mpiexec with 1 to 4 ranks. A product of
// the shell on every rank must equal the whole K's product at the same points, row by row, to
// single precision's rounding of the entries (6·10⁻⁸ of Σ_j |K_ij x_j|, with a margin), and its
// diagonal the whole K's in double precision.

#include "PetscTestEnvironment.hpp"

#include "BoxConstraints.hpp"
#include "DecomposedBox.hpp"
#include "MeshPart.hpp"
#include "PartProblem.hpp"
#include "ReducedLinearizedOperator.hpp"
#include "SinglePrecisionPartLaplacian.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using namespace rbm;
using namespace rbm::motion;
using rbm::test::DecomposedBox;

constexpr Label nx = 7, ny = 6, nz = 5;

double valueAt(const Vector3& x) { return std::sin(4 * x.x + x.y) + x.z * x.z - 0.3 * x.x; }

void checkAgainstWhole(const rbm::test::BoxDecomposition& decomposition)
{
    const DecomposedBox box(nx, ny, nz, decomposition);
    const std::vector<NodeConstraint> wholeConstraints = rbm::test::boxConstraints(box, Vector3{1.0, 0.2, 0.0});
    const RbmProblem whole(3, box.mesh.points, box.graph, wholeConstraints);
    const std::vector<double> wholeK = coupledDisplacementLaplacian(whole);
    const BlockPattern& wholePattern = whole.blockPattern();

    const MeshPart part(PETSC_COMM_WORLD, box.localCells(rbm::test::worldRank()));
    const RbmProblem problem = partProblem(3, part, rbm::test::partConstraints(part, wholeConstraints));
    const SinglePrecisionPartLaplacian single(problem, coupledDisplacementLaplacian(problem));

    const int owned = problem.ownedUnknownCount();
    PetscVec x, y, diagonal;
    RBM_CHECK_PETSC(MatCreateVecs(single.matrix(), x.out(), y.out()));
    RBM_CHECK_PETSC(VecDuplicate(x, diagonal.out()));
    double* entries = nullptr;
    RBM_CHECK_PETSC(VecGetArray(x, &entries));
    for (int a = 0; a < owned; ++a) entries[a] = valueAt(problem.referencePoints()[problem.unknownNodes()[a]]);
    RBM_CHECK_PETSC(VecRestoreArray(x, &entries));
    RBM_CHECK_PETSC(MatMult(single.matrix(), x, y));
    RBM_CHECK_PETSC(MatGetDiagonal(single.matrix(), diagonal));

    const double* product = nullptr;
    const double* diagonals = nullptr;
    RBM_CHECK_PETSC(VecGetArrayRead(y, &product));
    RBM_CHECK_PETSC(VecGetArrayRead(diagonal, &diagonals));
    int checked = 0;
    for (int a = 0; a < owned; ++a) {
        const int row = whole.unknownIndex()[part.nodeGlobalIds()[problem.unknownNodes()[a]]];
        double expected = 0.0, scale = 0.0;
        for (int position = wholePattern.rowOffsets[row]; position < wholePattern.rowOffsets[row + 1]; ++position) {
            const double term = wholeK[position] * valueAt(whole.referencePoints()[whole.unknownNodes()[wholePattern.columns[position]]]);
            expected += term;
            scale += std::abs(term);
        }
        EXPECT_NEAR(product[a], expected, 2e-7 * scale) << "whole row " << row;
        // In double: equal but for the order in which the part and the whole sum a node's edges.
        const double wholeDiagonal = wholeK[wholePattern.diagonal[row]];
        EXPECT_NEAR(diagonals[a], wholeDiagonal, 1e-14 * wholeDiagonal) << "whole row " << row;
        ++checked;
    }
    RBM_CHECK_PETSC(VecRestoreArrayRead(diagonal, &diagonals));
    RBM_CHECK_PETSC(VecRestoreArrayRead(y, &product));
    int total = 0;
    MPI_Allreduce(&checked, &total, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
    EXPECT_EQ(total, whole.unknownNodeCount());  // every row on exactly one rank
}

TEST(SinglePrecisionPartLaplacian, BlocksMultiplyAsTheWholeK) { checkAgainstWhole(rbm::test::blockDecomposition(nx, ny)); }

TEST(SinglePrecisionPartLaplacian, ScatteredCellsMultiplyAsTheWholeK) { checkAgainstWhole(rbm::test::scatteredDecomposition); }

TEST(SinglePrecisionPartLaplacian, NeedsAPart)
{
    const DecomposedBox box(nx, ny, nz, rbm::test::blockDecomposition(nx, ny));
    const RbmProblem whole(3, box.mesh.points, box.graph, rbm::test::boxConstraints(box, Vector3{1.0, 0.2, 0.0}));
    EXPECT_THROW(SinglePrecisionPartLaplacian(whole, coupledDisplacementLaplacian(whole)), std::invalid_argument);
}

} // namespace
