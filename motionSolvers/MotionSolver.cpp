#include "MotionSolver.hpp"

#include <stdexcept>
#include <string>

namespace rbm::motion {

MotionSolver::MotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients,
                           std::unique_ptr<BoundaryConditions> conditions, std::filesystem::path caseDirectory)
    : mesh_(mesh), coefficients_(coefficients), caseDirectory_(std::move(caseDirectory)), points0_(mesh.points),
      pointDisplacement_(mesh.points.size()), conditions_(std::move(conditions))
{
    if (!conditions_) throw std::invalid_argument("MotionSolver: no boundary conditions given");
    // Conditions that do not depend on time hold their values from the start, so a host that
    // only calls setPatchDisplacement sees the fixedValue patches of the field file.
    conditions_->initialise(points0_, pointDisplacement_);
    boundary_ = conditions_->describe();
}

MotionSolver::MotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients, BoundaryDescription boundary,
                           std::filesystem::path caseDirectory)
    : mesh_(mesh), coefficients_(coefficients), caseDirectory_(std::move(caseDirectory)), points0_(mesh.points),
      pointDisplacement_(mesh.points.size()), boundary_(std::move(boundary))
{
    if (boundary_.size() != mesh_.patches.size())
        throw std::invalid_argument("MotionSolver: the boundary description has " + std::to_string(boundary_.size()) +
                                    " patches, the mesh " + std::to_string(mesh_.patches.size()));
    for (std::size_t p = 0; p < boundary_.size(); ++p) {
        const BoundaryPatchDescription& patch = boundary_[p];
        for (Label point : patch.meshPoints)
            if (point < 0 || point >= static_cast<Label>(points0_.size()))
                throw std::invalid_argument("MotionSolver: patch " + mesh_.patches[p].name + " names point " +
                                            std::to_string(point) + ", the mesh has " +
                                            std::to_string(points0_.size()));
        if (patch.nodeClass == BoundaryNodeClass::sliding && patch.slidingNormals.size() != patch.meshPoints.size())
            throw std::invalid_argument("MotionSolver: sliding patch " + mesh_.patches[p].name + " has " +
                                        std::to_string(patch.slidingNormals.size()) + " normals for " +
                                        std::to_string(patch.meshPoints.size()) + " points");
    }
}

MotionSolver::~MotionSolver() = default;

std::string MotionSolver::fitIntoMemory(const AvailableMemory&) { return {}; }

void MotionSolver::updateBoundaryConditions(double time)
{
    if (!conditions_)
        throw std::logic_error("updateBoundaryConditions: the host evaluates this solver's boundary conditions");
    conditions_->update(time, points0_, pointDisplacement_);
}

void MotionSolver::setPatchDisplacement(std::string_view patchName, std::span<const Vector3> displacement)
{
    if (!conditions_)
        throw std::logic_error("setPatchDisplacement: the host evaluates this solver's boundary conditions");
    if (conditions_->setPatchDisplacement(patchName, displacement, pointDisplacement_)) {
        boundary_ = conditions_->describe();
        ++boundaryRevision_;
    }
}

std::vector<Vector3> MotionSolver::curPoints() const
{
    std::vector<Vector3> points(points0_.size());
    for (std::size_t k = 0; k < points.size(); ++k) points[k] = points0_[k] + pointDisplacement_[k];
    return points;
}

void MotionSolver::movePoints(std::span<const Vector3> points)
{
    if (points.size() != points0_.size())
        throw std::invalid_argument("movePoints: " + std::to_string(points.size()) + " points given, the mesh has " +
                                    std::to_string(points0_.size()));
    // The reference stays points0 (OpenFOAM's displacement solvers): the mesh is now at
    // points0 + displacement.
    for (std::size_t k = 0; k < points.size(); ++k) pointDisplacement_[k] = points[k] - points0_[k];
}

void MotionSolver::updateMesh()
{
    throw std::logic_error(std::string(typeName()) + ": topology changes (updateMesh) are not supported");
}

} // namespace rbm::motion
