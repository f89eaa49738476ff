#pragma once
// Chebyshev smoothing of degree `degree` on D⁻¹A over [0.1 λ, 1.1 λ] (PETSc's default multigrid
// smoother, with point Jacobi) for THREE interleaved vectors (3 values a row), the smoother of
// rbm's own multigrid cycles: one rank's (ThreeVectorMultigrid) and a decomposed run's
// (PartThreeVectorCycle), which differ only in how they multiply by A.
//
// x ← x + p(D⁻¹A) D⁻¹ (b − A x), from x = 0 where zeroGuess (one product fewer). multiply(in, out)
// is out = A in on three interleaved vectors; r, d and product are work arrays of x's size.
// Every loop writes its own row: deterministic, and threaded where worthThreading says so.

#include "ThreadCount.hpp"

#include <cstddef>

namespace rbm::motion {

template <typename Multiply>
void chebyshevSmooth(int rows, double lambda, int degree, const double* inverseDiagonal, const double* b, double* x,
                     bool zeroGuess, double* r, double* d, double* product, std::size_t matrixEntries,
                     const Multiply& multiply)
{
    const double upper = 1.1 * lambda, lower = 0.1 * lambda;
    const double theta = 0.5 * (upper + lower), delta = 0.5 * (upper - lower);
    const double sigma = theta / delta;
    double rho = 1.0 / sigma;
    const bool threads = worthThreading(matrixEntries);
    // r = D⁻¹ (b − A x), d = r / θ, x += d
    if (!zeroGuess) multiply(x, r);
#pragma omp parallel for schedule(static) if (threads)
    for (int row = 0; row < rows; ++row)
        for (int c = 0; c < 3; ++c) {
            const std::size_t k = 3 * static_cast<std::size_t>(row) + c;
            const double value = inverseDiagonal[row] * (b[k] - (zeroGuess ? 0.0 : r[k]));
            r[k] = value;
            d[k] = value / theta;
            x[k] = (zeroGuess ? 0.0 : x[k]) + d[k];
        }
    for (int step = 1; step < degree; ++step) {
        // r −= D⁻¹ A d; d = ρ' ρ d + (2 ρ'/δ) r; x += d
        multiply(d, product);
        const double rhoNext = 1.0 / (2.0 * sigma - rho);
        const double keep = rhoNext * rho, push = 2.0 * rhoNext / delta;
#pragma omp parallel for schedule(static) if (threads)
        for (int row = 0; row < rows; ++row)
            for (int c = 0; c < 3; ++c) {
                const std::size_t k = 3 * static_cast<std::size_t>(row) + c;
                r[k] -= inverseDiagonal[row] * product[k];
                d[k] = keep * d[k] + push * r[k];
                x[k] += d[k];
            }
        rho = rhoNext;
    }
}

} // namespace rbm::motion
