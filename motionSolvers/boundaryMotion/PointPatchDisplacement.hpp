#pragma once
// Boundary conditions of the point displacement field (the boundaryField of
// 0/pointDisplacement): OpenFOAM v1912's pointPatchField types, evaluated on the points of one
// patch at time t. The displacement is relative to the reference points (points0), as in
// OpenFOAM's displacement motion solvers.
//
// Patch points are numbered in OpenFOAM's localPoints order: the order in which the points
// first appear when walking the patch's faces in order, and each face's points in order
// (PrimitivePatch::meshPoints). `nonuniform` lists (value, p0) follow that order.
//
//   type                            node class   entries
//   fixedValue                      prescribed   value (uniform or nonuniform List<vector>; required)
//   uniformFixedValue               prescribed   uniformValue (vector Function1 of time)
//   oscillatingDisplacement         prescribed   amplitude (vector), omega (rad/s): amplitude sin(omega t)
//   angularOscillatingDisplacement  prescribed   axis, origin, angle0, amplitude (radians), omega (rad/s),
//                                                optional p0 (else the reference points):
//                                                angle = angle0 + amplitude sin(omega t),
//                                                p0Rel = p0 − origin, a = axis/|axis|,
//                                                u = p0Rel (cos − 1) + (a × p0Rel) sin + (a·p0Rel)(1 − cos) a,
//                                                i.e. the rotation of p0 by `angle` about the axis
//                                                through origin, counter-clockwise (right-hand rule)
//   solidBodyMotionDisplacement     prescribed   solidBodyMotionFunction + coefficients
//                                                (SolidBodyMotion.hpp): u = transform(points0) − points0
//   zeroGradient, calculated        free
//   slip, symmetry                  sliding      normal per point: OpenFOAM's patch pointNormals (the
//                                                normalised sum of the unit normals of the patch faces
//                                                around the point)
//   symmetryPlane                   sliding      one normal: average of the unit face normals; the patch
//                                                must be planar (|n_face − n_avg|² ≤ 1e-15, as OpenFOAM)
//   fixedNormalSlip                 sliding      n (vector; normalised here — OpenFOAM uses it as given)
//   empty, wedge                    ignored      (the 2D extraction handles these planes)
// Sliding nodes keep their displacement normal to the normal: u·n = 0.
//
// Constraint patches (OpenFOAM pointPatchField::New): on a mesh patch of type empty, wedge,
// symmetryPlane or symmetry, the field type of that name is used whatever the dictionary says
// (unless it says `patchType <that type>;`); a constraint field type on a patch of another
// type is an error ("inconsistent patch and patchField types").
//
// Example (0/pointDisplacement):
//     boundaryField
//     {
//         airfoil
//         {
//             type            angularOscillatingDisplacement;
//             axis            (0 0 1);
//             origin          (0.25 0 0);
//             angle0          0;
//             amplitude       0.0872665;   // 5 degrees, in radians
//             omega           6.2832;
//             value           uniform (0 0 0);
//         }
//         flap            { type solidBodyMotionDisplacement; solidBodyMotionFunction rotatingMotion;
//                           rotatingMotionCoeffs { origin (1 0 0); axis (0 0 1); omega 0.1; } }
//         farField        { type fixedValue; value uniform (0 0 0); }
//         bottom          { type slip; }
//         "(front|back)"  { type empty; }
//     }
//
// Every input error is an rbm::InputError naming the file, the line, the patch and the entry.

#include "FoamDictionary.hpp"
#include "PointVectorField.hpp"
#include "PatchNormals.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::motion {

enum class PatchNodeClass : std::uint8_t {
    prescribed,  // displacement given at every time
    sliding,     // unknown, held on the plane through its reference position normal to slidingNormal()
    free,        // unknown, moves like an interior node
    ignored,     // not a motion condition (empty, wedge): the 2D handling owns these points
    coupled,     // cyclic: unknown, tied to the partner points of the neighbour patch
};
std::string_view patchNodeClassName(PatchNodeClass nodeClass);

// patchMeshPoints (OpenFOAM's localPoints order of a patch): PolyMesh.hpp.

// patchPointNormals (OpenFOAM's PrimitivePatch::pointNormals): PatchNormals.hpp.

// Unit normal of a planar patch (OpenFOAM symmetryPlanePolyPatch: the average of the unit face
// normals). Throws rbm::InputError (naming `file`) when a face normal differs from the average
// by more than OpenFOAM allows (|n_f − n|² > 1e-15). Zero vector for a patch without faces.
Vector3 patchPlaneNormal(const PolyMesh& mesh, Label patchIndex, std::span<const Vector3> points,
                         const std::string& file = {});

// What a boundary condition needs to know about its patch when it is constructed.
struct PointPatchContext {
    const PolyMesh* mesh = nullptr;
    Label patchIndex = -1;
    std::vector<Label> meshPoints;           // patchMeshPoints(*mesh, patchIndex)
    std::span<const Vector3> points0;        // reference positions of all mesh points; empty: mesh->points
    std::filesystem::path caseDirectory;     // for relative file names and $FOAM_CASE
    io::FoamFileHeader header;               // of the field file (binary nonuniform lists)
    std::string file;                        // the field file, for messages

    // Fills meshPoints for the patch and sets the rest.
    static PointPatchContext forPatch(const PolyMesh& mesh, Label patchIndex, std::span<const Vector3> points0 = {},
                                      std::filesystem::path caseDirectory = {}, io::FoamFileHeader header = {},
                                      std::string file = {});
    const Patch& patch() const { return mesh->patches[static_cast<std::size_t>(patchIndex)]; }
    std::span<const Vector3> referencePoints() const { return points0.empty() ? std::span<const Vector3>(mesh->points) : points0; }
};

