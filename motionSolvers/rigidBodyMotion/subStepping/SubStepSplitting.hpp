#pragma once
// Halving of sub-steps that invert cells (`subSteps auto`): a sub-step is split in two while
// its depth of halving is below maxSubStepSplits. Once a sub-step at the deepest level still
// inverts cells, splitting is given up for the rest of the solve: smaller steps did not help
// there, and going on would cost up to 2^depth solves per remaining sub-step.

#include <string>

namespace rbm::motion {

class SubStepSplitting {
public:
    // maximumDepth 0: never split (a fixed `subSteps N`).
    explicit SubStepSplitting(int maximumDepth) : maximumDepth_(maximumDepth) {}
    bool allows(int depth) const { return !exhausted_ && maximumDepth_ > 0 && depth <= maximumDepth_; }
    // Whether to keep a sub-step at `depth` whose mesh is (not) valid; false: split it.
    bool accept(int depth, bool inverted)
    {
        if (!inverted) return true;
        if (depth < maximumDepth_) {
            ++splits_;
            return false;
        }
        exhausted_ = true;
        return true;
    }
    // For the solve's reason: " (3 sub-step splits)", and whether splitting was given up.
    std::string describe() const
    {
        std::string text;
        if (splits_ > 0) text += " (" + std::to_string(splits_) + " sub-step splits)";
        if (exhausted_) text += " (a sub-step still inverted cells after " + std::to_string(maximumDepth_) + " splits)";
        return text;
    }

private:
    int maximumDepth_;
    int splits_ = 0;
    bool exhausted_ = false;
};

} // namespace rbm::motion
