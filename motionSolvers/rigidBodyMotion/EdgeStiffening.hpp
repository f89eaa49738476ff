#pragma once
// The stiffening in effect (RigidBodyMotionOptions' `stiffening`, Stiffening.hpp's factors):
// the factor f_ij of every edge, computed once from the reference mesh, and the rule of
// `stiffening auto` that applies it only while every prescribed patch moves rigidly (a body
// moving in a fixed far field), not where a prescribed patch deforms (a bending wing), where
// it makes the mesh worse (docs/motionSolver.md, "Default stiffening").
//
// The factors are shared with the problems built from them (one array of about 200 bytes per
// cell in 3D instead of three).

#include "CellNeighbourGraph.hpp"
#include "PolyMesh.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RigidBodyMotionOptions.hpp"
#include "Vector3.hpp"

#include <memory>
#include <vector>

namespace rbm::motion {

class EdgeStiffening {
public:
    EdgeStiffening() = default;   // no stiffening
    // `referencePoints`: the problem's nodes (2D: planar nodes of `twoD`); `points0`: the
    // mesh's. Throws InputError (options.file, the stiffening entry's line) for a patch name
    // that is neither a patch nor a group of `mesh`.
    EdgeStiffening(const RigidBodyMotionOptions& options, const PolyMesh& mesh, const std::vector<Vector3>& points0,
                   const PseudoTwoDMesh* twoD, const CellNeighbourGraph& graph,
                   const std::vector<Vector3>& referencePoints, int dimension);

    // The factors in effect, per directed edge of the graph; null: no stiffening.
    const std::shared_ptr<const std::vector<double>>& factors() const { return inEffect_; }
    // The patches the distance is measured to (indices into mesh.patches).
    const std::vector<Label>& patches() const { return patches_; }
    // Whether `stiffening auto` decides per motion (followMotion below).
    bool automatic() const { return automatic_ != nullptr; }
    // `stiffening auto`: the factors for a motion whose prescribed patches do (not) all move
    // rigidly. Returns whether the factors in effect changed (the problem must be rebuilt).
    bool followMotion(bool allPatchesRigid);

private:
    std::shared_ptr<const std::vector<double>> inEffect_;
    std::shared_ptr<const std::vector<double>> automatic_;   // `stiffening auto`: the factors when applied
    std::vector<Label> patches_;
};

} // namespace rbm::motion
