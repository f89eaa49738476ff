#pragma once
// K ⊗ I restricted to the sliding planes, factorised once: the reduced Newton solver's
// preconditioner (its K⁻¹) when the problem has sliding nodes.
//
// Without sliding nodes every displacement component sees the same scalar K (the displacement
// block of the Hessian, a weighted graph Laplacian), factorised once and back-substituted per
// component. A sliding node couples its components: only its displacement along its plane (or
// line) is free, so the operator is P (K ⊗ I) P, P the projection onto the planes. Its normals
// are those of the reference mesh and never change during a run, so this operator too is one
// fixed matrix: in each sliding node's own orthonormal frame (the admissible directions
// first, then the normal ones) it is Qᵀ (K ⊗ I) Q with the normal rows and columns replaced by
// the identity, symmetric positive definite and as sparse as K ⊗ I. It is factorised once per
// problem, like the scalar K, so that a step with sliding walls costs what a step without them
// costs, instead of an iterative or multifrontal solve of the vector system per application.

#include "RbmProblem.hpp"
#include "SparseCholesky.hpp"

#include <array>
#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

class ProjectedLaplacianFactor {
public:
    // `laplacian`: K's values on problem.blockPattern() (one scalar per position).
    ProjectedLaplacianFactor(const RbmProblem& problem, std::span<const double> laplacian,
                             FactorPrecision precision = FactorPrecision::single);

    // z = P (P (K ⊗ I) P)⁻¹ P r on the compact displacement vectors (unknown nodes × dimension,
    // interleaved by node); r and z may not overlap.
    void solve(std::span<const double> r, std::span<double> z) const;

private:
    int dimension_ = 2;
    int nodeCount_ = 0;
    // Per unknown node: its frame's columns (admissible directions first) and how many are admissible.
    std::vector<std::array<Vector3, 3>> frame_;
    std::vector<int> admissible_;
    std::unique_ptr<SparseCholesky> factor_;
    mutable std::vector<double> local_;
};

} // namespace rbm::motion
