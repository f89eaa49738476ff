#include "GramSchmidt.hpp"

#include "OrderedSums.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace rbm::motion;

TEST(GramSchmidt, OrthonormalBasisAndCoordinatesReproduceTheColumns)
{
    const std::vector<std::vector<double>> columns{{1.0, 1.0, 0.0, 0.0}, {1.0, 0.0, 1.0, 0.0}, {0.0, 2.0, 1.0, 3.0}};
    const ThinQr qr = orthonormalise(columns);
    ASSERT_EQ(qr.basis.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            EXPECT_NEAR(dotProduct(qr.basis[i], qr.basis[j]), i == j ? 1.0 : 0.0, 1e-14);
    // column kept[j] = Σ_i r[j][i] basis[i]
    for (std::size_t j = 0; j < 3; ++j) {
        EXPECT_EQ(qr.kept[j], j);
        for (std::size_t k = 0; k < 4; ++k) {
            double value = 0.0;
            for (std::size_t i = 0; i <= j; ++i) value += qr.r[j][i] * qr.basis[i][k];
            EXPECT_NEAR(value, columns[j][k], 1e-14);
        }
        EXPECT_GT(qr.r[j][j], 0.0);
    }
}

TEST(GramSchmidt, NearlyDependentColumnsAreLeftOut)
{
    const std::vector<std::vector<double>> columns{
        {1.0, 0.0, 0.0}, {2.0, 1e-9, 0.0}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    const ThinQr qr = orthonormalise(columns);
    ASSERT_EQ(qr.kept, (std::vector<std::size_t>{0, 3}));
    EXPECT_EQ(qr.basis[1], (std::vector<double>{0.0, 1.0, 0.0}));
}
