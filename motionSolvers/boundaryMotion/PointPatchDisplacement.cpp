// OpenFOAM v1912 point-patch boundary conditions of the displacement field. See the header for
// the types, their node classes and the matching rules.

#include "PointPatchDisplacement.hpp"

#include "Function1.hpp"
#include "InputError.hpp"
#include "PatchNormals.hpp"
#include "Rotation.hpp"
#include "SolidBodyMotion.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

namespace rbm::motion {

namespace {

constexpr double small = 1e-15;     // OpenFOAM SMALL

std::string joinNames(const std::vector<std::string>& names)
{
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : " ") + n;
    return out;
}

std::string patchWhere(const PointPatchContext& context)
{
    return "patch " + context.patch().name + (context.file.empty() ? std::string() : " in file " + context.file);
}

// ---------------------------------------------------------------------------------------
// Prescribed types

class FixedValue final : public PointPatchDisplacement {
public:
    FixedValue(const io::Dictionary& dict, const PointPatchContext& context)
        : PointPatchDisplacement(context, "fixedValue")
    {
        if (!dict.contains("value"))
            throw InputError(dict.file(), dict.line(),
                             "keyword 'value' is undefined for fixedValue " + patchWhere(context) +
                                 ": expected 'value uniform (x y z);' or 'value nonuniform List<vector> N(...);'");
        values_ = readPatchVectorField(dict, "value", context);
    }
    PatchNodeClass nodeClass() const override { return PatchNodeClass::prescribed; }
    void evaluate(double, std::span<const Vector3>, std::span<Vector3> displacement) const override
    {
        std::copy(values_.begin(), values_.end(), displacement.begin());
    }

private:
    std::vector<Vector3> values_;
};

class UniformFixedValue final : public PointPatchDisplacement {
public:
    UniformFixedValue(const io::Dictionary& dict, const PointPatchContext& context)
        : PointPatchDisplacement(context, "uniformFixedValue"),
          uniformValue_(Function1<Vector3>::New("uniformValue", dict, context.caseDirectory))
    {}
    PatchNodeClass nodeClass() const override { return PatchNodeClass::prescribed; }
    bool isTimeDependent() const override { return !uniformValue_->isConstant(); }
    void evaluate(double t, std::span<const Vector3>, std::span<Vector3> displacement) const override
    {
        std::fill(displacement.begin(), displacement.end(), uniformValue_->value(t));
    }

private:
    std::unique_ptr<Function1<Vector3>> uniformValue_;
};

class OscillatingDisplacement final : public PointPatchDisplacement {
public:
    OscillatingDisplacement(const io::Dictionary& dict, const PointPatchContext& context)
        : PointPatchDisplacement(context, "oscillatingDisplacement"), amplitude_(dict.get<Vector3>("amplitude")),
          omega_(dict.get<double>("omega"))
    {}
    PatchNodeClass nodeClass() const override { return PatchNodeClass::prescribed; }
    bool isTimeDependent() const override { return true; }
    void evaluate(double t, std::span<const Vector3>, std::span<Vector3> displacement) const override
    {
        // amplitude_*sin(omega_*t)
        std::fill(displacement.begin(), displacement.end(), amplitude_ * std::sin(omega_ * t));
    }

private:
    Vector3 amplitude_;
    double omega_;
};

class AngularOscillatingDisplacement final : public PointPatchDisplacement {
public:
    AngularOscillatingDisplacement(const io::Dictionary& dict, const PointPatchContext& context)
        : PointPatchDisplacement(context, "angularOscillatingDisplacement"), axis_(dict.get<Vector3>("axis")),
          origin_(dict.get<Vector3>("origin")), angle0_(dict.get<double>("angle0")),
          amplitude_(dict.get<double>("amplitude")), omega_(dict.get<double>("omega"))
    {
        if (!(norm(axis_) > 0.0)) {
            const io::Entry& entry = dict.lookup("axis");
            throw InputError(entry.file(), entry.line(),
                             "angularOscillatingDisplacement " + patchWhere(context) + ": 'axis' must be non-zero");
        }
        if (dict.contains("p0")) p0_ = readPatchVectorField(dict, "p0", context);
    }
    PatchNodeClass nodeClass() const override { return PatchNodeClass::prescribed; }
    bool isTimeDependent() const override { return true; }
    void evaluate(double t, std::span<const Vector3> patchPoints0, std::span<Vector3> displacement) const override
    {
        // angle = angle0_ + amplitude_*sin(omega_*t); axisHat = axis_/mag(axis_); p0Rel = p0_ - origin_;
        // p0Rel*(cos(angle) - 1) + (axisHat ^ p0Rel*sin(angle)) + (axisHat & p0Rel)*(1 - cos(angle))*axisHat
        const double angle = angle0_ + amplitude_ * std::sin(omega_ * t);
        const Vector3 axisHat = axis_ / norm(axis_);
        const double c = std::cos(angle);
        const double s = std::sin(angle);
        const std::span<const Vector3> p0 = p0_.empty() ? patchPoints0 : std::span<const Vector3>(p0_);
        for (std::size_t i = 0; i < displacement.size(); ++i) {
            const Vector3 p0Rel = p0[i] - origin_;
            displacement[i] = p0Rel * (c - 1.0) + cross(axisHat, p0Rel * s) + dot(axisHat, p0Rel) * (1.0 - c) * axisHat;
        }
    }

private:
    Vector3 axis_;
    Vector3 origin_;
    double angle0_;
    double amplitude_;
    double omega_;
    std::vector<Vector3> p0_;   // empty: the reference points
};

class SolidBodyMotionDisplacement final : public PointPatchDisplacement {
public:
    SolidBodyMotionDisplacement(const io::Dictionary& dict, const PointPatchContext& context)
        : PointPatchDisplacement(context, "solidBodyMotionDisplacement"),
          motion_(SolidBodyMotion::New(dict, context.caseDirectory))
    {}
    PatchNodeClass nodeClass() const override { return PatchNodeClass::prescribed; }
    bool isTimeDependent() const override { return true; }
    void evaluate(double t, std::span<const Vector3> patchPoints0, std::span<Vector3> displacement) const override
    {
        // transformPoints(SBMFPtr_().transformation(), localPoints0()) - localPoints0()
        motion_->displacements(t, patchPoints0, displacement);
    }

private:
    std::unique_ptr<SolidBodyMotion> motion_;
};

// ---------------------------------------------------------------------------------------
// Free, ignored and sliding types

class Unconstrained final : public PointPatchDisplacement {
public:
    Unconstrained(const PointPatchContext& context, std::string type, PatchNodeClass nodeClass)
        : PointPatchDisplacement(context, std::move(type)), nodeClass_(nodeClass)
    {}
    PatchNodeClass nodeClass() const override { return nodeClass_; }

private:
    PatchNodeClass nodeClass_;
};

class Sliding final : public PointPatchDisplacement {
public:
    // One normal per patch point, or a single normal for all.
    Sliding(const PointPatchContext& context, std::string type, std::vector<Vector3> normals)
        : PointPatchDisplacement(context, std::move(type)), normals_(std::move(normals)),
          isMirror_(this->type() == "symmetry" || this->type() == "symmetryPlane")
    {}
    PatchNodeClass nodeClass() const override { return PatchNodeClass::sliding; }
    bool isMirrorPlane() const override { return isMirror_; }
    Vector3 slidingNormal(Label patchPoint) const override
    {
        return normals_.size() == 1 ? normals_.front() : normals_.at(static_cast<std::size_t>(patchPoint));
    }

private:
    std::vector<Vector3> normals_;
    bool isMirror_;
};

std::unique_ptr<PointPatchDisplacement> makePointNormalSliding(const PointPatchContext& context, std::string type)
{
    return std::make_unique<Sliding>(
        context, std::move(type),
        patchPointNormals(*context.mesh, context.patchIndex, context.meshPoints, context.referencePoints()));
}

bool isUnsupportedConstraintPatchType(const std::string& type)
{
    // Coupled and interface patches other than plain cyclic: their sides would move apart.
    static const std::vector<std::string> unsupported{"cyclicAMI",         "cyclicACMI",      "cyclicSlip",
                                                      "cyclicPeriodicAMI", "cyclicRepeatAMI", "nonuniformTransformCyclic",
                                                      "processor",         "processorCyclic"};
    return std::find(unsupported.begin(), unsupported.end(), type) != unsupported.end() ||
           type.rfind("nonConformal", 0) == 0;
}

} // namespace

