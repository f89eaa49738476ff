#include "rbmRigidBodyMotionSolver.H"

#include "IStringStream.H"
#include "OStringStream.H"
#include "addToRunTimeSelectionTable.H"
#include "coupledPolyPatch.H"
#include "pointMesh.H"
#include "processorPolyPatch.H"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace Foam
{
    defineTypeNameAndDebug(rbmRigidBodyMotionSolver, 0);

    // rbmMotionSolver: the name no other library registers (OpenFOAM v1912's
    // librigidBodyMeshMotion.so registers rigidBodyMotionSolver for its 6-DoF solver).
    RBM_ADD_MOTION_SOLVER_TO_SELECTION_TABLES(rbmRigidBodyMotionSolver, rbmMotionSolver);
}


namespace
{

// The coefficient only the plugin knows (rbmMoveMesh has the -writeInvalid option instead).
const Foam::word writeInvalidKeyword("writeInvalid");

// The environment variable that makes a decomposed 3D run take the gathered path (set to
// anything but 0): for comparing the two paths (memory, results) on one build.
const char* const gatherSwitch = "RBM_PLUGIN_GATHER";

void appendNormals(std::vector<double>& normals, const Foam::vector& n, Foam::label count)
{
    for (Foam::label i = 0; i < count; ++i)
    {
        normals.push_back(n.x());
        normals.push_back(n.y());
        normals.push_back(n.z());
    }
}

// A plain cyclic patch (translational or rotational): rbm ties its points to their partners on
// the neighbour patch (docs/openfoamPlugin.md). Not its derived types (cyclicSlip,
// nonuniformTransformCyclic, processorCyclic), which have other type names.
bool isPlainCyclic(const Foam::polyPatch& patch)
{
    return std::string(patch.type()) == "cyclic";
}

// A patch whose points are tied to another patch's, other than a plain cyclic. OpenFOAM
// v1912's AMI patches answer coupled() false (they are coupled by interpolation, not face to
// face) but still derive from coupledPolyPatch; the names catch the interface types of later
// versions too.
bool isCoupledOrInterface(const Foam::polyPatch& patch)
{
    const std::string type(patch.type());
    if (isPlainCyclic(patch))
    {
        return false;
    }
    return patch.coupled() || Foam::isA<Foam::coupledPolyPatch>(patch)
        || type.find("AMI") != std::string::npos || type.rfind("nonConformal", 0) == 0
        || type.rfind("cyclic", 0) == 0;
}

// fixedNormalSlip keeps its normal private: read it back from what the field writes.
Foam::vector fixedNormalSlipNormal(const Foam::pointPatchField<Foam::vector>& field)
{
    Foam::OStringStream os;
    field.write(os);
    Foam::IStringStream is(os.str());
    const Foam::dictionary dict(is);
    return Foam::vector(dict.lookup("n"));
}

// The entry that selects the motion solver, in the dictionary that holds the Coeffs block;
// OpenFOAM v1912 also reads it under its old name.
const Foam::word motionSolverKeyword("motionSolver");
const Foam::word oldMotionSolverKeyword("solver");

// rbm's own coefficients from the dictionary a selection table hands to the constructor.
// OpenFOAM v1912 hands the whole dynamicMeshDict and OpenFOAM 13 the <name>Coeffs block, or
// the whole mover dictionary when the block is absent; both then fall back to the enclosing
// dictionary (coeffDict(), optionalSubDict()), whose other entries rbm's keyword check would
// reject: the dynamicFvMesh, libs and the previous solver's entries (diffusivity, ...) a user
// leaves there when switching a case with one line. The dictionary that selected the solver
// has the motionSolver (or solver) entry; a Coeffs block has not. Absent block: every default.
Foam::dictionary rbmCoefficients(const Foam::dictionary& dict)
{
    const Foam::word& keyword =
        dict.found(motionSolverKeyword) ? motionSolverKeyword : oldMotionSolverKeyword;
    if (!dict.found(keyword))
    {
        return dict;
    }
    const Foam::word blockName(Foam::word(dict.lookup(keyword)) + "Coeffs");
    if (dict.isDict(blockName))
    {
        return dict.subDict(blockName);
    }
    Foam::dictionary empty;
    empty.name() = dict.name() + '.' + blockName;
    return empty;
}

} // End anonymous namespace


Foam::rbmRigidBodyMotionSolver::~rbmRigidBodyMotionSolver() = default;


