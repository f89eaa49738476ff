// Tests of invertedStepAdvice: the options that can help, or why none will.
#include "InvertedStepAdvice.hpp"

#include <gtest/gtest.h>

namespace rbm::motion {
namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(InvertedStepAdvice, NamesTheRobustOptionsTheUserLeftOut)
{
    RigidBodyMotionOptions options;
    options.formulation = RbmFormulation::linearized;
    options.weighting = EdgeWeighting::uniform;
    options.subSteps = 4;
    options.stiffening.exponent = 0.0;
    options.untangle = false;
    const std::string advice = invertedStepAdvice(options, 30.0, 0.01);
    EXPECT_TRUE(contains(advice, "formulation nonlinear")) << advice;
    EXPECT_TRUE(contains(advice, "weighting inverseDistanceSquared")) << advice;
    EXPECT_TRUE(contains(advice, "subSteps auto")) << advice;
    EXPECT_TRUE(contains(advice, "stiffening auto")) << advice;
    EXPECT_TRUE(contains(advice, "untangle on")) << advice;
    EXPECT_EQ(robustOptionChanges(options).size(), 5u);
    // Not the motion: the options come first.
    EXPECT_FALSE(contains(advice, "None of rbm's options")) << advice;
}

TEST(InvertedStepAdvice, WithTheDefaultsSaysWhatTheMotionAsksSqueezeBeforeRotation)
{
    const RigidBodyMotionOptions defaults;
    EXPECT_TRUE(robustOptionChanges(defaults).empty());
    const std::string squeeze = invertedStepAdvice(defaults, 30.0, 0.022);
    EXPECT_TRUE(contains(squeeze, "None of rbm's options will help: the motion squeezes cells to 0.022")) << squeeze;
    const std::string rotation = invertedStepAdvice(defaults, 30.0, 0.9);
    EXPECT_TRUE(contains(rotation, "the boundary turns by 30 degrees")) << rotation;
    const std::string other = invertedStepAdvice(defaults, 0.5, 0.9);
    EXPECT_TRUE(contains(other, "crosses another boundary")) << other;
}

} // namespace
} // namespace rbm::motion