// ---------------------------------------------------------------------------------------

std::string_view patchNodeClassName(PatchNodeClass nodeClass)
{
    switch (nodeClass) {
    case PatchNodeClass::prescribed: return "prescribed";
    case PatchNodeClass::sliding: return "sliding";
    case PatchNodeClass::free: return "free";
    case PatchNodeClass::ignored: return "ignored";
    case PatchNodeClass::coupled: return "coupled";
    }
    return "unknown";
}

Vector3 patchPlaneNormal(const PolyMesh& mesh, Label patchIndex, std::span<const Vector3> points, const std::string& file)
{
    const Patch& patch = mesh.patches.at(static_cast<std::size_t>(patchIndex));
    if (patch.faceCount == 0) return {};
    Vector3 average{};
    for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) average += faceUnitNormal(mesh.face(f), points);
    average /= static_cast<double>(patch.faceCount);
    for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
        const Vector3 n = faceUnitNormal(mesh.face(f), points);
        if (normSquared(n - average) > small) {
            std::ostringstream message;
            message << "symmetry plane '" << patch.name << "' is not planar: the normal " << n << " of its local face "
                    << (f - patch.startFace) << " differs from the average normal " << average << " by "
                    << normSquared(n - average)
                    << " (squared; OpenFOAM allows 1e-15). Split the patch into planar parts or use the symmetry type";
            throw InputError(file, 0, message.str());
        }
    }
    return average / norm(average);
}

