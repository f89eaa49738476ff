#pragma once
// The prescribed displacement along a sub-step path, from `from` (fraction 0) to `to`
// (fraction 1). Prescribed nodes are grouped by the patch that prescribes them
// (groupNodes[groupOffsets[g] .. groupOffsets[g+1]), NodeClasses.hpp); a group whose motion
// from -> to is rigid moves along that rigid motion, so that a rotation is split into
// rotations, not chords (docs/method.md §4); the other groups move along straight lines.
//
// A group's motion counts as rigid when its best rigid fit (centroid translation + best
// rotation, the fit of the thesis' eq. 2.10 over the group) reproduces every node to 1e-9 of
// the group's size plus its largest move.

#include "Vector3.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

class BoundaryPath {
public:
    // `reference`: the nodes' reference positions (2D: frame coordinates, z ignored). The path
    // reads `from` and `to` where the caller keeps them (two arrays per node fewer): they
    // must outlive it, unchanged. An empty `from` is the reference mesh (zero everywhere).
    BoundaryPath(int dimension, const std::vector<Vector3>& reference, const std::vector<int>& groupOffsets,
                 const std::vector<int>& groupNodes, std::span<const Vector3> from, std::span<const Vector3> to);

    // The displacement of every node at `fraction` ∈ (0, 1] of the path (exactly `to` at 1).
    std::vector<Vector3> at(double fraction) const;

    // Whether every group's motion from -> to is rigid (to rounding; an empty group counts as rigid).
    bool allRigid() const;

    // The largest rotation angle (radians) of the groups that move rigidly.
    double largestRigidAngle() const;

private:
    struct GroupMotion {
        bool rigid = false;
        Vector3 centre;       // of the group at `from`
        Vector3 translation;  // of the centre
        Vector3 rotation;     // 2D: (0, 0, θ) counter-clockwise; 3D: rotation vector
    };

    Vector3 flat(Vector3 v) const;
    Vector3 fromOf(int node) const { return from_.empty() ? Vector3{} : from_[node]; }
    Vector3 position(int node, std::span<const Vector3> displacement) const;
    void fit(int group);

    int dimension_;
    const std::vector<Vector3>& reference_;
    const std::vector<int>& groupOffsets_;
    const std::vector<int>& groupNodes_;
    std::span<const Vector3> from_;
    std::span<const Vector3> to_;
    std::vector<GroupMotion> motions_;
};

} // namespace rbm::motion
