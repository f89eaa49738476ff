#pragma once
// The boundary conditions of a motion solver when rbm evaluates them itself (rbmMoveMesh's
// front door: boundaryMotion/PatchBoundaryConditions.hpp, from 0/pointDisplacement). A host
// that evaluates its own conditions (the OpenFOAM plugin) has none: it hands MotionSolver a
// BoundaryDescription and writes the prescribed values into pointDisplacement() itself.
// Declared here, below the implementations, so that the solvers need no boundary-condition
// code.

#include "BoundaryDescription.hpp"
#include "Vector3.hpp"

#include <span>
#include <string_view>

namespace rbm::motion {

class BoundaryConditions {
public:
    virtual ~BoundaryConditions() = default;

    // Node classes and sliding planes, one entry per mesh patch.
    virtual BoundaryDescription describe() const = 0;
    // The prescribed values that do not depend on time (a host that only sets some patches
    // still sees the fixed ones), written into `displacement` (one per mesh point).
    virtual void initialise(std::span<const Vector3> points0, std::span<Vector3> displacement) const = 0;
    // Every condition at `time`: sliding points lose their normal displacement, then the
    // prescribed points get their values (prescribed beats sliding).
    virtual void update(double time, std::span<const Vector3> points0, std::span<Vector3> displacement) const = 0;
    // From now on the patch's points take `values` (localPoints order), written into
    // `displacement` at once. Returns true when describe() changed. Throws
    // std::invalid_argument for an unknown patch, a 2D plane or a wrong length.
    virtual bool setPatchDisplacement(std::string_view patchName, std::span<const Vector3> values,
                                      std::span<Vector3> displacement) = 0;
};

} // namespace rbm::motion