PointPatchContext PointPatchContext::forPatch(const PolyMesh& mesh, Label patchIndex, std::span<const Vector3> points0,
                                              std::filesystem::path caseDirectory, io::FoamFileHeader header,
                                              std::string file)
{
    PointPatchContext context;
    context.mesh = &mesh;
    context.patchIndex = patchIndex;
    context.meshPoints = patchMeshPoints(mesh, patchIndex);
    context.points0 = points0;
    context.caseDirectory = std::move(caseDirectory);
    context.header = std::move(header);
    context.file = std::move(file);
    return context;
}

// ---------------------------------------------------------------------------------------

void PointPatchDisplacement::evaluate(double, std::span<const Vector3>, std::span<Vector3>) const
{
    throw std::logic_error("patch " + patchName_ + ": boundary condition " + type_ + " is " +
                           std::string(patchNodeClassName(nodeClass())) + ", not prescribed; it has no displacement to evaluate");
}

void PointPatchDisplacement::evaluateOnMesh(double t, std::span<const Vector3> points0, std::span<Vector3> displacement) const
{
    std::vector<Vector3> local0(meshPoints_.size());
    std::vector<Vector3> localDisplacement(meshPoints_.size());
    for (std::size_t i = 0; i < meshPoints_.size(); ++i) local0[i] = points0[static_cast<std::size_t>(meshPoints_[i])];
    evaluate(t, local0, localDisplacement);
    for (std::size_t i = 0; i < meshPoints_.size(); ++i)
        displacement[static_cast<std::size_t>(meshPoints_[i])] = localDisplacement[i];
}

Vector3 PointPatchDisplacement::slidingNormal(Label) const
{
    throw std::logic_error("patch " + patchName_ + ": boundary condition " + type_ + " is " +
                           std::string(patchNodeClassName(nodeClass())) + ", not sliding; it has no sliding normal");
}

// ---------------------------------------------------------------------------------------

void PointPatchDisplacementRegistry::add(std::string type, Factory factory, std::string constraintType)
{
    entries_[std::move(type)] = Registered{std::move(factory), std::move(constraintType)};
}

std::vector<std::string> PointPatchDisplacementRegistry::types() const
{
    std::vector<std::string> names;
    for (const auto& [name, entry] : entries_) names.push_back(name);
    return names;
}

