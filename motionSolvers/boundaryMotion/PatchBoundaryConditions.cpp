#include "PatchBoundaryConditions.hpp"

#include "InputError.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

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

} // namespace

PatchBoundaryConditions::PatchBoundaryConditions(const PolyMesh& mesh, const io::Dictionary* pointDisplacement,
                                                 std::filesystem::path caseDirectory,
                                                 const PointPatchDisplacementRegistry& registry)
    : mesh_(mesh), caseDirectory_(std::move(caseDirectory))
{
    conditions_ = readPointPatchDisplacements(pointDisplacement ? *pointDisplacement
                                                                : defaultPointDisplacement(caseDirectory_),
                                              mesh_, caseDirectory_, mesh_.points, registry);
}

BoundaryDescription PatchBoundaryConditions::describe() const
{
    BoundaryDescription boundary;
    boundary.reserve(conditions_.size());
    for (const auto& condition : conditions_) {
        BoundaryPatchDescription patch;
        patch.meshPoints = condition->meshPoints();
        switch (condition->nodeClass()) {
        case PatchNodeClass::prescribed: patch.nodeClass = BoundaryNodeClass::prescribed; break;
        case PatchNodeClass::free: patch.nodeClass = BoundaryNodeClass::free; break;
        case PatchNodeClass::ignored: patch.nodeClass = BoundaryNodeClass::ignored; break;
        case PatchNodeClass::coupled: patch.nodeClass = BoundaryNodeClass::coupled; break;
        case PatchNodeClass::sliding:
            patch.nodeClass = BoundaryNodeClass::sliding;
            patch.mirror = condition->isMirrorPlane();
            patch.slidingNormals.resize(patch.meshPoints.size());
            for (std::size_t k = 0; k < patch.meshPoints.size(); ++k)
                patch.slidingNormals[k] = condition->slidingNormal(static_cast<Label>(k));
            break;
        }
        boundary.push_back(std::move(patch));
    }
    return boundary;
}

void PatchBoundaryConditions::initialise(std::span<const Vector3> points0, std::span<Vector3> displacement) const
{
    for (const auto& condition : conditions_) {
        if (condition->nodeClass() == PatchNodeClass::prescribed && !condition->isTimeDependent())
            condition->evaluateOnMesh(0.0, points0, displacement);
    }
}

void PatchBoundaryConditions::update(double time, std::span<const Vector3> points0, std::span<Vector3> displacement) const
{
    // Sliding points keep no normal displacement (their plane passes through their reference
    // position); prescribed patches are evaluated afterwards, so a point on a prescribed and a
    // sliding patch gets the prescribed value (prescribed beats sliding).
    for (const auto& condition : conditions_) {
        if (condition->nodeClass() != PatchNodeClass::sliding) continue;
        const std::vector<Label>& points = condition->meshPoints();
        for (std::size_t k = 0; k < points.size(); ++k) {
            const Vector3 normal = condition->slidingNormal(static_cast<Label>(k));
            Vector3& u = displacement[points[k]];
            u -= dot(u, normal) * normal;
        }
    }
    for (const auto& condition : conditions_) {
        if (condition->nodeClass() == PatchNodeClass::prescribed) condition->evaluateOnMesh(time, points0, displacement);
    }
}

bool PatchBoundaryConditions::setPatchDisplacement(std::string_view patchName, std::span<const Vector3> values,
                                                   std::span<Vector3> displacement)
{
    const Label patchIndex = mesh_.findPatch(std::string(patchName));
    if (patchIndex < 0)
        throw std::invalid_argument("setPatchDisplacement: unknown patch " + std::string(patchName) +
                                    ". Valid patches are: " + patchNameList(mesh_));
    const Patch& patch = mesh_.patches[patchIndex];
    if (patch.type == "empty" || patch.type == "wedge")
        throw std::invalid_argument("setPatchDisplacement: patch " + patch.name + " is of type " + patch.type +
                                    ", whose points follow the 2D solution");
    std::unique_ptr<PointPatchDisplacement>& condition = conditions_[static_cast<std::size_t>(patchIndex)];
    if (static_cast<std::size_t>(condition->pointCount()) != values.size())
        throw std::invalid_argument("setPatchDisplacement: patch " + patch.name + " has " +
                                    std::to_string(condition->pointCount()) + " points but " +
                                    std::to_string(values.size()) +
                                    " displacements were given (one per point, in the patch's localPoints order)");
    bool changed = false;
    if (auto* host = dynamic_cast<HostPrescribedDisplacement*>(condition.get())) {
        host->setValues(values);
    } else {
        const PointPatchContext context = PointPatchContext::forPatch(mesh_, patchIndex, mesh_.points, caseDirectory_);
        condition = std::make_unique<HostPrescribedDisplacement>(context, values);
        changed = true;
    }
    const std::vector<Label>& points = condition->meshPoints();
    for (std::size_t k = 0; k < points.size(); ++k) displacement[points[k]] = values[k];
    return changed;
}

std::unique_ptr<BoundaryConditions> makePatchBoundaryConditions(const PolyMesh& mesh,
                                                                const io::Dictionary* pointDisplacement,
                                                                const std::filesystem::path& caseDirectory)
{
    return std::make_unique<PatchBoundaryConditions>(mesh, pointDisplacement, caseDirectory);
}

} // namespace rbm::motion