void Foam::rbmRigidBodyMotionSolver::construct(const dictionary& dict)
{
    const polyMesh& pMesh = mesh();

    // The coefficients rbm reads: rbmMoveMesh's keywords, without the plugin's own.
    coefficients_ = rbmCoefficients(dict);
    dictionary coefficients(coefficients_);
    writeInvalid_ = coefficients.lookupOrDefault<bool>(writeInvalidKeyword, false);
    coefficients.remove(writeInvalidKeyword);
    OStringStream text;
    coefficients.write(text, false);

    // Decomposed 3D runs solve on the processors' parts; the rest (and serial runs, whose
    // numbering is the mesh's own) on the whole mesh, gathered onto every processor.
    const std::string reason = gatherReason(text.str());
    const bool onParts = Pstream::parRun() && reason.empty();
    label nDescribedPatches = 0;
    if (onParts)
    {
        localMesh_ = std::make_unique<rbmLocalMesh>(pMesh, points0());
        nDescribedPatches = pMesh.boundaryMesh().size();
    }
    else
    {
        globalMesh_ = std::make_unique<rbmGlobalMesh>(pMesh, points0());
        nDescribedPatches = globalMesh_->nRealPatches();
    }

    std::vector<rbm::host::HostPatchBoundary> boundary(nDescribedPatches);
    prescribedPatches_.assign(boundary.size(), false);
    prescribedPoints_.setSize(pMesh.nPoints());
    prescribedPoints_ = false;
    for (label patchi = 0; patchi < nDescribedPatches; ++patchi)
    {
        boundary[patchi] = describePatch(patchi);
    }

    try
    {
        if (onParts)
        {
            partSolver_ = std::make_unique<rbm::host::HostPartMotionSolver>
            (
                localMesh_->hostMesh(),
                localMesh_->globalPointLabels(),
                text.str(),
                coefficients_.name(),
                boundary
            );
        }
        else
        {
            solver_ = std::make_unique<rbm::host::HostMotionSolver>
            (
                globalMesh_->hostMesh(),
                text.str(),
                coefficients_.name(),
                boundary,
                pMesh.time().path()
            );
        }
    }
    catch (const rbm::host::HostInputError& error)
    {
        FatalIOErrorInFunction(coefficients_)
            << error.what() << exit(FatalIOError);
    }
    catch (const std::exception& error)
    {
        FatalErrorInFunction
            << "rigidBodyMotionSolver: " << error.what() << exit(FatalError);
    }
    if (onParts)
    {
        Info<< "rigidBodyMotionSolver (rbm): " << label(partSolver_->globalPointCount()) << " points, distributed over "
            << Pstream::nProcs() << " processors (each solves its own part; none holds the whole mesh),"
            << " solved in 3D" << (writeInvalid_ ? ", writeInvalid yes" : "") << endl;
    }
    else
    {
        Info<< "rigidBodyMotionSolver (rbm): " << globalMesh_->nGlobalPoints() << " points"
            << (Pstream::parRun() ? " gathered from the processors" : "") << ", solved in "
            << solver_->dimension() << "D" << (writeInvalid_ ? ", writeInvalid yes" : "");
        if (Pstream::parRun())
        {
            Info<< " (not solved on the processors' parts: " << reason.c_str() << ")";
        }
        Info<< endl;
    }
}


std::string Foam::rbmRigidBodyMotionSolver::gatherReason(const std::string& coefficientsText) const
{
    if (!Pstream::parRun())
    {
        return std::string();
    }
    const polyMesh& pMesh = mesh();
    // Each reason is decided on every processor (the patches, the fields and the environment
    // may differ between them) and reduced, so that all take the same path.
    bool switchedOff = std::getenv(gatherSwitch) != nullptr && std::string(std::getenv(gatherSwitch)) != "0";
    bool pseudoTwoD = pMesh.nSolutionD() != 3;
    bool cyclic = false;
    bool ownNormal = false;
    forAll(pMesh.boundaryMesh(), patchi)
    {
        const polyPatch& patch = pMesh.boundaryMesh()[patchi];
        if (isA<processorPolyPatch>(patch))
        {
            cyclic = cyclic || !isType<processorPolyPatch>(patch);
        }
        else
        {
            cyclic = cyclic || isPlainCyclic(patch) || isCoupledOrInterface(patch);
            ownNormal = ownNormal || pointDisplacement_.boundaryField()[patchi].type() == "fixedNormalSlip";
        }
    }
    bool otherVariant = false;
    try
    {
        otherVariant = !rbm::host::HostPartMotionSolver::solvesVariant(coefficientsText, coefficients_.name());
    }
    catch (const rbm::host::HostInputError& error)
    {
        FatalIOErrorInFunction(coefficients_)
            << error.what() << exit(FatalIOError);
    }
    reduce(switchedOff, orOp<bool>());
    reduce(pseudoTwoD, orOp<bool>());
    reduce(cyclic, orOp<bool>());
    reduce(ownNormal, orOp<bool>());
    std::string reason;
    const auto add = [&reason](bool applies, const char* text)
    {
        if (applies)
        {
            reason += (reason.empty() ? "" : "; ") + std::string(text);
        }
    };
    add(switchedOff, "RBM_PLUGIN_GATHER is set");
    add(pseudoTwoD, "the mesh is pseudo-2D");
    add(cyclic, "the mesh has cyclic or interface patches");
    add(ownNormal, "a fixedNormalSlip patch slides on its own normal");
    add(otherVariant, "the coefficients choose a variant other than the default reduced Newton solver");
    return reason;
}