std::unique_ptr<PointPatchDisplacement> PointPatchDisplacementRegistry::create(const io::Dictionary& patchDictionary,
                                                                              const PointPatchContext& context) const
{
    const Patch& patch = context.patch();
    const std::string where = context.file.empty() ? patchDictionary.file() : context.file;
    const io::Entry* typeEntry = patchDictionary.find("type");
    if (!typeEntry)
        throw InputError(patchDictionary.file(), patchDictionary.line(),
                         "keyword 'type' is undefined for patch " + patch.name + " in file " + where +
                             ". Valid patchField types are: " + joinNames(types()));
    const std::string type = patchDictionary.get<std::string>("type");
    const auto found = entries_.find(type);
    if (found == entries_.end())
        throw InputError(typeEntry->file(), typeEntry->line(),
                         "Unknown patchField type " + type + " for patch " + patch.name + " in file " + where +
                             ". Valid patchField types are: " + joinNames(types()));

    // OpenFOAM pointPatchField::New: a constraint patch imposes its own field type.
    const auto patchTypeEntry = entries_.find(patch.type);
    const std::string patchConstraint =
        (patchTypeEntry != entries_.end() && patchTypeEntry->second.constraintType == patch.type) ? patch.type : "";
    // A registry that takes one of these types on (decomposedPointPatchDisplacements: the
    // processor patches of one rank's part) lists it as a constraint type.
    if (patchConstraint.empty() && isUnsupportedConstraintPatchType(patch.type))
        throw InputError(typeEntry->file(), typeEntry->line(),
                         "patch " + patch.name + " has the mesh patch type " + patch.type +
                             ", which rbm does not support for mesh motion" +
                             (patch.type == "processor" ? std::string(" in a serial run (a decomposed case moves with "
                                                                      "rbmMoveMesh -parallel under mpirun)")
                                                        : std::string()));
    const bool patchTypeOverride = patchDictionary.contains("patchType") &&
                                   patchDictionary.get<std::string>("patchType") == patch.type;
    if (!patchTypeOverride && found->second.constraintType != patchConstraint) {
        if (patchConstraint.empty())
            throw InputError(typeEntry->file(), typeEntry->line(),
                             "inconsistent patch and patchField types for patch " + patch.name + " in file " + where +
                                 ": patch type " + patch.type + " and patchField type " + type);
        return patchTypeEntry->second.factory(patchDictionary, context);
    }
    return found->second.factory(patchDictionary, context);
}

void registerBuiltinPointPatchDisplacements(PointPatchDisplacementRegistry& registry)
{
    auto make = [](auto factory) { return PointPatchDisplacementRegistry::Factory(factory); };
    registry.add("fixedValue", make([](const io::Dictionary& d, const PointPatchContext& c) {
                     return std::unique_ptr<PointPatchDisplacement>(std::make_unique<FixedValue>(d, c));
                 }));
    registry.add("uniformFixedValue", make([](const io::Dictionary& d, const PointPatchContext& c) {
                     return std::unique_ptr<PointPatchDisplacement>(std::make_unique<UniformFixedValue>(d, c));
                 }));
    registry.add("oscillatingDisplacement", make([](const io::Dictionary& d, const PointPatchContext& c) {
                     return std::unique_ptr<PointPatchDisplacement>(std::make_unique<OscillatingDisplacement>(d, c));
                 }));
    registry.add("angularOscillatingDisplacement", make([](const io::Dictionary& d, const PointPatchContext& c) {
                     return std::unique_ptr<PointPatchDisplacement>(
                         std::make_unique<AngularOscillatingDisplacement>(d, c));
                 }));
    registry.add("solidBodyMotionDisplacement", make([](const io::Dictionary& d, const PointPatchContext& c) {
                     return std::unique_ptr<PointPatchDisplacement>(std::make_unique<SolidBodyMotionDisplacement>(d, c));
                 }));
    for (const char* type : {"zeroGradient", "calculated"})
        registry.add(type, make([type](const io::Dictionary&, const PointPatchContext& c) {
                         return std::unique_ptr<PointPatchDisplacement>(
                             std::make_unique<Unconstrained>(c, type, PatchNodeClass::free));
                     }));
    for (const char* type : {"empty", "wedge"})
        registry.add(
            type,
            make([type](const io::Dictionary&, const PointPatchContext& c) {
                return std::unique_ptr<PointPatchDisplacement>(std::make_unique<Unconstrained>(c, type, PatchNodeClass::ignored));
            }),
            type);
    // A plain cyclic patch: its points pair with the neighbour patch's (CyclicCoupling.hpp).
    registry.add(
        "cyclic",
        make([](const io::Dictionary&, const PointPatchContext& c) {
            return std::unique_ptr<PointPatchDisplacement>(std::make_unique<Unconstrained>(c, "cyclic", PatchNodeClass::coupled));
        }),
        "cyclic");
    registry.add("slip", make([](const io::Dictionary&, const PointPatchContext& c) {
                     return makePointNormalSliding(c, "slip");
                 }));
    registry.add(
        "symmetry",
        make([](const io::Dictionary&, const PointPatchContext& c) { return makePointNormalSliding(c, "symmetry"); }),
        "symmetry");
    registry.add(
        "symmetryPlane",
        make([](const io::Dictionary& d, const PointPatchContext& c) {
            const std::string file = c.file.empty() ? d.file() : c.file;
            const Vector3 n = patchPlaneNormal(*c.mesh, c.patchIndex, c.referencePoints(), file);
            return std::unique_ptr<PointPatchDisplacement>(
                std::make_unique<Sliding>(c, "symmetryPlane", std::vector<Vector3>{n}));
        }),
        "symmetryPlane");
    registry.add("fixedNormalSlip", make([](const io::Dictionary& d, const PointPatchContext& c) {
                     const Vector3 n = d.get<Vector3>("n");
                     if (!(norm(n) > 0.0)) {
                         const io::Entry& entry = d.lookup("n");
                         throw InputError(entry.file(), entry.line(),
                                          "fixedNormalSlip " + patchWhere(c) + ": 'n' must be a non-zero vector");
                     }
                     return std::unique_ptr<PointPatchDisplacement>(
                         std::make_unique<Sliding>(c, "fixedNormalSlip", std::vector<Vector3>{n / norm(n)}));
                 }));
}

