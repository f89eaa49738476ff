#include "LocalGlobalThenNewton.hpp"

namespace rbm::motion {

LocalGlobalThenNewton::LocalGlobalThenNewton(const RbmProblem& problem, LocalGlobalOptions localGlobal,
                                             CoupledNewtonOptions newton)
    : problem_(problem), localGlobal_(problem, localGlobal), newtonOptions_(newton)
{}

RbmResult LocalGlobalThenNewton::solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    RbmResult first = localGlobal_.solve(prescribedDisplacement, initialGuess);
    if (first.converged) return first;
    if (!newton_) newton_ = std::make_unique<CoupledNewtonSolver>(problem_, newtonOptions_);
    RbmResult second = newton_->solve(prescribedDisplacement, &first);
    second.iterations += first.iterations;
    second.linearIterations += first.linearIterations;
    second.reason = "local/global stalled (" + first.reason + "), then Newton: " + second.reason;
    return second;
}

} // namespace rbm::motion