rbm::host::HostPatchBoundary Foam::rbmRigidBodyMotionSolver::describePatch(label patchi)
{
    const polyPatch& patch = mesh().boundaryMesh()[patchi];
    const pointPatchField<vector>& field = pointDisplacement_.boundaryField()[patchi];
    rbm::host::HostPatchBoundary b;
    const word& fieldType = field.type();
    if (isA<processorPolyPatch>(patch))
    {
        // The faces between processors: the part solver joins the parts across them.
        b.nodeClass = rbm::host::HostNodeClass::ignored;
        return b;
    }
    if (isCoupledOrInterface(patch))
    {
        FatalErrorInFunction
            << "rigidBodyMotionSolver: patch " << patch.name() << " is of type " << patch.type()
            << ", a coupled or interface patch; rbm's motion solver supports plain cyclic patches"
            << " only, not cyclicAMI, cyclicACMI, cyclicPeriodicAMI, cyclicSlip,"
            << " nonuniformTransformCyclic or nonConformal*: the two sides would move"
            << " independently and come apart."
            << exit(FatalError);
    }
    if (patch.type() == "empty" || patch.type() == "wedge")
    {
        b.nodeClass = rbm::host::HostNodeClass::ignored;
    }
    else if (isPlainCyclic(patch))
    {
        b.nodeClass = rbm::host::HostNodeClass::coupled;
    }
    else if (field.fixesValue())
    {
        b.nodeClass = rbm::host::HostNodeClass::prescribed;
        prescribedPatches_[patchi] = true;
        for (const label pointi : pointDisplacement_.mesh().boundary()[patchi].meshPoints())
        {
            prescribedPoints_[pointi] = true;
        }
    }
    else if (fieldType == "slip" || fieldType == "symmetry")
    {
        b.nodeClass = rbm::host::HostNodeClass::sliding;
        b.mirror = fieldType == "symmetry";
        b.slidingNormals = patchPointNormals(patchi);
    }
    else if (fieldType == "symmetryPlane")
    {
        b.nodeClass = rbm::host::HostNodeClass::sliding;
        b.mirror = true;
        b.slidingNormals = uniformNormals(patchi, patchPlaneNormal(patchi));
    }
    else if (fieldType == "fixedNormalSlip")
    {
        b.nodeClass = rbm::host::HostNodeClass::sliding;
        b.slidingNormals = uniformNormals(patchi, fixedNormalSlipNormal(field));
    }
    else
    {
        b.nodeClass = rbm::host::HostNodeClass::free;
    }
    return b;
}


std::vector<double> Foam::rbmRigidBodyMotionSolver::patchPointNormals(label patchi) const
{
    if (globalMesh_)
    {
        return globalMesh_->pointNormals(patchi);
    }
    std::vector<double> normals;
    for (const vector& n : mesh().boundaryMesh()[patchi].pointNormals())
    {
        appendNormals(normals, n, 1);
    }
    return normals;
}


std::vector<double> Foam::rbmRigidBodyMotionSolver::uniformNormals(label patchi, const vector& n) const
{
    std::vector<double> normals;
    appendNormals
    (
        normals,
        n,
        globalMesh_ ? globalMesh_->patchPointCount(patchi) : mesh().boundaryMesh()[patchi].nPoints()
    );
    return normals;
}


Foam::vector Foam::rbmRigidBodyMotionSolver::patchPlaneNormal(label patchi) const
{
    if (globalMesh_)
    {
        return globalMesh_->planeNormal(patchi);
    }
    // This processor's faces of the plane (the part solver sums the normals over the
    // processors itself: PartBoundary.hpp).
    return normalised(sum(mesh().boundaryMesh()[patchi].faceNormals()));
}