const PointPatchDisplacementRegistry& builtinPointPatchDisplacements()
{
    static const PointPatchDisplacementRegistry registry = [] {
        PointPatchDisplacementRegistry r;
        registerBuiltinPointPatchDisplacements(r);
        return r;
    }();
    return registry;
}

const PointPatchDisplacementRegistry& decomposedPointPatchDisplacements()
{
    static const PointPatchDisplacementRegistry registry = [] {
        PointPatchDisplacementRegistry r;
        registerBuiltinPointPatchDisplacements(r);
        // The cut between two ranks' parts: its points are the shared points the distributed
        // solve ties together (motionSolvers/distributed/), not a boundary of the domain.
        r.add(
            "processor",
            [](const io::Dictionary&, const PointPatchContext& c) {
                return std::unique_ptr<PointPatchDisplacement>(
                    std::make_unique<Unconstrained>(c, "processor", PatchNodeClass::ignored));
            },
            "processor");
        return r;
    }();
    return registry;
}

std::vector<Vector3> readPatchVectorField(const io::Dictionary& patchDictionary, std::string_view keyword,
                                          const PointPatchContext& context)
{
    const io::Entry& entry = patchDictionary.lookup(keyword);
    const std::size_t count = context.meshPoints.size();
    if (entry.isDictionary())
        throw InputError(entry.file(), entry.line(),
                         "'" + std::string(keyword) + "' of " + patchWhere(context) +
                             " must be 'uniform (x y z)' or 'nonuniform List<vector> N(...)', not a dictionary");
    io::TokenStream stream = entry.stream(context.header);
    if (stream.atEnd()) stream.fail("'" + std::string(keyword) + "' of " + patchWhere(context) + " has no value");
    std::vector<Vector3> values;
    if (stream.peek().isPunctuation('(')) {
        values.assign(count, stream.readVector());   // deprecated bare value: uniform
    } else {
        const std::string form = stream.readWord();
        if (form == "uniform") {
            values.assign(count, stream.readVector());
        } else if (form == "nonuniform") {
            if (stream.peek().kind == io::Token::Kind::Word) {
                const std::string listType = stream.readWord();
                if (listType != "List<vector>")
                    stream.fail("expected List<vector> after nonuniform in '" + std::string(keyword) + "' of " +
                                patchWhere(context) + ", found " + listType);
            }
            values = stream.readVectorList(count);   // bounded: no allocation beyond the patch size
            if (values.size() != count)
                stream.fail("'" + std::string(keyword) + "' of " + patchWhere(context) + " holds " +
                            std::to_string(values.size()) + " vectors but the patch has " + std::to_string(count) +
                            " points (one vector per point, in the patch's localPoints order)");
        } else {
            stream.fail("expected uniform or nonuniform in '" + std::string(keyword) + "' of " + patchWhere(context) +
                        ", found " + form);
        }
    }
    if (!stream.atEnd())
        stream.fail("unexpected '" + stream.peek().text + "' after the value of '" + std::string(keyword) + "' of " +
                    patchWhere(context));
    return values;
}

