#pragma once
// `algorithm localGlobal`: the coupled nonlinear energy minimised by local/global iterations
// (LocalGlobalSolver.hpp); where they stall (maxIterations without convergence: a loosely
// held boundary, thesis §3.1.3), Newton (CoupledNewtonSolver.hpp) finishes from where they
// stopped.

#include "CoupledNewtonSolver.hpp"
#include "LocalGlobalSolver.hpp"

#include <memory>

namespace rbm::motion {

class LocalGlobalThenNewton final : public RbmSolver {
public:
    LocalGlobalThenNewton(const RbmProblem& problem, LocalGlobalOptions localGlobal, CoupledNewtonOptions newton);
    const RbmProblem& problem() const override { return problem_; }
    // Iteration counts are the sums of both stages; the reason says when Newton took over.
    RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess) override;

private:
    const RbmProblem& problem_;
    LocalGlobalSolver localGlobal_;
    CoupledNewtonOptions newtonOptions_;
    std::unique_ptr<CoupledNewtonSolver> newton_;   // built the first time local/global stalls
};

} // namespace rbm::motion