Foam::tmp<Foam::pointField>
Foam::rbmRigidBodyMotionSolver::curPoints() const
{
    tmp<pointField> tcurPoints
    (
        points0() + pointDisplacement_.primitiveField()
    );
    twoDCorrectPoints(tcurPoints.ref());
    return tcurPoints;
}


void Foam::rbmRigidBodyMotionSolver::solve()
{
    // The points have moved (OpenFOAM's displacement solvers do the same first).
    movePoints(mesh().points());

    // OpenFOAM evaluates the boundary conditions; the prescribing patches write their values
    // into the internal field, the first patch last so that it wins on shared points (rbm's
    // rule between prescribing patches).
    pointDisplacement_.boundaryFieldRef().updateCoeffs();
    for (label patchi = prescribedPatches_.size() - 1; patchi >= 0; --patchi)
    {
        if (prescribedPatches_[patchi])
        {
            pointDisplacement_.boundaryFieldRef()[patchi].evaluate(Pstream::commsTypes::blocking);
        }
    }

    const Time& runTime = mesh().time();
    rbm::host::HostStepReport report;
    try
    {
        report = solveStep(pointDisplacement_.primitiveFieldRef());
    }
    catch (const rbm::host::HostInputError& error)
    {
        FatalIOErrorInFunction(coefficients_)
            << error.what() << exit(FatalIOError);
    }
    catch (const std::exception& error)
    {
        FatalErrorInFunction
            << "rigidBodyMotionSolver: time " << rbmOpenFOAM::timeName(runTime) << ": " << error.what()
            << exit(FatalError);
    }

    Info<< report.logLine.c_str() << endl;
    for (const std::string& warning : report.warnings)
    {
        WarningInFunction
            << "rigidBodyMotionSolver: time " << rbmOpenFOAM::timeName(runTime) << ": " << warning.c_str() << endl;
    }
    if (!report.valid && partSolver_)
    {
        report.problem += std::string(" ") + gatherSwitch + "=1 in the environment (mpirun -x " + gatherSwitch
            + ") solves the whole mesh on every processor instead.";
    }
    if (!report.valid)
    {
        if (writeInvalid_ && report.finite)
        {
            WarningInFunction
                << "rigidBodyMotionSolver: time " << rbmOpenFOAM::timeName(runTime) << ": "
                << report.problem.c_str() << nl
                << "    writeInvalid yes: the run goes on with this mesh, which is NOT valid"
                << " for a flow solver." << endl;
        }
        else
        {
            FatalErrorInFunction
                << "rigidBodyMotionSolver: time " << rbmOpenFOAM::timeName(runTime) << ": "
                << report.problem.c_str() << exit(FatalError);
        }
    }
}


rbm::host::HostStepReport Foam::rbmRigidBodyMotionSolver::solveStep(vectorField& u)
{
    const Time& runTime = mesh().time();
    const int step = static_cast<int>(++stepCount_);
    if (partSolver_)
    {
        // This processor's points: the part solver reads the prescribed ones and writes all.
        displacement_.resize(3*u.size());
        forAll(u, pointi)
        {
            displacement_[3*pointi] = u[pointi].x();
            displacement_[3*pointi + 1] = u[pointi].y();
            displacement_[3*pointi + 2] = u[pointi].z();
        }
        rbm::host::HostStepReport report = partSolver_->solve
        (
            step, runTime.value(), rbmOpenFOAM::timeName(runTime), displacement_.data(), displacement_.size()
        );
        forAll(u, pointi)
        {
            u[pointi] = vector(displacement_[3*pointi], displacement_[3*pointi + 1], displacement_[3*pointi + 2]);
        }
        return report;
    }
    globalMesh_->gather(u, prescribedPoints_, displacement_);
    rbm::host::HostStepReport report = solver_->solve
    (
        step, runTime.value(), rbmOpenFOAM::timeName(runTime), displacement_.data(), displacement_.size()
    );
    globalMesh_->scatter(displacement_, u);
    return report;
}


void Foam::rbmRigidBodyMotionSolver::topologyChangeUnsupported() const
{
    FatalErrorInFunction
        << "rigidBodyMotionSolver (rbm) does not support topology changes or redistribution:"
        << " its cell-neighbour graph and RBM problem belong to the initial topology."
        << exit(FatalError);
}
