#include "InvertedStepAdvice.hpp"

#include "RbmSolverSelection.hpp"

#include <iomanip>
#include <sstream>

namespace rbm::motion {

std::vector<std::string> robustOptionChanges(const RigidBodyMotionOptions& o, int /*dimension*/)
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

std::string invertedStepAdvice(const RigidBodyMotionOptions& options, int dimension, double largestRotationDegrees,
                               double cellSizeRatio)
{
    std::ostringstream text;
    if (const std::vector<std::string> changes = robustOptionChanges(options, dimension); !changes.empty()) {
        text << "In rigidBodyMotionSolverCoeffs, what can help this motion: ";
        for (std::size_t k = 0; k < changes.size(); ++k) text << (k ? "; " : "") << changes[k];
        text << ".";
        return text.str();
    }
    text << std::setprecision(2);
    const bool reducedNewton = options.coupling == RbmCoupling::coupled &&
                               options.formulation == RbmFormulation::nonlinear &&
                               options.algorithm == RbmAlgorithm::reducedNewton;
    if (cellSizeRatio < squeezeAdviceRatio && dimension == 2 && reducedNewton &&
        effectiveScaling(options, dimension).stiffness != 0.0) {
        text << "In rigidBodyMotionSolverCoeffs, what can help this motion: scaling similar (the motion squeezes cells to "
             << cellSizeRatio << " of their size and less, a body closing a gap; with it each neighbourhood may shrink "
                "as freely as it turns); where the body translates, transverseStiffness 100 (the columns across the "
                "motion move as one and the gap closes evenly; `transverseStiffness auto` applies it by itself only "
                "where every fixed wall faces the motion, as in OpenFOAM's movingCone).";
    } else if (cellSizeRatio < squeezeAdviceRatio) {
        text << "None of rbm's options will help: the motion squeezes cells to " << cellSizeRatio
             << " of their size and less (a body closing a gap; 1 % of the cells), and rbm moves every node's neighbourhood as close to ";
        if (dimension == 2)
            text << "a turned and uniformly scaled copy of itself as it can, which does not shrink in one direction only: "
                    "the cells beside the gap shear until they fold.";
        else
            text << "a rigid body as it can, which does not shrink: the cells nearest the gap fold.";
        text << " What can: more cells in the gap, a smaller motion between remeshings, or a Laplacian motion solver "
                "with a directional diffusivity for this case.";
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