class PointPatchDisplacement {
public:
    PointPatchDisplacement(const PointPatchContext& context, std::string type)
        : patchName_(context.patch().name), type_(std::move(type)), meshPoints_(context.meshPoints)
    {}
    virtual ~PointPatchDisplacement() = default;
    PointPatchDisplacement(const PointPatchDisplacement&) = delete;
    PointPatchDisplacement& operator=(const PointPatchDisplacement&) = delete;

    const std::string& patchName() const { return patchName_; }
    // The OpenFOAM type name actually used (after the constraint-patch rule).
    const std::string& type() const { return type_; }
    // Patch point i is mesh point meshPoints()[i] (localPoints order).
    const std::vector<Label>& meshPoints() const { return meshPoints_; }
    Label pointCount() const { return static_cast<Label>(meshPoints_.size()); }

    virtual PatchNodeClass nodeClass() const = 0;
    // True when evaluate() depends on t (lets callers skip re-evaluation).
    virtual bool isTimeDependent() const { return false; }

    // Prescribed types: displacement[i] of patch point i at time t, from its reference position
    // patchPoints0[i]; both spans hold pointCount() entries. Other classes throw std::logic_error.
    virtual void evaluate(double t, std::span<const Vector3> patchPoints0, std::span<Vector3> displacement) const;
    // The same on mesh-wide arrays: reads points0[meshPoints()[i]], writes displacement[meshPoints()[i]].
    void evaluateOnMesh(double t, std::span<const Vector3> points0, std::span<Vector3> displacement) const;

    // Sliding types: unit normal of the plane patch point i slides on. Others throw std::logic_error.
    virtual Vector3 slidingNormal(Label patchPoint) const;
    // Sliding types: true when the plane is a mirror of the mesh (symmetry, symmetryPlane),
    // so that a point on it may turn only about the normal; false for slip-type walls.
    virtual bool isMirrorPlane() const { return false; }

private:
    std::string patchName_;
    std::string type_;
    std::vector<Label> meshPoints_;
};

// Selection of boundary-condition types by name: a plain map of factories, filled explicitly
// (registerBuiltinPointPatchDisplacements), no static registration.
class PointPatchDisplacementRegistry {
public:
    using Factory = std::function<std::unique_ptr<PointPatchDisplacement>(const io::Dictionary& patchDictionary,
                                                                          const PointPatchContext& context)>;

    // constraintType: the mesh patch type this field type belongs to ("empty", "symmetryPlane",
    // ...), empty for ordinary types.
    void add(std::string type, Factory factory, std::string constraintType = {});
    bool contains(std::string_view type) const { return entries_.find(type) != entries_.end(); }
    std::vector<std::string> types() const;   // sorted

    // Reads `type` from the patch dictionary and applies the constraint-patch rule. Errors:
    // "Unknown patchField type X for patch P in file F. Valid types are: ...".
    std::unique_ptr<PointPatchDisplacement> create(const io::Dictionary& patchDictionary,
                                                   const PointPatchContext& context) const;

private:
    struct Registered {
        Factory factory;
        std::string constraintType;
    };
    std::map<std::string, Registered, std::less<>> entries_;
};

void registerBuiltinPointPatchDisplacements(PointPatchDisplacementRegistry& registry);
// A registry holding the built-in types.
const PointPatchDisplacementRegistry& builtinPointPatchDisplacements();
// The built-in types and `processor` (ignored: the patches between the ranks' parts of a
// decomposed case, which only a distributed run may read; a serial run refuses them).
const PointPatchDisplacementRegistry& decomposedPointPatchDisplacements();

// One boundary condition per mesh patch, in patch order, from the boundaryField entries that
// apply to the patches (io::resolveBoundaryField: OpenFOAM's precedence of patch names, groups,
// patterns and implicit `empty`). `header` and `file`: of the field file (binary lists,
// messages). `points0`: reference positions of all mesh points (empty: mesh.points).
std::vector<std::unique_ptr<PointPatchDisplacement>> makePointPatchDisplacements(
    std::span<const io::PointPatchFieldEntry> entries, const PolyMesh& mesh, const io::FoamFileHeader& header,
    const std::string& file, const std::filesystem::path& caseDirectory = {}, std::span<const Vector3> points0 = {},
    const PointPatchDisplacementRegistry& registry = builtinPointPatchDisplacements());

// The same for a field read with io::readPointVectorField (e.g. 0/pointDisplacement).
std::vector<std::unique_ptr<PointPatchDisplacement>> makePointPatchDisplacements(
    const io::PointVectorField& field, const PolyMesh& mesh, const std::filesystem::path& caseDirectory = {},
    std::span<const Vector3> points0 = {},
    const PointPatchDisplacementRegistry& registry = builtinPointPatchDisplacements());

// The same for a field file already parsed as a dictionary (its `boundaryField` is resolved
// with io::resolveBoundaryField). A patch without an entry is an error.
std::vector<std::unique_ptr<PointPatchDisplacement>> readPointPatchDisplacements(
    const io::Dictionary& field, const PolyMesh& mesh, const std::filesystem::path& caseDirectory = {},
    std::span<const Vector3> points0 = {},
    const PointPatchDisplacementRegistry& registry = builtinPointPatchDisplacements());

// A `uniform`/`nonuniform` vector field entry of a patch dictionary (value, p0) with one vector
// per patch point. A bare vector is read as uniform (OpenFOAM's deprecated form).
std::vector<Vector3> readPatchVectorField(const io::Dictionary& patchDictionary, std::string_view keyword,
                                          const PointPatchContext& context);

} // namespace rbm::motion
