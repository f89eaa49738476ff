#include "MemoryFit.hpp"

#include <sstream>
#include <stdexcept>

namespace rbm::motion {

namespace {

std::string general(double value)
{
    std::ostringstream text;
    text.precision(10);
    text << value;
    return text.str();
}

} // namespace

MemoryFit fitSolveIntoMemory(const RigidBodyMotionOptions& options, const SolveSize& size,
                             const AvailableMemory& available)
{
    const SolveVariant variant = solveVariantOf(options);
    const int systems = linearSystemsAtOnce(options);
    const MemoryEstimate needed = estimateSolveMemory(variant, size, options.linearSolver, systems);
    if (needed.bytes <= available.bytes) return {};

    if (options.linearSolver == LinearSolverKind::automatic && variant == SolveVariant::coupledLinearized &&
        needed.direct) {
        const MemoryEstimate lean = estimateSolveMemory(variant, size, LinearSolverKind::matrixFree, systems);
        if (lean.bytes <= available.bytes) {
            std::ostringstream note;
            note << "the direct factorisation would need about " << formatBytes(needed.bytes) << ", only "
                 << formatBytes(available.bytes) << " is available (" << available.source
                 << "): solving matrix-free (linearSolver matrixFree, about " << formatBytes(lean.bytes) << ")";
            return {LinearSolverKind::matrixFree, note.str()};
        }
    }

    std::ostringstream message;
    message << "the solve needs about " << formatBytes(needed.bytes) << " of memory, but only "
            << formatBytes(available.bytes) << " is available (" << available.source << "): " << options.describe()
            << ", "
            << (needed.direct ? "direct factorisation" : needed.matrixFree ? "matrix-free Krylov" : "Krylov + multigrid")
            << " of " << general(needed.rows) << " unknowns (" << general(size.unknownNodes) << " nodes in "
            << size.dimension << "D)";
    if (systems > 1) message << ", " << systems << " systems at once (linearized sub-steps)";
    message << ".";
    // The leanest alternative that fits: matrix-free (linearized only), else assembled Krylov.
    for (const LinearSolverKind alternative : {LinearSolverKind::matrixFree, LinearSolverKind::iterative}) {
        if (alternative == options.linearSolver || needed.matrixFree) break;
        if (alternative == LinearSolverKind::matrixFree && variant != SolveVariant::coupledLinearized) continue;
        const MemoryEstimate other = estimateSolveMemory(variant, size, alternative, systems);
        if (other.bytes < needed.bytes && other.bytes <= available.bytes) {
            message << " With 'linearSolver " << linearSolverName(alternative)
                    << ";' in rigidBodyMotionSolverCoeffs (constant/dynamicMeshDict) it needs about "
                    << formatBytes(other.bytes) << ".";
            break;
        }
    }
    message << " Run it on a machine with more memory, or coarsen the mesh.";
    throw std::runtime_error(message.str());
}

} // namespace rbm::motion
