#pragma once
// rbmMoveMesh's time loop, outside main so that tests can run it: OpenFOAM's moveMesh with
// rbm's motion solver (docs/method.md §5).
//
// The run (documented for users in docs/rbmMoveMesh.md):
//  0. A run that writes takes the case lock (io/CaseLock.hpp) before reading anything: a
//     second rbmMoveMesh on the case meanwhile is refused (exit status 2).
//  1. Setup reads and checks every input before anything is written: system/controlDict,
//     constant/dynamicMeshDict, constant/polyMesh, the point displacement field with the
//     boundary conditions, and for a restart the warm start. Bad input is an rbm::InputError
//     and leaves the case folder exactly as it was.
//  2. Steps k = 1..N at t_k = startTime + k deltaT (computed, not accumulated, so a period's
//     end lands exactly on its time), N = the largest k with t_k <= endTime + 1e-9 deltaT (or a few
//     ulps of the times when they are large against deltaT).
//     Each step: updateBoundaryConditions(t_k), solve() for the total displacement against
//     points0 = constant/polyMesh/points (warm-started from the previous step), quality of
//     curPoints(), one log line and one JSON line.
//  3. At write times (controlDict writeControl) the step is written atomically:
//     <time>/polyMesh/points, <time>/pointDisplacement and, unless -noVTK,
//     VTK/<caseName>_<time>.vtu with VTK/<caseName>.pvd. The initial mesh goes to VTK too.
//  4. A step with inverted cells or a solve that did not converge (the message gives PETSc's
//     converged/diverged reason) stops the run with exit status 1 and writes nothing for that
//     step; with -writeInvalid it is written anyway (whatever the write schedule) with a loud
//     warning, the run goes on, and the exit status is still 1. A solve that produced NaN or
//     infinite values (displacements or residual) always stops the run and is never written;
//     a boundary condition that gives NaN or infinite displacements is bad input (status 2),
//     naming the patch's entry.
//  Setup also checks OpenFOAM's polyMesh rules across files (upper-triangular order, closed
//  cells), rejects a patch both moving and sliding (a motion given by name to a symmetry
//  or symmetryPlane patch), and, before the solver assembles, compares the estimated memory
//  of the solve (motionSolvers/rigidBodyMotion/MemoryEstimate.hpp) with what the machine has.
//
// Restart (startFrom latestTime, or a startTime whose folder an earlier run wrote): the
// boundary conditions are those of the earliest time folder up to the start time that has
// a pointDisplacement (normally 0/pointDisplacement: the conditions are functions of the
// absolute time, given once); the start folder's own pointDisplacement, when it is another
// file, only warm-starts the solver (its internalField is the total displacement of that
// time). The start folder's polyMesh/points are not read: the mesh at any time is
// points0 + pointDisplacement.

#include "ControlDict.hpp"
#include "LoadAdaptiveThreads.hpp"
#include "MemoryEstimate.hpp"
#include "MotionSolver.hpp"
#include "PointVectorField.hpp"
#include "PolyMesh.hpp"
#include "QualityReport.hpp"
#include "RunLog.hpp"
#include "StepAssessment.hpp"
#include "ThreadCount.hpp"
#include "VtkWriter.hpp"
#include "RunSummary.hpp"
#include "RunTimes.hpp"
#include "WriteSchedule.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rbm::app {

// Exit statuses of rbmMoveMesh.
inline constexpr int exitSuccess = 0;
inline constexpr int exitRunFailed = 1;   // inverted cells, no convergence, NaN, not enough memory, a failure during the run
inline constexpr int exitBadInput = 2;    // bad command line or case, or the case locked by another run (nothing written)

struct MoveMeshOptions {
    std::filesystem::path caseDirectory = ".";
    bool writeVtk = true;        // -noVTK turns it off
    bool writeInvalid = false;   // -writeInvalid
    bool parallel = false;       // -parallel
    // False on the MPI ranks other than 0 of a -parallel run: every rank reads the case and
    // takes part in the distributed solve, rank 0 alone writes (time folders, VTK, log).
    bool writesFiles = true;
};

// A command-line problem: printed with the usage, exit status 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct CommandLine {
    MoveMeshOptions options;
    bool help = false;
    bool version = false;
    // PETSc's options with their values, in order (handed to PetscInitialize).
    std::vector<std::string> petscArguments;
};

// rbmMoveMesh's own options may come anywhere; every other option must be PETSc's, which
// is recognised by an underscore in its name (-ksp_type, -rbm_pc_type, -log_view) or by
// name (-info, -malloc, -malloc_debug, -nox, -options_file ...): it is passed on together
// with the arguments that follow it up to the next option (its value). Anything else
// (an unknown option such as -noVtk, a stray word) is a UsageError.
CommandLine parseCommandLine(int argc, const char* const* argv);

// The text of -help: options, files, dictionary keywords, log format, exit statuses.
std::string usageText();
// "rbmMoveMesh <version> (PETSc <version>)".
std::string versionText();

// One time step, as a test or a host sees it after the step (written or not).
struct StepObservation {
    const io::StepLogRecord& record;
    const motion::MotionSolver& solver;
    const std::vector<Vector3>& points;   // curPoints() of the step
    bool valid = true;
};

