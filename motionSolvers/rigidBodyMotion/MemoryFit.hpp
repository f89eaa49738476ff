#pragma once
// Whether an RBM solve fits in the memory there is, decided before anything is assembled
// (MemoryEstimate.hpp's model), so that a run too large for the machine stops at once with a
// clear message instead of swapping for hours or being killed half way:
//
//   - it fits: nothing changes;
//   - `linearSolver automatic` (the default) chose a direct factorisation of the coupled
//     linearized system that does not fit, and the matrix-free solve does (the same minimum,
//     a third of the memory at 10⁶ nodes; slower over long time series): the solve goes
//     matrix-free and the note says so;
//   - otherwise: std::runtime_error saying what the solve needs, what is available, and the
//     leanest `linearSolver` that would fit, if any.

#include "MemoryEstimate.hpp"
#include "RigidBodyMotionOptions.hpp"

#include <optional>
#include <string>

namespace rbm::motion {

struct MemoryFit {
    std::optional<LinearSolverKind> linearSolver;  // the one `automatic` falls back to; none: unchanged
    std::string note;                              // for the log, when linearSolver is set
};

MemoryFit fitSolveIntoMemory(const RigidBodyMotionOptions& options, const SolveSize& size,
                             const AvailableMemory& available);

} // namespace rbm::motion
