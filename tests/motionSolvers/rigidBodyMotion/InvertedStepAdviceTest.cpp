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
    const std::string advice = invertedStepAdvice(options, 3, 30.0, 0.01);
    EXPECT_TRUE(contains(advice, "formulation nonlinear")) << advice;
    EXPECT_TRUE(contains(advice, "weighting inverseDistanceSquared")) << advice;
    EXPECT_TRUE(contains(advice, "subSteps auto")) << advice;
    EXPECT_TRUE(contains(advice, "stiffening auto")) << advice;
    EXPECT_TRUE(contains(advice, "untangle on")) << advice;
    EXPECT_EQ(robustOptionChanges(options, 3).size(), 5u);
    // Not the motion: the options come first.
    EXPECT_FALSE(contains(advice, "None of rbm's options")) << advice;
}

TEST(InvertedStepAdvice, WithTheDefaultsSaysWhatTheMotionAsksSqueezeBeforeRotation)
{
    const RigidBodyMotionOptions defaults;
    for (int dimension : {2, 3}) {
        EXPECT_TRUE(robustOptionChanges(defaults, dimension).empty());
        const std::string squeeze = invertedStepAdvice(defaults, dimension, 30.0, 0.022);
        // 2D: the scale may be freed (scaling similar); 3D: neighbourhoods are rigid, nothing helps.
        EXPECT_EQ(contains(squeeze, "what can help this motion: scaling similar (the motion squeezes cells to 0.022"),
                  dimension == 2)
            << squeeze;
        EXPECT_EQ(contains(squeeze, "None of rbm's options will help: the motion squeezes cells to 0.022"), dimension == 3)
            << squeeze;
        // 2D: the translation's penalty too, for a gap that its automatic rule leaves out.
        EXPECT_EQ(contains(squeeze, "where the body translates, transverseStiffness 100"), dimension == 2) << squeeze;
        const std::string rotation = invertedStepAdvice(defaults, dimension, 30.0, 0.9);
        EXPECT_TRUE(contains(rotation, "the boundary turns by 30 degrees")) << rotation;
        const std::string other = invertedStepAdvice(defaults, dimension, 0.5, 0.9);
        EXPECT_TRUE(contains(other, "crosses another boundary")) << other;
    }
}

TEST(InvertedStepAdvice, In2DWithTheScaleAlreadyFreeSaysWhyNothingHelps)
{
    RigidBodyMotionOptions similar;
    similar.automaticScaling = false;
    similar.scaling.stiffness = 0.0;  // `scaling similar;`
    const std::string advice = invertedStepAdvice(similar, 2, 0.0, 0.02);
    EXPECT_TRUE(contains(advice, "None of rbm's options will help")) << advice;
    EXPECT_TRUE(contains(advice, "uniformly scaled")) << advice;
    RigidBodyMotionOptions newton;
    newton.algorithm = RbmAlgorithm::newton;  // the thesis' variants fit rotations only
    EXPECT_FALSE(contains(invertedStepAdvice(newton, 2, 0.0, 0.02), "scaling similar"));
}

} // namespace
} // namespace rbm::motion