namespace {

// A patch both moving and sliding: on a constraint patch (symmetryPlane, symmetry) OpenFOAM's
// pointPatchField::New silently replaces the entry's type by the constraint's, so a motion
// given to that patch by name would be dropped without a word. The types that do not
// prescribe a motion are the free, sliding and 2D ones; an entry matched by a group or a
// regular expression, or with a `patchType`, is not addressed to this patch alone.
void checkNotBothMovingAndSliding(const io::PointPatchFieldEntry& entry, const PointPatchDisplacement& condition,
                                  const Patch& patch)
{
    static const std::set<std::string> notMoving{"zeroGradient", "calculated", "slip",  "fixedNormalSlip",
                                                 "symmetry",     "symmetryPlane", "empty", "wedge"};
    if (condition.nodeClass() != PatchNodeClass::sliding || entry.type == condition.type() ||
        entry.match != io::PointPatchFieldEntry::Match::PatchName || notMoving.count(entry.type) ||
        entry.dictionary.contains("patchType"))
        return;
    const io::Entry* typeEntry = entry.dictionary.find("type");
    throw InputError(entry.dictionary.file(), typeEntry ? typeEntry->line() : entry.dictionary.line(),
                     "patch " + patch.name + " is a " + patch.type +
                         " patch in constant/polyMesh/boundary, so its points slide on it, but its entry gives it type " +
                         entry.type + ", a prescribed motion: a patch cannot both move and slide. Expected type " +
                         condition.type() + " for this patch (or another patch type in the boundary file)");
}

} // namespace

std::vector<std::unique_ptr<PointPatchDisplacement>> makePointPatchDisplacements(
    std::span<const io::PointPatchFieldEntry> entries, const PolyMesh& mesh, const io::FoamFileHeader& header,
    const std::string& file, const std::filesystem::path& caseDirectory, std::span<const Vector3> points0,
    const PointPatchDisplacementRegistry& registry)
{
    if (entries.size() != mesh.patches.size())
        throw std::invalid_argument("makePointPatchDisplacements: " + std::to_string(entries.size()) +
                                    " boundaryField entries for " + std::to_string(mesh.patches.size()) + " patches");
    std::vector<std::unique_ptr<PointPatchDisplacement>> conditions;
    conditions.reserve(entries.size());
    for (std::size_t patchIndex = 0; patchIndex < entries.size(); ++patchIndex) {
        const PointPatchContext context = PointPatchContext::forPatch(mesh, static_cast<Label>(patchIndex), points0,
                                                                      caseDirectory, header, file);
        conditions.push_back(registry.create(entries[patchIndex].dictionary, context));
        checkNotBothMovingAndSliding(entries[patchIndex], *conditions.back(), mesh.patches[patchIndex]);
    }
    return conditions;
}

std::vector<std::unique_ptr<PointPatchDisplacement>> makePointPatchDisplacements(
    const io::PointVectorField& field, const PolyMesh& mesh, const std::filesystem::path& caseDirectory,
    std::span<const Vector3> points0, const PointPatchDisplacementRegistry& registry)
{
    return makePointPatchDisplacements(field.boundaryField, mesh, field.header, field.dictionary.file(), caseDirectory,
                                       points0, registry);
}

std::vector<std::unique_ptr<PointPatchDisplacement>> readPointPatchDisplacements(
    const io::Dictionary& field, const PolyMesh& mesh, const std::filesystem::path& caseDirectory,
    std::span<const Vector3> points0, const PointPatchDisplacementRegistry& registry)
{
    const std::vector<io::PointPatchFieldEntry> entries =
        io::resolveBoundaryField(field.subDictionary("boundaryField"), mesh.patches);
    return makePointPatchDisplacements(entries, mesh, field.header(), field.file(), caseDirectory, points0, registry);
}

} // namespace rbm::motion
