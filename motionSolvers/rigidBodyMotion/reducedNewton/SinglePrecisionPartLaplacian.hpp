#pragma once
// The scalar K of one rank's part of a distributed 3D problem (PartLaplacian) in single
// precision on the part problem's own block pattern, as a PETSc shell matrix over the ranks: the
// fine level of the parts' multigrid cycle (DistributedAggregation.hpp) after its set-up.
//
// Why: PETSc's AIJ copy of K costs about 326 bytes a point (27 doubles, their column indices and
// row data); the cycle only smooths and forms residuals with K, where single precision is what
// the serial 3D cycle already uses (ThreeVectorMultigrid). This holds 27 floats a point (108
// bytes) on the pattern the part problem holds anyway, and the diagonal in double. The
// preconditioner it is part of is applied to a flexible Newton-CG, so its rounding changes the
// path of the iteration, not its end: each Newton step is tested on the double-precision energy.
//
// A product y = K x gathers the ghost unknowns' x from their owners (NodeExchange::updateGhosts)
// and sums each owned row in the pattern's order: deterministic for a given decomposition. Rows and columns are the owned unknowns of every rank, in PartLaplacian's order
// (each rank's after the lower ranks').

#include "PetscSupport.hpp"
#include "RbmProblem.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

class SinglePrecisionPartLaplacian {
public:
    // laplacian: K's entries in the problem's blockPattern() order (coupledDisplacementLaplacian);
    // only the owned rows are kept. Collective (creates the shell over the part's communicator).
    SinglePrecisionPartLaplacian(const RbmProblem& problem, std::span<const double> laplacian);
    // From PETSc's assembled K (owned unknown rows, global numbering): unknownRows holds every
    // unknown node's global row (owned and ghosts), as K was assembled with. So that the copy
    // can be made after the cycle's set-up, whose transient does not then hold it too.
    SinglePrecisionPartLaplacian(const RbmProblem& problem, Mat laplacian, std::span<const PetscInt> unknownRows);
    SinglePrecisionPartLaplacian(const SinglePrecisionPartLaplacian&) = delete;
    SinglePrecisionPartLaplacian& operator=(const SinglePrecisionPartLaplacian&) = delete;

    Mat matrix() const { return matrix_; }  // MatMult and MatGetDiagonal
    // y = K x for three vectors at once, interleaved (3 values per owned unknown): one pass over
    // K and one ghost exchange serve the three (PartThreeVectorCycle's smoothing). Collective.
    void multiplyThree(const double* x, double* y) const;
    const std::vector<double>& diagonal() const { return diagonal_; }  // per owned unknown
    int ownedRows() const { return ownedUnknowns_; }

private:
    explicit SinglePrecisionPartLaplacian(const RbmProblem& problem);
    void createShell();
    void multiply(Vec x, Vec y) const;
    static PetscErrorCode shellMultiply(Mat matrix, Vec x, Vec y);
    static PetscErrorCode shellDiagonal(Mat matrix, Vec diagonal);

    const RbmProblem& problem_;
    int ownedUnknowns_ = 0;
    std::vector<float> values_;     // the owned rows' entries, blockPattern() order
    std::vector<double> diagonal_;  // per owned unknown
    void fetchGhosts(const double* x, int width) const;

    // For the ghost exchange of a product, sized at first use (1 or 3 values a node): a node array
    // (the exchange's), and the ghost unknowns' values in the part's order.
    mutable std::vector<double> nodeValues_, ghostValues_;
    PetscMat matrix_;
};

} // namespace rbm::motion
