#include "MotionSolver.hpp"

#include "InputError.hpp"
#include "PointPatchDisplacement.hpp"

#include <algorithm>
#include <stdexcept>

namespace rbm::motion {

namespace {

// A patch whose displacement a host program sets directly (setPatchDisplacement): prescribed,
// holds the last values it was given.
class HostPrescribedDisplacement final : public PointPatchDisplacement {
public:
    HostPrescribedDisplacement(const PointPatchContext& context, std::span<const Vector3> values)
        : PointPatchDisplacement(context, "hostPrescribed"), values_(values.begin(), values.end())
    {}
    PatchNodeClass nodeClass() const override { return PatchNodeClass::prescribed; }
    void evaluate(double, std::span<const Vector3>, std::span<Vector3> displacement) const override
    {
        std::copy(values_.begin(), values_.end(), displacement.begin());
    }
    void setValues(std::span<const Vector3> values) { std::copy(values.begin(), values.end(), values_.begin()); }

private:
    std::vector<Vector3> values_;
};

// Every patch fixedValue zero; constraint patches (empty, wedge, symmetryPlane, symmetry)
// take their own type by OpenFOAM's constraint-patch rule (pointPatchField::New).
io::Dictionary defaultPointDisplacement(const std::filesystem::path& caseDirectory)
{
    return io::Dictionary::parseText("boundaryField { \".*\" { type fixedValue; value uniform (0 0 0); } }",
                                     (caseDirectory / "0" / "pointDisplacement").string() + " (default: fixedValue 0)");
}

std::string patchNames(const PolyMesh& mesh)
{
    std::string names;
    for (const Patch& patch : mesh.patches) names += (names.empty() ? "" : " ") + patch.name;
    return names;
}

} // namespace

MotionSolver::MotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients,
                           const io::Dictionary* pointDisplacement, std::filesystem::path caseDirectory)
    : mesh_(mesh), coefficients_(coefficients), caseDirectory_(std::move(caseDirectory)), points0_(mesh.points),
      pointDisplacement_(mesh.points.size())
{
    if (pointDisplacement) {
        patchConditions_ = readPointPatchDisplacements(*pointDisplacement, mesh_, caseDirectory_, points0_);
    } else {
        patchConditions_ = readPointPatchDisplacements(defaultPointDisplacement(caseDirectory_), mesh_, caseDirectory_,
                                                       points0_);
    }
    // Conditions that do not depend on time hold their values from the start, so a host that
    // only calls setPatchDisplacement sees the fixedValue patches of the field file.
    for (const auto& condition : patchConditions_) {
        if (condition->nodeClass() == PatchNodeClass::prescribed && !condition->isTimeDependent())
            condition->evaluateOnMesh(0.0, points0_, pointDisplacement_);
    }
    describeBoundary();
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

void MotionSolver::describeBoundary()
{
    boundary_.clear();
    boundary_.reserve(patchConditions_.size());
    for (const auto& condition : patchConditions_) {
        BoundaryPatchDescription patch;
        patch.meshPoints = condition->meshPoints();
        switch (condition->nodeClass()) {
        case PatchNodeClass::prescribed: patch.nodeClass = BoundaryNodeClass::prescribed; break;
        case PatchNodeClass::free: patch.nodeClass = BoundaryNodeClass::free; break;
        case PatchNodeClass::ignored: patch.nodeClass = BoundaryNodeClass::ignored; break;
        case PatchNodeClass::sliding:
            patch.nodeClass = BoundaryNodeClass::sliding;
            patch.mirror = condition->isMirrorPlane();
            patch.slidingNormals.resize(patch.meshPoints.size());
            for (std::size_t k = 0; k < patch.meshPoints.size(); ++k)
                patch.slidingNormals[k] = condition->slidingNormal(static_cast<Label>(k));
            break;
        }
        boundary_.push_back(std::move(patch));
    }
}

MotionSolver::~MotionSolver() = default;

void MotionSolver::updateBoundaryConditions(double time)
{
    if (patchConditions_.empty() && !boundary_.empty())
        throw std::logic_error("updateBoundaryConditions: the host evaluates this solver's boundary conditions");
    // Sliding points keep no normal displacement (their plane passes through their reference
    // position); prescribed patches are evaluated afterwards, so a point on a prescribed and a
    // sliding patch gets the prescribed value (prescribed beats sliding).
    for (const auto& condition : patchConditions_) {
        if (condition->nodeClass() != PatchNodeClass::sliding) continue;
        const std::vector<Label>& points = condition->meshPoints();
        for (std::size_t k = 0; k < points.size(); ++k) {
            const Vector3 normal = condition->slidingNormal(static_cast<Label>(k));
            Vector3& u = pointDisplacement_[points[k]];
            u -= dot(u, normal) * normal;
        }
    }
    for (const auto& condition : patchConditions_) {
        if (condition->nodeClass() == PatchNodeClass::prescribed)
            condition->evaluateOnMesh(time, points0_, pointDisplacement_);
    }
}

void MotionSolver::setPatchDisplacement(std::string_view patchName, std::span<const Vector3> displacement)
{
    if (patchConditions_.empty() && !boundary_.empty())
        throw std::logic_error("setPatchDisplacement: the host evaluates this solver's boundary conditions");
    const Label patchIndex = mesh_.findPatch(std::string(patchName));
    if (patchIndex < 0)
        throw std::invalid_argument("setPatchDisplacement: unknown patch " + std::string(patchName) +
                                    ". Valid patches are: " + patchNames(mesh_));
    const Patch& patch = mesh_.patches[patchIndex];
    if (patch.type == "empty" || patch.type == "wedge")
        throw std::invalid_argument("setPatchDisplacement: patch " + patch.name + " is of type " + patch.type +
                                    ", whose points follow the 2D solution");
    std::unique_ptr<PointPatchDisplacement>& condition = patchConditions_[static_cast<std::size_t>(patchIndex)];
    if (static_cast<std::size_t>(condition->pointCount()) != displacement.size())
        throw std::invalid_argument("setPatchDisplacement: patch " + patch.name + " has " +
                                    std::to_string(condition->pointCount()) + " points but " +
                                    std::to_string(displacement.size()) +
                                    " displacements were given (one per point, in the patch's localPoints order)");
    if (auto* host = dynamic_cast<HostPrescribedDisplacement*>(condition.get())) {
        host->setValues(displacement);
    } else {
        const PointPatchContext context = PointPatchContext::forPatch(mesh_, patchIndex, points0_, caseDirectory_);
        condition = std::make_unique<HostPrescribedDisplacement>(context, displacement);
        describeBoundary();
    }
    const std::vector<Label>& points = condition->meshPoints();
    for (std::size_t k = 0; k < points.size(); ++k) pointDisplacement_[points[k]] = displacement[k];
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