class MoveMeshRun {
public:
    // Setup (step 1 above): reads and checks everything, writes nothing. Throws
    // rbm::InputError (or std::invalid_argument from the solver's checks) for bad input.
    // `out` receives the header and the log lines, `err` warnings and errors.
    MoveMeshRun(MoveMeshOptions options, std::ostream& out, std::ostream& err);
    ~MoveMeshRun();
    MoveMeshRun(const MoveMeshRun&) = delete;
    MoveMeshRun& operator=(const MoveMeshRun&) = delete;

    // Called after every step, before the run may stop.
    void setStepObserver(std::function<void(const StepObservation&)> observer) { observer_ = std::move(observer); }

    // Steps 2-4: returns exitSuccess or exitRunFailed. Exceptions during the run (an
    // InputError found late, a PETSc failure) propagate; runMoveMesh turns them into
    // exit statuses.
    int run();

    double startTime() const { return startTime_; }
    int stepCount() const { return stepCount_; }
    double stepTime(int step) const { return startTime_ + step * control_.deltaT; }
    const io::ControlDict& controlDict() const { return control_; }
    const PolyMesh& mesh() const { return mesh_; }
    const motion::MotionSolver& solver() const { return *solver_; }
    std::string caseName() const { return caseName_; }
    // postProcessing/rbmMoveMesh/<startTime>/log.jsonl
    std::filesystem::path jsonLogFile() const;

private:
    struct CellFieldWorkspace;

    // rbm's threads on a shared machine: the cores other processes leave, measured from the
    // run's start on (src/LoadAdaptiveThreads.hpp).
    LoadAdaptiveThreads threads_{threadCount()};

    void printHeader() const;
    std::string timeNameOf(double time);
    void writeTime(const std::string& timeName, const std::vector<Vector3>& points);
    void writeVtk(double time, const std::string& timeName, const std::vector<Vector3>& points);
    // The constructor's parts: controlDict's times (start, step count), the start folder and
    // the pointDisplacement file of the boundary conditions (RunTimes.hpp); the mesh, checked
    // against OpenFOAM's polyMesh rules (its topology, built by the check, returned).
    void readTimes();
    MeshTopology readCheckedMesh();
    // nodeClasses_ and prescribedPatches_ from the solver's boundary description.
    void computeNodeClasses();
    // The memory the solve may use: RBM_AVAILABLE_MEMORY_MB (MiB) when set, else what the
    // machine can give; the solver fits itself into it (MotionSolver::fitIntoMemory) before
    // it assembles anything. Throws InputError for a malformed RBM_AVAILABLE_MEMORY_MB.
    static std::optional<motion::AvailableMemory> availableMemory();
    // Throws rbm::InputError naming the patch whose condition gave a NaN or infinite
    // displacement at `time` (called after updateBoundaryConditions).
    void checkBoundaryDisplacementIsFinite(double time) const;
    void printSummary(int stepsRun, double wallSeconds) const;
    // run()'s parts: the leftovers of an interrupted run's writes removed (and said); the
    // initial mesh's quality line (and VTK); one time step, false when the run stops there
    // (exitStatus then says why).
    void removeInterruptedWrites();
    void reportInitialMesh(const std::vector<Vector3>& points);
    bool runStep(int step, std::vector<Vector3>& points, io::JsonLinesWriter& jsonLog, int& exitStatus, int& stepsRun);
    void warnWritingInvalid(const io::StepLogRecord& record);

    MoveMeshOptions options_;
    std::ostream& out_;
    std::ostream& err_;
    std::filesystem::path caseDirectory_;
    std::string caseName_;
    io::ControlDict control_;
    double startTime_ = 0.0;
    std::string startTimeName_;
    int stepCount_ = 0;
    double endTolerance_ = 1e-9;   // in steps
    int timePrecision_ = 6;
    int timeNameWidth_ = 8;
    std::filesystem::path boundaryFieldFile_;
    std::optional<std::filesystem::path> warmStartFile_;

    PolyMesh mesh_;
    io::Dictionary dynamicMeshDict_;
    std::string memoryNote_;  // printed in the header when the solver went leaner to fit in memory
    io::PointVectorField boundaryField_;   // its internalField released after the start (not used)
    std::unique_ptr<motion::MotionSolver> solver_;
    std::vector<std::uint8_t> nodeClasses_;   // per point: 0 free, 1 sliding, 2 prescribed
    std::vector<std::uint8_t> prescribedPatches_;   // per patch: 1 when its condition is prescribed

    std::unique_ptr<motion::StepAssessor> assessor_;   // quality, log figures, validity of a step
    std::unique_ptr<CellFieldWorkspace> cells_;
    std::unique_ptr<io::PvdCollection> pvd_;

    std::unique_ptr<WriteSchedule> writeSchedule_;   // from run()'s start

    std::function<void(const StepObservation&)> observer_;

    RunSummary extremes_;   // worst values over the run, for the summary
};

// Setup and run with every exception turned into an exit status and a message on `err`
// (InputError and usage problems: 2; failures during the run: 1). Never throws. A run
// that writes (options.writesFiles, not -parallel) first locks the case (io/CaseLock.hpp)
// and returns 2 when another run holds it; a -parallel run's rank 0 locks in moveMeshMain.
int runMoveMesh(const MoveMeshOptions& options, std::ostream& out, std::ostream& err,
                std::function<void(const StepObservation&)> observer = {});

// The whole program: command line, PETSc session (with the PETSc options), -help,
// -version, the parallel check, runMoveMesh. Never throws.
int moveMeshMain(int argc, char** argv, std::ostream& out, std::ostream& err);

} // namespace rbm::app
