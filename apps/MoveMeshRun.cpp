#include "MoveMeshRun.hpp"

#include "BlockRowLayout.hpp"
#include "CaseLock.hpp"
#include "CompressedFile.hpp"
#include "DecomposedMoveMeshRun.hpp"
#include "FoamDictionaryWriter.hpp"
#include "InputError.hpp"
#include "LoadAdaptiveThreads.hpp"
#include "MemoryEstimate.hpp"
#include "MeshTopology.hpp"
#include "MotionOutput.hpp"
#include "MotionSolverRegistry.hpp"
#include "PetscSupport.hpp"
#include "PointPatchDisplacement.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RigidBodyMotionOptions.hpp"
#include "StepAssessment.hpp"
#include "ThesisQuality.hpp"
#include "ThreadCount.hpp"
#include "TimeFolderWriter.hpp"
#include "WholeFile.hpp"
#include "WriteSchedule.hpp"

#include "NumberText.hpp"

#include <petscversion.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <numbers>
#include <ostream>
#include <set>
#include <sstream>

#ifndef RBM_VERSION
#define RBM_VERSION "unknown"
#endif

namespace rbm::app {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool isFinite(const Vector3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Node classes written to VTK's "nodeClass" point field.
constexpr std::uint8_t nodeFree = 0;
constexpr std::uint8_t nodeSliding = 1;
constexpr std::uint8_t nodePrescribed = 2;

// PETSc options without an underscore in their name (the others all have one).
bool isPetscOptionWithoutUnderscore(std::string_view argument)
{
    static constexpr std::string_view names[] = {"-info", "-malloc", "-nox", "-display", "-log", "-fp_trap",
                                                 "-v",    "-checkstack"};
    return std::find(std::begin(names), std::end(names), argument) != std::end(names);
}

// The sentence after an error in a step: what the step had written. `parts`: 0 nothing, 1 its
// time folder, 2 its time folder and VTK file.
std::string writtenByStep(const std::string& name, int parts, bool vtk)
{
    return parts == 0          ? "Nothing was written for this time; earlier times stay as written."
           : parts == 1 && vtk ? "Time folder " + name + " was written, its VTK file was not (the .pvd lists the earlier times)."
                               : "Time " + name + " was written.";
}

// One writing run per case (io/CaseLock.hpp), taken before the case is read and held to the
// end. False, with the message on `err`, when another run holds it; a file system without
// locks gets a warning.
bool lockCase(const fs::path& caseDirectory, std::optional<io::CaseLock>& lock, std::ostream& err)
{
    lock = io::CaseLock::acquire(caseDirectory);
    if (lock->heldByAnother()) err << "rbmMoveMesh: " << lock->message() << "\nNothing was written.\n";
    if (lock->state() == io::CaseLock::State::Unavailable && !lock->message().empty()) {
        err << "rbmMoveMesh: warning: " << lock->message() << '\n';
    }
    return !lock->heldByAnother();
}

bool looksLikeNumber(std::string_view text)
{
    double value = 0.0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

} // namespace

// ---- Command line ---------------------------------------------------------------------------

CommandLine parseCommandLine(int argc, const char* const* argv)
{
    CommandLine commandLine;
    for (int i = 1; i < argc; ++i) {
        const std::string argument = argv[i];
        if (argument == "-case") {
            if (i + 1 >= argc) throw UsageError("-case needs a case folder");
            commandLine.options.caseDirectory = argv[++i];
        } else if (argument == "-noVTK") {
            commandLine.options.writeVtk = false;
        } else if (argument == "-parallel") {
            commandLine.options.parallel = true;
        } else if (argument == "-writeInvalid") {
            commandLine.options.writeInvalid = true;
        } else if (argument == "-help" || argument == "--help" || argument == "-h") {
            commandLine.help = true;
        } else if (argument == "-version" || argument == "--version") {
            commandLine.version = true;
        } else if (argument.size() > 1 && argument[0] == '-' &&
                   (argument.find('_') != std::string::npos || isPetscOptionWithoutUnderscore(argument))) {
            commandLine.petscArguments.push_back(argument);
            // Its value(s): what follows up to the next option (a negative number is a value).
            while (i + 1 < argc && (argv[i + 1][0] != '-' || looksLikeNumber(argv[i + 1]))) {
                commandLine.petscArguments.emplace_back(argv[++i]);
            }
        } else if (!argument.empty() && argument[0] == '-') {
            throw UsageError("unknown option '" + argument + "'");
        } else {
            throw UsageError("unexpected argument '" + argument + "' (give the case folder with -case DIR)");
        }
    }
    return commandLine;
}

std::string versionText()
{
    return std::string("rbmMoveMesh ") + RBM_VERSION + " (PETSc " + std::to_string(PETSC_VERSION_MAJOR) + "." +
           std::to_string(PETSC_VERSION_MINOR) + "." + std::to_string(PETSC_VERSION_SUBMINOR) + ")";
}

namespace {

// Words joined by `separator`, wrapped before column `width`; continuation lines start
// with `indent`. `column` is where the first word starts.
std::string wrapped(const std::vector<std::string>& words, const std::string& separator, std::size_t column,
                    const std::string& indent, std::size_t width = 88)
{
    std::string out;
    for (std::size_t i = 0; i < words.size(); ++i) {
        const std::string piece = words[i] + (i + 1 < words.size() ? separator : "");
        if (i > 0 && column + piece.size() > width) {
            while (!out.empty() && out.back() == ' ') out.pop_back();
            out += "\n" + indent;
            column = indent.size();
        }
        out += piece;
        column += piece.size();
    }
    return out;
}

} // namespace

std::string usageText()
{
    const std::string indent(29, ' ');
    std::vector<std::string> coefficients{"rigidBodyMotionSolverCoeffs", "{"};
    for (const std::string_view keyword : motion::RigidBodyMotionOptions::keywords()) coefficients.emplace_back(keyword);
    coefficients.emplace_back("}");
    std::ostringstream text;
    text << "Usage: rbmMoveMesh [-case DIR] [-noVTK] [-parallel] [-writeInvalid] [-help] [-version]\n"
            "                   [PETSc options]\n"
            "\n"
            "Moves the mesh of an OpenFOAM case over time with the rigid body motion (RBM) method,\n"
            "like OpenFOAM's moveMesh: at every time step the boundary conditions of the point\n"
            "displacement field are evaluated, the motion solver computes the displacement of the\n"
            "other points (total displacement relative to constant/polyMesh), and the mesh quality\n"
            "is checked. Write times get <time>/polyMesh/points and <time>/pointDisplacement.\n"
            "\n"
            "Options:\n"
            "  -case DIR       case folder (default: the current folder)\n"
            "  -noVTK          do not write VTK/<case>_<time>.vtu and VTK/<case>.pvd\n"
            "  -parallel       under mpirun -np N: on a case decomposePar split into N processor\n"
            "                  folders, rank r reads and writes processor<r> only (3D, the default\n"
            "                  solver); on an undecomposed case, the solve is distributed over the\n"
            "                  N ranks (each reads the whole case; rank 0 writes)\n"
            "  -writeInvalid   write steps with inverted cells or without convergence anyway\n"
            "                  (with a warning; the run goes on, the exit status is still 1)\n"
            "  -help           print this message\n"
            "  -version        print the version\n"
            "  PETSc options   anything with an underscore (-ksp_type cg, -rbm_pc_type gamg,\n"
            "                  -log_view) or -info, -malloc, -nox: passed to PETSc\n"
            "\n"
            "Files read:\n"
            "  system/controlDict         startFrom (startTime|firstTime|latestTime), startTime,\n"
            "                             endTime, deltaT, writeControl (timeStep|runTime|\n"
            "                             adjustableRunTime|cpuTime|clockTime), writeInterval,\n"
            "                             writeFormat (ascii|binary), writePrecision,\n"
            "                             writeCompression (on|off), timeFormat (general|fixed|\n"
            "                             scientific), timePrecision\n"
            "  constant/dynamicMeshDict   motionSolver (or solver): "
         << wrapped(motion::builtinMotionSolvers().names(), ", ", 55, indent) << ";\n"
         << indent << wrapped(coefficients, " ", indent.size(), indent + "  ") << "\n"
         << "  constant/polyMesh          the mesh; its points are the reference points0\n"
            "  <time>/pointDisplacement   boundaryField: the motion of every patch, from the\n"
            "                             earliest time folder up to the start time that has\n"
            "                             the file; types: "
         << wrapped(motion::builtinPointPatchDisplacements().types(), ", ", 46, indent)
         << "\n"
            "                             The start time's internalField warm-starts a restart.\n"
            "\n"
            "Files written (each time folder and VTK file atomically; one run per case at a time):\n"
            "  <time>/polyMesh/points     at write times (writeFormat, writePrecision, writeCompression)\n"
            "  <time>/pointDisplacement   at write times (ascii)\n"
            "  VTK/<case>_<time>.vtu      at write times and for the initial mesh; VTK/<case>.pvd\n"
            "  postProcessing/rbmMoveMesh/<startTime>/log.jsonl   one JSON object per time step\n"
            "\n"
            "Log line per time step:\n"
            "  Time = 0.025     sub-steps  1  iterations    3  residual 2.10e-10  worst quality  0.3100\n"
            "  max non-orthogonality  28.40  inverted 0  wall   0.120 s  (one line)\n"
            "\n"
            "Before assembling, the memory the solve needs is estimated and compared with what the\n"
            "machine has (MemAvailable, a cgroup limit, or RBM_AVAILABLE_MEMORY_MB=<MiB> in the\n"
            "environment); a solve that does not fit stops the run with both figures (exit status 1).\n"
            "\n"
            "Exit status: 0 success; 1 a step with inverted cells, without convergence or with NaN\n"
            "values (nothing written for it), not enough memory, or a failure during the run (a\n"
            "file that cannot be written: the message gives the OS reason); 2 bad command line or\n"
            "case, or another rbmMoveMesh is moving the case (nothing written).\n"
            "See docs/rbmMoveMesh.md.\n";
    return text.str();
}

// ---- Per-cell fields for VTK ------------------------------------------------------------------

struct MoveMeshRun::CellFieldWorkspace {
    std::optional<io::VtkCells> vtkCells;
    const PseudoTwoDMesh* twoD = nullptr;   // pseudo-3D meshes, for the 2D cell metrics (the assessor's)
    std::vector<Vector3> nodePositions;
};

// ---- Setup ----------------------------------------------------------------------------------

MoveMeshRun::MoveMeshRun(MoveMeshOptions options, std::ostream& out, std::ostream& err)
    : options_(std::move(options)), out_(out), err_(err), caseDirectory_(options_.caseDirectory)
{
    std::error_code error;
    if (!fs::is_directory(caseDirectory_, error)) {
        throw InputError(caseDirectory_.string(), 0, "the case folder does not exist or is not a folder");
    }
    {
        fs::path absolute = fs::weakly_canonical(fs::absolute(caseDirectory_), error);
        if (error) absolute = fs::absolute(caseDirectory_);
        caseName_ = absolute.filename().string();
        if (caseName_.empty() || caseName_ == "." || caseName_ == "..") caseName_ = "case";
    }

    readTimes();
    MeshTopology topology = readCheckedMesh();   // kept for the quality checks and VTK
    dynamicMeshDict_ = io::Dictionary::readFile(caseDirectory_ / "constant" / "dynamicMeshDict");
    const fs::path boundaryFieldPath = io::resolveMaybeCompressed(boundaryFieldFile_);
    boundaryField_ = io::readPointVectorField(boundaryFieldPath, mesh_);

    solver_ = motion::builtinMotionSolvers().create(mesh_, dynamicMeshDict_, &boundaryField_.dictionary,
                                                     caseDirectory_);
    // Before the solver assembles anything: does the solve fit in the memory there is?
    if (const std::optional<motion::AvailableMemory> available = availableMemory())
        memoryNote_ = solver_->fitIntoMemory(*available);
    computeNodeClasses();
    // The quality checks: the topology above (and VTK's below) and the
    // solver's 2D mesh of a pseudo-3D case, each built once.
    assessor_ = std::make_unique<motion::StepAssessor>(mesh_, std::move(topology), solver_->twoDMesh());
    cells_ = std::make_unique<CellFieldWorkspace>();

    // The displacement at the start time: the start folder's internalField (zero in a fresh
    // case; the total displacement of that time in a folder an earlier run wrote). It is the
    // initial mesh (points0 + displacement) and the warm start of the first solve. The solver's
    // own initial state is not used: it already holds the time-independent boundary values,
    // which would show the initial mesh with its boundary moved and its interior not.
    std::vector<Vector3> initial(mesh_.points.size());
    const fs::path startField = caseDirectory_ / startTimeName_ / "pointDisplacement";
    if (io::existsMaybeCompressed(startField)) {
        const fs::path startFieldPath = io::resolveMaybeCompressed(startField);
        if (fs::equivalent(startFieldPath, boundaryFieldPath, error)) {
            initial = std::move(boundaryField_.internalField);
        } else {
            initial = io::readPointVectorField(startFieldPath, mesh_).internalField;
        }
        if (std::any_of(initial.begin(), initial.end(), [](const Vector3& u) { return u != Vector3{}; })) {
            warmStartFile_ = startFieldPath;
        }
    }
    solver_->pointDisplacement() = std::move(initial);
    // The boundary field's own values are read once, here: the output writes the solver's.
    std::vector<Vector3>().swap(boundaryField_.internalField);

    if (options_.writeVtk) {
        cells_->vtkCells = io::vtkCellsOf(mesh_, assessor_->topology());
        // Not a clean extrusion (no 2D mesh): the 3D cell metrics are written instead.
        cells_->twoD = assessor_->twoDMesh();
        pvd_ = std::make_unique<io::PvdCollection>(caseDirectory_ / "VTK" / (caseName_ + ".pvd"));
        pvd_->load();
    }

    timeNameWidth_ = std::max<int>(8, static_cast<int>(std::max(startTimeName_.size(),
                                                                control_.timeName(control_.endTime).size())));
}

void MoveMeshRun::readTimes()
{
    RunTimes times = readRunTimes(caseDirectory_, caseDirectory_);
    control_ = std::move(times.control);
    timePrecision_ = control_.timePrecision;
    startTime_ = times.startTime;
    startTimeName_ = std::move(times.startTimeName);
    stepCount_ = times.stepCount;
    endTolerance_ = times.endTolerance;
    boundaryFieldFile_ = std::move(times.boundaryFieldFile);
}

MeshTopology MoveMeshRun::readCheckedMesh()
{
    const fs::path polyMeshFolder = caseDirectory_ / "constant" / "polyMesh";
    mesh_ = io::readPolyMesh(polyMeshFolder);
    // OpenFOAM's rules the reader does not check one file at a time: upper-triangular face
    // order, closed and consistently oriented cells, no point twice in a face. Inverted
    // cells are not an input error here (the initial mesh's are reported as a warning).
    TopologyCheckOptions topologyChecks;
    topologyChecks.checkCellVolumes = false;
    topologyChecks.maxMessages = 5;
    MeshTopology topology;   // built by the check
    if (const auto problems = checkPolyMeshOrdering(mesh_, topologyChecks, topology); !problems.empty()) {
        std::string text = "the mesh breaks OpenFOAM's polyMesh rules (files faces, owner, neighbour):";
        for (const std::string& problem : problems) text += "\n  " + problem;
        throw InputError(polyMeshFolder.string(), 0, text);
    }
    return topology;
}

MoveMeshRun::~MoveMeshRun() = default;

fs::path MoveMeshRun::jsonLogFile() const
{
    return caseDirectory_ / "postProcessing" / "rbmMoveMesh" / startTimeName_ / "log.jsonl";
}

void MoveMeshRun::computeNodeClasses()
{
    // For the VTK output and the written boundary conditions: the classes the solver uses
    // (prescribed beats sliding beats free).
    const motion::BoundaryDescription& boundary = solver_->boundary();
    nodeClasses_.assign(mesh_.points.size(), nodeFree);
    prescribedPatches_.assign(mesh_.patches.size(), 0);
    for (std::size_t p = 0; p < boundary.size(); ++p) {
        std::uint8_t nodeClass = nodeFree;
        switch (boundary[p].nodeClass) {
        case motion::BoundaryNodeClass::prescribed:
            nodeClass = nodePrescribed;
            prescribedPatches_[p] = 1;
            break;
        case motion::BoundaryNodeClass::sliding: nodeClass = nodeSliding; break;
        case motion::BoundaryNodeClass::free:
        case motion::BoundaryNodeClass::coupled:
        case motion::BoundaryNodeClass::ignored: continue;
        }
        for (const Label point : boundary[p].meshPoints) {
            std::uint8_t& current = nodeClasses_[static_cast<std::size_t>(point)];
            current = std::max(current, nodeClass);
        }
    }
}

std::optional<motion::AvailableMemory> MoveMeshRun::availableMemory()
{
    // What RBM_AVAILABLE_MEMORY_MB says (tests; a machine whose figures mislead), else what the
    // machine can give.
    const char* limit = std::getenv("RBM_AVAILABLE_MEMORY_MB");
    if (!limit || !*limit) return motion::availableMemory();
    char* end = nullptr;
    const double mebibytes = std::strtod(limit, &end);
    if (end == limit || *end != '\0' || !(mebibytes >= 0.0)) {
        throw InputError("RBM_AVAILABLE_MEMORY_MB", 0,
                         std::string("expected a number of MiB (the memory rbmMoveMesh may use), found '") + limit + "'");
    }
    return motion::AvailableMemory{mebibytes * 1048576.0, "RBM_AVAILABLE_MEMORY_MB"};
}

void MoveMeshRun::checkBoundaryDisplacementIsFinite(double time) const
{
    const std::vector<Vector3>& displacement = solver_->pointDisplacement();
    if (std::all_of(displacement.begin(), displacement.end(), [](const Vector3& u) { return isFinite(u); })) return;
    for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
        for (const Label point : io::patchPointLabels(mesh_, static_cast<Label>(p))) {
            const Vector3& u = displacement[static_cast<std::size_t>(point)];
            if (isFinite(u)) continue;
            const io::PointPatchFieldEntry& entry = boundaryField_.boundaryField[p];
            throw InputError(entry.dictionary.file().empty() ? boundaryFieldFile_.string() : entry.dictionary.file(),
                             entry.dictionary.line(),
                             "the boundary condition of patch " + mesh_.patches[p].name + " (type " + entry.type +
                                 ") gives the displacement (" + general(u.x) + " " + general(u.y) + " " +
                                 general(u.z) + ") at time " + general(time) + " (point " + std::to_string(point) +
                                 "); expected finite numbers");
        }
    }
    throw std::runtime_error("the displacement of a point inside the mesh is NaN or infinite before the solve at time " +
                             general(time));
}

void MoveMeshRun::printHeader() const
{
    auto relative = [&](const fs::path& file) {
        std::error_code error;
        const fs::path shown = fs::relative(file, caseDirectory_, error);
        return (error || shown.empty()) ? file.string() : shown.string();
    };
    const char* startFrom = control_.startFrom == io::ControlDict::StartFrom::StartTime   ? "startTime"
                            : control_.startFrom == io::ControlDict::StartFrom::FirstTime ? "firstTime"
                                                                                          : "latestTime";
    const char* writeControl = "timeStep";
    switch (control_.writeControl) {
    case io::ControlDict::WriteControl::TimeStep: writeControl = "timeStep"; break;
    case io::ControlDict::WriteControl::RunTime: writeControl = "runTime"; break;
    case io::ControlDict::WriteControl::AdjustableRunTime: writeControl = "adjustableRunTime"; break;
    case io::ControlDict::WriteControl::CpuTime: writeControl = "cpuTime"; break;
    case io::ControlDict::WriteControl::ClockTime: writeControl = "clockTime"; break;
    }
    out_ << versionText() << "\n"
         << "Case          : " << caseDirectory_.string() << "\n"
         << "Mesh          : " << mesh_.pointCount() << " points, " << mesh_.faceCount() << " faces, "
         << mesh_.cellCount() << " cells, " << mesh_.patches.size() << " patches\n"
         << "Motion solver : " << solver_->typeName();
    if (const std::string settings = solver_->describe(); !settings.empty()) out_ << ": " << settings;
    out_ << " (constant/dynamicMeshDict)\n"
         << "Boundary      : " << relative(boundaryFieldFile_) << "\n"
         << "Threads       : " << describeThreadCount() << "\n";
    if (!memoryNote_.empty()) out_ << "Memory        : " << memoryNote_ << "\n";
    if (warmStartFile_) out_ << "Warm start    : " << relative(*warmStartFile_) << "\n";
    out_ << "Time          : from " << startTimeName_ << " (startFrom " << startFrom << ") to "
         << control_.timeName(control_.endTime) << ", deltaT " << general(control_.deltaT) << ": " << stepCount_
         << (stepCount_ == 1 ? " step" : " steps") << "\n"
         << "Write         : writeControl " << writeControl << ", writeInterval " << general(control_.writeInterval)
         << ", " << (control_.binary ? "binary" : "ascii") << ", precision " << control_.writePrecision
         << (control_.writeCompression ? ", compressed" : "") << (options_.writeVtk ? "; VTK in VTK/" : "; no VTK")
         << (options_.writeInvalid ? "; -writeInvalid" : "") << "\n"
         << "Log           : " << relative(jsonLogFile()) << "\n\n";
    const double reached = stepTime(stepCount_);
    if (std::abs(reached - control_.endTime) > endTolerance_ * control_.deltaT) {
        err_ << "rbmMoveMesh: warning: endTime " << general(control_.endTime)
             << " is not a whole number of time steps after the start; the run stops at " << general(reached) << "\n";
    }
    // As in OpenFOAM, the last time is written only when it is a write time.
    bool lastIsWritten = true;
    if (stepCount_ > 0 && control_.writeControl == io::ControlDict::WriteControl::TimeStep) {
        lastIsWritten = stepCount_ % std::max<long long>(1, std::llround(control_.writeInterval)) == 0;
    } else if (stepCount_ > 0 && (control_.writeControl == io::ControlDict::WriteControl::RunTime ||
                                  control_.writeControl == io::ControlDict::WriteControl::AdjustableRunTime)) {
        auto index = [&](int step) {
            return static_cast<long long>((step + 0.5) * control_.deltaT / control_.writeInterval);
        };
        lastIsWritten = index(stepCount_) > std::max<long long>(0, index(stepCount_ - 1));
    }
    if (!lastIsWritten) {
        err_ << "rbmMoveMesh: warning: the last time " << general(reached)
             << " is not a write time (writeControl, writeInterval): its mesh will not be written\n";
    }
}

// ---- Time names and write times ---------------------------------------------------------------

std::string MoveMeshRun::timeNameOf(double time)
{
    const int precision = io::adjustedTimePrecision(time, control_.deltaT, control_.timeFormat, timePrecision_);
    if (precision > timePrecision_) {
        // OpenFOAM's Time does the same, with the same message.
        err_ << "rbmMoveMesh: Increased the timePrecision from " << timePrecision_ << " to " << precision
             << " to distinguish between timeNames at time " << general(time, 17) << "\n";
        timePrecision_ = precision;
    }
    return io::timeName(time, control_.timeFormat, timePrecision_);
}

// ---- Writing ----------------------------------------------------------------------------------

void MoveMeshRun::writeTime(const std::string& timeName, const std::vector<Vector3>& points)
{
    if (!options_.writesFiles) return;
    io::TimeFolderWriter folder(caseDirectory_, timeName);
    stageMeshMotion(folder, timeName, mesh_, points, solver_->pointDisplacement(), boundaryField_, prescribedPatches_,
                    control_);
    folder.commit();
}

void MoveMeshRun::writeVtk(double time, const std::string& timeName, const std::vector<Vector3>& points)
{
    if (!options_.writesFiles) return;
    // assessor_ evaluated `points` just before (their geometry, computed now if the step's
    // evaluation did without it).
    const MeshGeometry& geometry = assessor_->geometryAt(points);
    const std::size_t cellCount = geometry.cellVolumes.size();
    const Label internalFaces = mesh_.internalFaceCount();

    io::VtkField nonOrthogonality{"nonOrthogonality", 1, std::vector<double>(cellCount, 0.0)};
    io::VtkField skewness{"skewness", 1, std::vector<double>(cellCount, 0.0)};
    io::VtkField volume{"volume", 1, geometry.cellVolumes};
    io::VtkField quality{"quality", 1, std::vector<double>(cellCount, std::numeric_limits<double>::quiet_NaN())};
    io::VtkField inverted{"inverted", 1, std::vector<double>(cellCount, 0.0)};

    constexpr double degrees = 180.0 / std::numbers::pi;
    for (Label f = 0; f < mesh_.faceCount(); ++f) {
        const Label owner = mesh_.owner[static_cast<std::size_t>(f)];
        const Vector3& faceCentre = geometry.faceCentres[static_cast<std::size_t>(f)];
        const Vector3& faceArea = geometry.faceAreas[static_cast<std::size_t>(f)];
        const Vector3& ownerCentre = geometry.cellCentres[static_cast<std::size_t>(owner)];
        if (f < internalFaces) {
            const Label neighbour = mesh_.neighbour[static_cast<std::size_t>(f)];
            const Vector3& neighbourCentre = geometry.cellCentres[static_cast<std::size_t>(neighbour)];
            const double cosine = faceNonOrthogonalityCosine(ownerCentre, neighbourCentre, faceArea);
            const double angle = std::acos(std::clamp(cosine, -1.0, 1.0)) * degrees;
            const double skew = faceSkewness(mesh_.face(f), points, faceCentre, faceArea, ownerCentre, neighbourCentre);
            for (const Label cell : {owner, neighbour}) {
                auto& n = nonOrthogonality.values[static_cast<std::size_t>(cell)];
                auto& s = skewness.values[static_cast<std::size_t>(cell)];
                n = std::max(n, angle);
                s = std::max(s, skew);
            }
        } else {
            auto& s = skewness.values[static_cast<std::size_t>(owner)];
            s = std::max(s, boundaryFaceSkewness(mesh_.face(f), points, faceCentre, faceArea, ownerCentre));
        }
    }

    if (cells_->twoD) {
        // 2D: the thesis' q (triangles) and F_shape (quadrilaterals) on the front plane, and
        // inverted = signed area <= 0, as the 2D quality report counts them.
        const PseudoTwoDMesh& twoD = *cells_->twoD;
        cells_->nodePositions.resize(static_cast<std::size_t>(twoD.nodeCount()));
        for (Label n = 0; n < twoD.nodeCount(); ++n) {
            cells_->nodePositions[static_cast<std::size_t>(n)] =
                twoD.frame.toLocal(points[static_cast<std::size_t>(twoD.frontPointOfNode[static_cast<std::size_t>(n)])]);
        }
        const auto& nodes = cells_->nodePositions;
        for (Label c = 0; c < twoD.planar.cellCount(); ++c) {
            const auto polygon = twoD.planar.cell(c);
            double& q = quality.values[static_cast<std::size_t>(c)];
            if (polygon.size() == 3) {
                q = triangleMeanRatio(nodes[polygon[0]], nodes[polygon[1]], nodes[polygon[2]]);
            } else if (polygon.size() == 4) {
                q = quadrilateralShape(nodes[polygon[0]], nodes[polygon[1]], nodes[polygon[2]], nodes[polygon[3]]);
            }
            inverted.values[static_cast<std::size_t>(c)] = twoD.planar.signedArea(c, nodes) <= 0.0 ? 1.0 : 0.0;
        }
    } else {
        const MeshTopology& topology = assessor_->cellFaceTopology();
        for (std::size_t c = 0; c < cellCount; ++c) {
            const motion::PyramidQuality pyramids = motion::cellPyramidQuality(mesh_, topology, geometry, static_cast<Label>(c));
            quality.values[c] = pyramids.ratio;
            inverted.values[c] = pyramids.inverted ? 1.0 : 0.0;
        }
    }

    const std::vector<Vector3>& displacement = solver_->pointDisplacement();
    io::VtkField displacementField{"pointDisplacement", 3, std::vector<double>(3 * displacement.size())};
    for (std::size_t i = 0; i < displacement.size(); ++i) {
        displacementField.values[3 * i] = displacement[i].x;
        displacementField.values[3 * i + 1] = displacement[i].y;
        displacementField.values[3 * i + 2] = displacement[i].z;
    }
    io::VtkField nodeClass{"nodeClass", 1, std::vector<double>(nodeClasses_.begin(), nodeClasses_.end())};

    const std::string dataset = caseName_ + "_" + timeName + ".vtu";
    const fs::path folder = caseDirectory_ / "VTK";
    fs::create_directories(folder);
    io::writeVtu(folder / dataset, points, *cells_->vtkCells, {displacementField, nodeClass},
                 {nonOrthogonality, skewness, volume, quality, inverted});
    pvd_->add(time, dataset);
    pvd_->write();
}

// ---- The loop -------------------------------------------------------------------------------

int MoveMeshRun::run()
{
    const Clock::time_point runStart = Clock::now();
    writeSchedule_ = std::make_unique<WriteSchedule>(control_, startTime_);
    removeInterruptedWrites();
    printHeader();
    io::JsonLinesWriter jsonLog = options_.writesFiles ? io::JsonLinesWriter(jsonLogFile(), true) : io::JsonLinesWriter();
    std::vector<Vector3> points = solver_->curPoints();
    reportInitialMesh(points);

    int exitStatus = exitSuccess;
    int stepsRun = 0;
    for (int step = 1; step <= stepCount_; ++step)
        if (!runStep(step, points, jsonLog, exitStatus, stepsRun)) break;
    printSummary(stepsRun, secondsSince(runStart));
    return exitStatus;
}

void MoveMeshRun::removeInterruptedWrites()
{
    if (!options_.writesFiles) return;
    for (const std::string& name : io::removeStaleStagingFolders(caseDirectory_))
        err_ << "rbmMoveMesh: removed " << name << ", the unfinished time folder of an interrupted run\n";
    for (const std::string& name : io::removeStaleTemporaries(caseDirectory_ / "VTK", {".vtu", ".pvd"}))
        err_ << "rbmMoveMesh: removed VTK/" << name << ", the unfinished VTK file of an interrupted run\n";
}

void MoveMeshRun::reportInitialMesh(const std::vector<Vector3>& points)
{
    // The initial mesh: quality, and the first entry of the VTK series.
    const StepQuality initial = assessor_->evaluateStep(points);
    out_ << "Initial mesh (time " << startTimeName_ << "): worst quality " << fixed(initial.worstCellQuality, 4)
         << ", max non-orthogonality " << fixed(initial.maxNonOrthogonality, 2) << ", max skewness "
         << fixed(initial.maxSkewness, 3) << ", inverted " << initial.invertedCellCount << "\n\n";
    if (initial.invertedCellCount > 0) {
        err_ << "rbmMoveMesh: warning: the initial mesh already has " << initial.invertedCellCount
             << " inverted cells\n";
    }
    if (options_.writeVtk) writeVtk(startTime_, startTimeName_, points);
    // Not held through the solves (QualityEvaluator::releaseWorkspaces).
    assessor_->releaseWorkspaces();
    out_.flush();
}

bool MoveMeshRun::runStep(int step, std::vector<Vector3>& points, io::JsonLinesWriter& jsonLog, int& exitStatus,
                          int& stepsRun)
{
    threads_.update();   // the cores others left during the last step (or the set-up)
    const Clock::time_point stepStart = Clock::now();
    const double time = stepTime(step);
    std::string name;
    int writtenParts = 0;   // for an error's message (writtenByStep)
    try {
        name = timeNameOf(time);
        solver_->updateBoundaryConditions(time);
        checkBoundaryDisplacementIsFinite(time);
        std::vector<Vector3>().swap(points);   // the last step's: not held through the solve
        const motion::MotionSolveReport solve = solver_->solve();
        points = solver_->curPoints();
        for (const std::string& warning : solve.warnings)
            err_ << "rbmMoveMesh: warning: time " << name << ": " << warning << '\n';

        // A solve that produced NaN or infinite values failed whatever it reports; such a
        // mesh is never written (not even with -writeInvalid) and stops the run.
        io::StepLogRecord record;
        record.step = step;
        record.time = time;
        record.timeName = name;
        const motion::StepVerdict verdict = assessor_->assess(solve, solver_->pointDisplacement(), points, record);
        const bool scheduled = writeSchedule_->isWriteTime(step, time);   // called every step: it keeps state
        if (verdict.valid ? scheduled : options_.writeInvalid && verdict.finite) {
            if (!verdict.valid) warnWritingInvalid(record);
            writeTime(name, points);
            writtenParts = 1;
            if (options_.writeVtk) writeVtk(time, name, points);
            writtenParts = 2;
            record.written = true;
        }
        record.wallSeconds = secondsSince(stepStart);

        out_ << io::formatStepLogLine(record, timeNameWidth_) << '\n';
        out_.flush();
        if (jsonLog.isOpen()) jsonLog.append(io::stepLogJson(record));
        ++stepsRun;
        extremes_.add(record, step, verdict.finite);
        if (observer_) observer_(StepObservation{record, *solver_, points, verdict.valid});
        assessor_->releaseWorkspaces();

        if (verdict.valid) return true;
        ++extremes_.invalidSteps;
        exitStatus = exitRunFailed;
        if (options_.writeInvalid && verdict.finite) return true;
        err_ << "rbmMoveMesh: time " << name << ": " << motion::invalidStepCause(verdict, record)
             << ".\nNothing was written for time " << name << (verdict.finite ? "" : " (not even with -writeInvalid)")
             << "; earlier times stay as written. "
             << motion::invalidStepAdvice(verdict, record, "-writeInvalid writes the step anyway to look at it",
                                          solver_->invertedStepAdvice())
             << "\n";
        return false;
    } catch (const InputError& error) {
        err_ << "rbmMoveMesh: time " << (name.empty() ? general(time) : name) << ": " << error.what() << '\n'
             << writtenByStep(name, writtenParts, options_.writeVtk) << '\n';
        exitStatus = exitBadInput;
        return false;
    } catch (const std::exception& error) {
        err_ << "rbmMoveMesh: time " << (name.empty() ? general(time) : name) << ": " << error.what() << '\n'
             << writtenByStep(name, writtenParts, options_.writeVtk) << '\n';
        exitStatus = exitRunFailed;
        return false;
    }
}

void MoveMeshRun::warnWritingInvalid(const io::StepLogRecord& record)
{
    err_ << "\n*** WARNING (-writeInvalid): writing time " << record.timeName << " although "
         << (record.invertedCells > 0 ? std::to_string(record.invertedCells) + " cells are inverted"
                                      : std::string("the solve did not converge (") + record.reason + ")")
         << ": this mesh is NOT valid for a flow solver ***\n\n";
}

void MoveMeshRun::printSummary(int stepsRun, double wallSeconds) const
{
    extremes_.print(out_, stepsRun, stepCount_, wallSeconds);
}

// ---- Program --------------------------------------------------------------------------------

int runMoveMesh(const MoveMeshOptions& options, std::ostream& out, std::ostream& err,
                std::function<void(const StepObservation&)> observer)
{
    std::optional<io::CaseLock> lock;   // a -parallel run's rank 0 holds it in runOnAllRanks
    if (options.writesFiles && !options.parallel && !lockCase(options.caseDirectory, lock, err)) return exitBadInput;
    std::unique_ptr<MoveMeshRun> run;
    try {
        run = std::make_unique<MoveMeshRun>(options, out, err);
    } catch (const InputError& error) {
        err << "rbmMoveMesh: " << error.what() << "\nNothing was written.\n";
        return exitBadInput;
    } catch (const std::invalid_argument& error) {
        // The solver's checks of the problem it was given (boundary conditions, mesh).
        err << "rbmMoveMesh: " << error.what() << "\nNothing was written.\n";
        return exitBadInput;
    } catch (const std::exception& error) {
        err << "rbmMoveMesh: " << error.what() << "\nNothing was written.\n";
        return exitRunFailed;
    } catch (...) {
        err << "rbmMoveMesh: unknown error while reading the case\nNothing was written.\n";
        return exitRunFailed;
    }
    try {
        if (observer) run->setStepObserver(std::move(observer));
        return run->run();
    } catch (const InputError& error) {
        err << "rbmMoveMesh: " << error.what() << '\n';
        return exitBadInput;
    } catch (const std::exception& error) {
        err << "rbmMoveMesh: " << error.what() << '\n';
        return exitRunFailed;
    } catch (...) {
        err << "rbmMoveMesh: unknown error\n";
        return exitRunFailed;
    }
}

namespace {

// A -parallel run: every rank runs the whole program on the replicated case with the
// solvers distributed over PETSC_COMM_WORLD (BlockRowLayout.hpp); rank 0 prints and writes.
// The other ranks keep their messages and print them only when their exit status differs
// from rank 0's (a failure of their own), so a bad case is reported once.
int runOnAllRanks(MoveMeshOptions options, int rank, std::ostream& out, std::ostream& err)
{
    std::optional<io::CaseLock> lock;
    int refused = rank == 0 && !lockCase(options.caseDirectory, lock, err);
    MPI_Bcast(&refused, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    if (refused) return exitBadInput;
    motion::setSolverCommunicator(PETSC_COMM_WORLD);
    std::ostringstream quietOut, quietErr;
    options.writesFiles = rank == 0;
    const int status = runMoveMesh(options, rank == 0 ? out : quietOut, rank == 0 ? err : quietErr);
    motion::setSolverCommunicator(PETSC_COMM_SELF);
    int statusOfRankZero = status;
    MPI_Bcast(&statusOfRankZero, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    if (rank != 0 && status != statusOfRankZero) err << "[rank " << rank << "] " << quietErr.str();
    int worst = status;
    MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    return worst;
}

} // namespace

int moveMeshMain(int argc, char** argv, std::ostream& out, std::ostream& err)
{
    try {
        const CommandLine commandLine = parseCommandLine(argc, argv);
        if (commandLine.help) {
            out << usageText();
            return exitSuccess;
        }
        if (commandLine.version) {
            out << versionText() << '\n';
            return exitSuccess;
        }

        // PETSc sees only its own options (PetscInitialize keeps pointers to them: they live
        // as long as the session).
        std::vector<std::string> petscStorage;
        petscStorage.emplace_back(argc > 0 ? argv[0] : "rbmMoveMesh");
        petscStorage.insert(petscStorage.end(), commandLine.petscArguments.begin(), commandLine.petscArguments.end());
        std::vector<char*> petscPointers;
        for (std::string& argument : petscStorage) petscPointers.push_back(argument.data());
        petscPointers.push_back(nullptr);
        int petscArgc = static_cast<int>(petscStorage.size());
        char** petscArgv = petscPointers.data();
        motion::PetscSession session(&petscArgc, &petscArgv);

        int size = 1;
        int rank = 0;
        MPI_Comm_size(PETSC_COMM_WORLD, &size);
        MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
        if (size > 1 && !commandLine.options.parallel) {
            // N copies of a serial run would all write the same time folders.
            if (rank == 0) {
                err << "rbmMoveMesh: started on " << size
                    << " MPI ranks without -parallel. Add -parallel to distribute the solve over the ranks, "
                       "or run on one process.\n";
            }
            return exitBadInput;
        }
        applyThreadCountPolicy(size);   // OMP_NUM_THREADS, else the cores, else 1 per rank (ThreadCount.hpp)
        // A case decomposePar split: each rank moves its processor folder (DecomposedMoveMeshRun.hpp).
        if (isDecomposedRun(commandLine.options))
            return runDecomposedMoveMesh(commandLine.options, PETSC_COMM_WORLD, out, err);
        if (size == 1) return runMoveMesh(commandLine.options, out, err);
        return runOnAllRanks(commandLine.options, rank, out, err);
    } catch (const UsageError& error) {
        err << "rbmMoveMesh: " << error.what() << "\n\n" << usageText();
        return exitBadInput;
    } catch (const std::exception& error) {
        err << "rbmMoveMesh: " << error.what() << '\n';
        return exitRunFailed;
    } catch (...) {
        err << "rbmMoveMesh: unknown error\n";
        return exitRunFailed;
    }
}

} // namespace rbm::app
