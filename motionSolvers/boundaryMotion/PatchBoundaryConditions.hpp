#pragma once
// rbm's own boundary conditions of a point displacement field (PointPatchDisplacement.hpp,
// one per mesh patch) as a motion solver's BoundaryConditions: what rbmMoveMesh and the C++
// API (setPatchDisplacement) drive the solver with.

#include "BoundaryConditions.hpp"
#include "FoamDictionary.hpp"
#include "PointPatchDisplacement.hpp"
#include "PolyMesh.hpp"

#include <filesystem>
#include <memory>
#include <vector>

namespace rbm::motion {

class PatchBoundaryConditions final : public BoundaryConditions {
public:
    // `pointDisplacement`: the field dictionary (0/pointDisplacement); nullptr means every patch
    // fixedValue zero (constraint patches such as empty take their own type) until a host calls
    // setPatchDisplacement. The reference points are mesh.points; the mesh must outlive this.
    // Throws rbm::InputError for bad conditions.
    // `registry`: the condition types (decomposedPointPatchDisplacements for one rank's part).
    PatchBoundaryConditions(const PolyMesh& mesh, const io::Dictionary* pointDisplacement,
                            std::filesystem::path caseDirectory,
                            const PointPatchDisplacementRegistry& registry = builtinPointPatchDisplacements());

    BoundaryDescription describe() const override;
    void initialise(std::span<const Vector3> points0, std::span<Vector3> displacement) const override;
    void update(double time, std::span<const Vector3> points0, std::span<Vector3> displacement) const override;
    bool setPatchDisplacement(std::string_view patchName, std::span<const Vector3> values,
                              std::span<Vector3> displacement) override;

private:
    const PolyMesh& mesh_;
    std::filesystem::path caseDirectory_;
    std::vector<std::unique_ptr<PointPatchDisplacement>> conditions_;  // one per mesh patch
};

// The same as a unique_ptr, for MotionSolver's constructor.
std::unique_ptr<BoundaryConditions> makePatchBoundaryConditions(const PolyMesh& mesh,
                                                                const io::Dictionary* pointDisplacement,
                                                                const std::filesystem::path& caseDirectory);

} // namespace rbm::motion
