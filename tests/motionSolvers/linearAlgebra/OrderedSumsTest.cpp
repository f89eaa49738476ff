#include "OrderedSums.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace rbm::motion;

TEST(OrderedSums, DotProductAndNormOfSmallVectors)
{
    const std::vector<double> a{3.0, 4.0, 0.0}, b{1.0, -2.0, 5.0};
    EXPECT_EQ(dotProduct(a, b), -5.0);
    EXPECT_EQ(euclideanNorm(a), 5.0);
    EXPECT_EQ(euclideanNorm(std::vector<double>{}), 0.0);
}

TEST(OrderedSums, SumsInIndexOrder)
{
    // 1 + 1e16 − 1e16 is 0 in index order (1 is lost), 1 in any order that pairs the large terms first.
    const std::vector<double> a{1.0, 1e16, -1e16}, ones{1.0, 1.0, 1.0};
    EXPECT_EQ(dotProduct(a, ones), 0.0);
}
