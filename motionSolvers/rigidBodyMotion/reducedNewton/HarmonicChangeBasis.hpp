#pragma once
// The harmonic correction of the warm start's predictor, K⁻¹ (b(new) − b(base)), without a
// back-substitution: where the prescribed change (new − base on the prescribed nodes) is a
// combination of the changes met before, the same combination of their extensions K⁻¹ B. On
// a rigid body's boundary every change lies in one small space (2D: the body's points, their
// turn by 90° and the two translations, four vectors), so after the first steps of a time
// series none needs a solve. Only where K⁻¹ is one fixed linear map (a factorisation, or the
// 3D cycle without sliding nodes, not an inner iteration) and the boundary enters b linearly
// (no sliding offsets), and where the kept extensions stay small against the problem.

#include "LaplacianPreconditioner.hpp"
#include "RbmProblem.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

class HarmonicChangeBasis {
public:
    // enabled false: correctionFromBasis() always declines (a back-substitution at every step, for tests).
    HarmonicChangeBasis(const RbmProblem& problem, const LaplacianPreconditioner& preconditioner, bool enabled)
        : problem_(problem), preconditioner_(preconditioner), enabled_(enabled)
    {
    }

    // correction ← K⁻¹ (b(prescribed) − b(base)) (compact) from the basis; boundaryChange ← the
    // prescribed change (dimension() entries per prescribed node), empty where not applicable.
    // False where not applicable or where the change leaves the basis: then the caller solves
    // and hands the result to remember().
    bool correctionFromBasis(std::span<const Vector3> prescribed, std::span<const Vector3> base,
                             std::vector<double>& boundaryChange, std::vector<double>& correction);
    // Adds the part of boundaryChange outside the basis and its extension (from correction, the
    // solved K⁻¹ B of the whole change) while the basis has room.
    void remember(std::vector<double> boundaryChange, std::span<const double> correction);

    std::size_t size() const { return harmonicBasis_.size(); }
    int correctionsFromBasis() const { return correctionsFromBasis_; }

    // A change below this share of the displacements themselves is rounding: no correction.
    static constexpr double roundingChangeShare = 1e-12;

private:
    const RbmProblem& problem_;
    const LaplacianPreconditioner& preconditioner_;
    bool enabled_;
    // Orthonormal prescribed changes (dimension() entries per prescribed node, in
    // prescribedNodes_ order) and K⁻¹ B of each (compact); at most 12 (a 3D rigid motion's
    // space), kept only while one extension has at most maximumHarmonicBasisEntries entries.
    std::vector<int> prescribedNodes_;
    std::vector<std::vector<double>> boundaryBasis_, harmonicBasis_;
    static constexpr std::size_t maximumHarmonicBasisSize = 12;
    static constexpr std::size_t maximumHarmonicBasisEntries = 1 << 20;  // 8 MiB an extension, 96 MiB at most
    // A change counts as a combination when what is left outside the basis is below this share
    // of it (rounding of rotated coordinates is about 1e-13 of the change; the start only needs
    // to be close, Newton ends at the same minimum).
    static constexpr double harmonicBasisTolerance = 1e-9;
    int correctionsFromBasis_ = 0;
};

} // namespace rbm::motion
