#include "InvertedStepAdvice.hpp"

#include <iomanip>
#include <sstream>

namespace rbm::motion {

std::vector<std::string> robustOptionChanges(const RigidBodyMotionOptions& o)
{
    std::vector<std::string> changes;
    if (o.formulation == RbmFormulation::linearized)
        changes.push_back("formulation nonlinear (exact rotations: the linearized form shears cells under large turns)");
    if (o.weighting != EdgeWeighting::inverseDistanceSquared)
        changes.push_back("weighting inverseDistanceSquared (keeps small and stretched cells rigid)");
    if (!o.automaticSubSteps())
        changes.push_back("subSteps auto (halves a sub-step that inverts cells, up to maxSubStepSplits times)");
    else if (o.maxSubStepSplits < RigidBodyMotionOptions{}.maxSubStepSplits)
        changes.push_back("a larger maxSubStepSplits");
    if (!o.stiffening.enabled()) changes.push_back("stiffening auto (the cells next to a moving body turn with it)");
    if (!o.untangle) changes.push_back("untangle on (moves the points around inverted cells until they are valid)");
    return changes;
}

std::string invertedStepAdvice(const RigidBodyMotionOptions& options, double largestRotationDegrees,
                               double cellSizeRatio)
{
    std::ostringstream text;
    if (const std::vector<std::string> changes = robustOptionChanges(options); !changes.empty()) {
        text << "In rigidBodyMotionSolverCoeffs, what can help this motion: ";
        for (std::size_t k = 0; k < changes.size(); ++k) text << (k ? "; " : "") << changes[k];
        text << ".";
        return text.str();
    }
    text << std::setprecision(2);
    if (cellSizeRatio < squeezeAdviceRatio) {
        text << "None of rbm's options will help: the motion squeezes cells to " << cellSizeRatio
             << " of their size and less (a body closing a gap; 1 % of the cells), and rbm moves every node's neighbourhood as close to a "
                "rigid body as it can, which does not shrink: the cells nearest the gap fold. What can: more cells "
                "in the gap, a smaller motion between remeshings, or a Laplacian motion solver for this case.";
    } else if (largestRotationDegrees > 1.0) {
        text << "None of rbm's options will help: the boundary turns by " << largestRotationDegrees
             << " degrees, more than the cells between it and the fixed boundary can take with the defaults in effect "
                "(nonlinear, 1/|d|^2 weights, automatic sub-steps, stiffening, untangling). What can: more cells "
                "around the moving body, or a smaller rotation between remeshings.";
    } else {
        text << "None of rbm's options will help: the defaults in effect (nonlinear, 1/|d|^2 weights, automatic "
                "sub-steps, stiffening, untangling) are its most robust choices. A prescribed motion that "
                "deforms a patch or crosses another boundary does this; the step's mesh shows where.";
    }
    return text.str();
}

} // namespace rbm::motion
