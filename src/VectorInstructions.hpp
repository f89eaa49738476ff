#pragma once
// Whether the AVX2 variants of rbm's hottest loops may run (ReducedHessian3D's products,
// ThreeVectorMultigrid's matrix products). They are compiled next to baseline x86-64 (SSE2)
// variants with GCC's target attribute and chosen at run time, so the program still runs on a
// CPU without AVX. Neither variant uses FMA, so both round lane by lane as the scalar formulas
// and give the same result bit for bit; tests switch AVX2 off to check exactly that. AVX2
// rather than AVX: the kernels broadcast lanes often, and AVX2 does that in one instruction
// (vpermpd) where AVX needs two shuffles, which shows in the whole 3D solve (rbmBenchmark's
// twist3D case).

namespace rbm {

// Tests' switch (true by default).
inline bool& avxKernelsAllowed()
{
    static bool allowed = true;
    return allowed;
}

// The CPU has AVX2 and the switch allows it.
inline bool useAvxKernels()
{
#if defined(__x86_64__)
    static const bool available = __builtin_cpu_supports("avx2");
    return available && avxKernelsAllowed();
#else
    return false;
#endif
}

} // namespace rbm
