#include "DecomposedMoveMeshRun.hpp"

#include "CaseLock.hpp"
#include "CompressedFile.hpp"
#include "DecomposedCase.hpp"
#include "InputError.hpp"
#include "MeshTopology.hpp"
#include "MotionOutput.hpp"
#include "MotionSolverRegistry.hpp"
#include "PartQuality.hpp"
#include "PartRigidBodyMotion.hpp"
#include "PatchBoundaryConditions.hpp"
#include "PeakMemory.hpp"
#include "PetscSupport.hpp"
#include "RunSummary.hpp"
#include "RunTimes.hpp"
#include "ThreadCount.hpp"
#include "TimeFolderWriter.hpp"
#include "WriteSchedule.hpp"

#include "NumberText.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>

namespace rbm::app {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

bool isFinite(const Vector3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The largest of every rank's status: all ranks go on only when every rank can.
int agreed(int status, MPI_Comm communicator)
{
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &status, 1, MPI_INT, MPI_MAX, communicator));
    return status;
}

bool onEveryRank(bool mine, MPI_Comm communicator)
{
    int value = mine ? 1 : 0;
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_INT, MPI_LAND, communicator));
    return value != 0;
}

// One rank's processor folder as it reads it: everything before the first collective step.
struct ProcessorCase {
    fs::path folder;  // <case>/processor<rank>
    RunTimes times;
    io::ProcessorMesh processor;
    io::PointVectorField field;
    std::unique_ptr<motion::PatchBoundaryConditions> conditions;
    motion::BoundaryDescription boundary;
    std::vector<std::uint8_t> prescribedPatches;
    std::vector<Vector3> displacement;  // the start time's (the warm start), then each step's
    bool warmStart = false;
    motion::MotionSolverSelection solver;
};

ProcessorCase readProcessorCase(const fs::path& caseDirectory, int rank)
{
    ProcessorCase local;
    local.folder = caseDirectory / ("processor" + std::to_string(rank));
    local.times = readRunTimes(caseDirectory, local.folder);
    const io::Dictionary dynamicMeshDict = io::Dictionary::readFile(caseDirectory / "constant" / "dynamicMeshDict");
    local.solver = motion::selectedMotionSolver(dynamicMeshDict);
    if (local.solver.name != "rigidBodyMotionSolver" && local.solver.name != "rbmMotionSolver")
        throw InputError(local.solver.file, local.solver.line,
                         "motionSolver " + local.solver.name +
                             ": a decomposed case moves with rigidBodyMotionSolver (or rbmMotionSolver) only");
    local.processor = io::readProcessorMesh(caseDirectory, rank);
    const PolyMesh& mesh = local.processor.mesh;
    TopologyCheckOptions checks;
    checks.checkCellVolumes = false;
    checks.maxMessages = 5;
    if (const auto problems = checkPolyMeshOrdering(mesh, checks); !problems.empty()) {
        std::string text = "the mesh breaks OpenFOAM's polyMesh rules (files faces, owner, neighbour):";
        for (const std::string& problem : problems) text += "\n  " + problem;
        throw InputError((local.folder / "constant" / "polyMesh").string(), 0, text);
    }
    const fs::path fieldFile = io::resolveMaybeCompressed(local.times.boundaryFieldFile);
    local.field = io::readPointVectorField(fieldFile, mesh);
    local.conditions = std::make_unique<motion::PatchBoundaryConditions>(
        mesh, &local.field.dictionary, caseDirectory, motion::decomposedPointPatchDisplacements());
    local.boundary = local.conditions->describe();
    local.prescribedPatches.assign(mesh.patches.size(), 0);
    for (std::size_t p = 0; p < local.boundary.size(); ++p)
        local.prescribedPatches[p] = local.boundary[p].nodeClass == motion::BoundaryNodeClass::prescribed;
    motion::checkPartIsSolvable(local.solver.coefficients, mesh, local.boundary);

    // The start folder's displacement: the mesh at the start and the first solve's warm start.
    local.displacement.assign(mesh.points.size(), Vector3{});
    const fs::path startField = local.folder / local.times.startTimeName / "pointDisplacement";
    if (io::existsMaybeCompressed(startField)) {
        const fs::path startFile = io::resolveMaybeCompressed(startField);
        local.displacement = startFile == fieldFile ? local.field.internalField
                                                    : io::readPointVectorField(startFile, mesh).internalField;
        local.warmStart = std::any_of(local.displacement.begin(), local.displacement.end(),
                                      [](const Vector3& u) { return u != Vector3{}; });
    }
    return local;
}

class DecomposedRun {
public:
    DecomposedRun(const MoveMeshOptions& options, MPI_Comm communicator, std::ostream& out, std::ostream& err)
        : options_(options), communicator_(communicator), out_(out), err_(err)
    {
        RBM_CHECK_PETSC(MPI_Comm_rank(communicator_, &rank_));
        RBM_CHECK_PETSC(MPI_Comm_size(communicator_, &ranks_));
    }

    int run();

private:
    // Setup's local phase: the lock, the processor folder count, every rank's files. Agreed.
    int readEverything();
    // Every processor folder's start time the same (exit status 2 otherwise). Collective.
    int checkSameStartTime();
    // The summary's memory line: the largest peak resident memory of a rank, and the sum.
    void printPeakMemory();
    void printHeader();
    bool runStep(int step, int& exitStatus);
    // The two-phase write of `name` on every rank; false (with the message said) when some
    // rank could not stage or commit it.
    bool writeOnEveryRank(const std::string& name, const std::vector<Vector3>& points);
    // The local part of a step before the solve: the boundary conditions at `time`.
    int evaluateConditions(double time, const std::string& name);
    StepQuality quality(const std::vector<Vector3>& points);
    std::vector<Vector3> movedPoints() const;
    // A message of this rank's, prefixed with its processor folder.
    std::ostream& rankError() { return err_ << "rbmMoveMesh: [processor" << rank_ << "] "; }
    bool isRankZero() const { return rank_ == 0; }
    fs::path jsonLogFile() const
    {
        return options_.caseDirectory / "postProcessing" / "rbmMoveMesh" / local_.times.startTimeName / "log.jsonl";
    }

    MoveMeshOptions options_;
    MPI_Comm communicator_;
    std::ostream& out_;
    std::ostream& err_;
    int rank_ = 0;
    int ranks_ = 1;
    std::optional<io::CaseLock> lock_;
    ProcessorCase local_;
    std::unique_ptr<motion::PartRigidBodyMotion> motion_;
    std::unique_ptr<motion::PartQuality> quality_;   // the whole mesh's figures, on every rank
    std::unique_ptr<WriteSchedule> schedule_;
    io::JsonLinesWriter jsonLog_;
    RunSummary summary_;
    int timePrecision_ = 6;
    int stepsLogged_ = 0;
};

int DecomposedRun::readEverything()
{
    int status = exitSuccess;
    try {
        if (isRankZero()) {
            lock_ = io::CaseLock::acquire(options_.caseDirectory);
            if (lock_->heldByAnother()) throw InputError(options_.caseDirectory.string(), 0, lock_->message());
        }
        const int folders = io::countProcessorFolders(options_.caseDirectory);
        if (folders != ranks_)
            throw InputError(options_.caseDirectory.string(), 0,
                             "the case is decomposed into " + std::to_string(folders) + " processor folders but " +
                                 std::to_string(ranks_) + " MPI ranks run: start mpirun -np " +
                                 std::to_string(folders));
        local_ = readProcessorCase(options_.caseDirectory, rank_);
    } catch (const InputError& error) {
        rankError() << error.what() << '\n';
        status = exitBadInput;
    } catch (const std::exception& error) {
        rankError() << error.what() << '\n';
        status = exitRunFailed;
    }
    status = agreed(status, communicator_);
    if (status == exitSuccess) status = checkSameStartTime();
    if (status != exitSuccess && isRankZero()) err_ << "rbmMoveMesh: nothing was written.\n";
    return status;
}

int DecomposedRun::checkSameStartTime()
{
    // startFrom latestTime picks each processor folder's own latest time: an interrupted
    // earlier run may have left them apart.
    double range[2] = {local_.times.startTime, -local_.times.startTime};
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_DOUBLE, MPI_MAX, communicator_));
    if (range[0] == -range[1]) return exitSuccess;
    if (isRankZero())
        err_ << "rbmMoveMesh: " << options_.caseDirectory.string() << ": the processor folders start at different times ("
             << general(-range[1]) << " to " << general(range[0])
             << "): remove the later times from the folders that have them, or give startTime\n";
    return exitBadInput;
}

void DecomposedRun::printPeakMemory()
{
    struct {
        double mebibytes;
        int rank;
    } largest{peakResidentMebibytes(), rank_};
    double total = largest.mebibytes;
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE_INT, MPI_MAXLOC, communicator_));
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, communicator_));
    if (isRankZero())
        out_ << "  peak memory            " << fixed(largest.mebibytes, 0) << " MiB on the largest rank (processor"
             << largest.rank << "), " << fixed(total, 0) << " MiB over " << ranks_ << " ranks\n";
}

void DecomposedRun::printHeader()
{
    long long cells = local_.processor.mesh.cellCount();
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &cells, 1, MPI_LONG_LONG, MPI_SUM, communicator_));
    if (!isRankZero()) return;
    const io::ControlDict& control = local_.times.control;
    out_ << versionText() << "\n"
         << "Case          : " << options_.caseDirectory.string() << "\n"
         << "Decomposed    : " << ranks_ << " processor folders, one per MPI rank; " << motion_->part().globalNodeCount()
         << " points, " << cells << " cells in all (no rank holds the whole mesh)\n"
         << "Motion solver : rigidBodyMotionSolver: " << motion_->describe() << " (constant/dynamicMeshDict)\n"
         << "Boundary      : processor*/" << local_.times.boundaryFieldFile.parent_path().filename().string()
         << "/pointDisplacement\n"
         << "Threads       : " << describeThreadCount() << "\n";
    if (local_.warmStart) out_ << "Warm start    : processor*/" << local_.times.startTimeName << "/pointDisplacement\n";
    out_ << "Time          : from " << local_.times.startTimeName << " to " << control.timeName(control.endTime)
         << ", deltaT " << general(control.deltaT) << ": " << local_.times.stepCount
         << (local_.times.stepCount == 1 ? " step" : " steps") << "\n"
         << "Write         : processor*/<time> (both phases on every rank), writeInterval "
         << general(control.writeInterval) << ", " << (control.binary ? "binary" : "ascii") << ", precision "
         << control.writePrecision << "; no VTK (ParaView reads the processor folders)"
         << (options_.writeInvalid ? "; -writeInvalid" : "") << "\n"
         << "Log           : postProcessing/rbmMoveMesh/" << local_.times.startTimeName << "/log.jsonl\n\n";
    out_.flush();
}

std::vector<Vector3> DecomposedRun::movedPoints() const
{
    std::vector<Vector3> points = local_.processor.mesh.points;
    for (std::size_t p = 0; p < points.size(); ++p) points[p] += local_.displacement[p];
    return points;
}

StepQuality DecomposedRun::quality(const std::vector<Vector3>& points)
{
    const StepQuality whole = quality_->evaluateStep(points);
    quality_->releaseWorkspaces();
    return whole;
}

int DecomposedRun::evaluateConditions(double time, const std::string& name)
{
    int status = exitSuccess;
    try {
        local_.conditions->update(time, local_.processor.mesh.points, local_.displacement);
        for (std::size_t p = 0; p < local_.boundary.size(); ++p)
            for (Label point : local_.boundary[p].meshPoints)
                if (!isFinite(local_.displacement[point]))
                    throw InputError(local_.times.boundaryFieldFile.string(), 0,
                                     "the boundary condition of patch " + local_.processor.mesh.patches[p].name +
                                         " gives a NaN or infinite displacement at time " + general(time) +
                                         "; expected finite numbers");
    } catch (const InputError& error) {
        rankError() << "time " << name << ": " << error.what() << '\n';
        status = exitBadInput;
    } catch (const std::exception& error) {
        rankError() << "time " << name << ": " << error.what() << '\n';
        status = exitRunFailed;
    }
    return agreed(status, communicator_);
}

bool DecomposedRun::writeOnEveryRank(const std::string& name, const std::vector<Vector3>& points)
{
    std::optional<io::TimeFolderWriter> folder;
    bool staged = true;
    try {
        folder.emplace(local_.folder, name);
        stageMeshMotion(*folder, name, local_.processor.mesh, points, local_.displacement, local_.field,
                        local_.prescribedPatches, local_.times.control);
    } catch (const std::exception& error) {
        rankError() << "time " << name << ": " << error.what() << '\n';
        staged = false;
    }
    if (!onEveryRank(staged, communicator_)) {
        folder.reset();  // its staging folder removed: no processor folder gets the time
        if (isRankZero()) err_ << "rbmMoveMesh: time " << name << " was not written on any processor.\n";
        return false;
    }
    bool committed = true;
    try {
        folder->commit();
    } catch (const std::exception& error) {
        rankError() << "time " << name << ": " << error.what() << '\n';
        committed = false;
    }
    if (!onEveryRank(committed, communicator_)) {
        if (isRankZero())
            err_ << "rbmMoveMesh: time " << name
                 << " was staged on every processor but not committed on all (see above): remove processor*/" << name
                 << " before reconstructPar.\n";
        return false;
    }
    return true;
}

bool DecomposedRun::runStep(int step, int& exitStatus)
{
    const Clock::time_point started = Clock::now();
    const RunTimes& times = local_.times;
    const double time = times.stepTime(step);
    const int precision = io::adjustedTimePrecision(time, times.control.deltaT, times.control.timeFormat, timePrecision_);
    if (precision > timePrecision_) timePrecision_ = precision;
    const std::string name = io::timeName(time, times.control.timeFormat, timePrecision_);
    if (const int status = evaluateConditions(time, name); status != exitSuccess) {
        exitStatus = status;
        if (isRankZero()) err_ << "rbmMoveMesh: nothing was written for time " << name << ".\n";
        return false;
    }
    const motion::MotionSolveReport solve = motion_->solve(local_.displacement);
    if (isRankZero())
        for (const std::string& warning : solve.warnings)
            err_ << "rbmMoveMesh: warning: time " << name << ": " << warning << '\n';
    const bool finite =
        onEveryRank(std::all_of(local_.displacement.begin(), local_.displacement.end(), isFinite), communicator_) &&
        std::isfinite(solve.residual);
    const std::vector<Vector3> points = movedPoints();

    io::StepLogRecord record;
    record.step = step;
    record.time = time;
    record.timeName = name;
    record.subSteps = solve.subStepCount;
    record.iterations = solve.iterations;
    record.residual = solve.residual;
    record.energy = solve.energy;
    record.converged = solve.converged && finite;
    record.reason = finite ? solve.reason : solve.reason + "; NaN or infinite displacements";
    if (finite) {
        const StepQuality figures = quality(points);
        record.worstQuality = figures.worstCellQuality;
        record.maxNonOrthogonality = figures.maxNonOrthogonality;
        record.maxSkewness = figures.maxSkewness;
        record.invertedCells = figures.invertedCellCount;
    }
    const bool valid = record.converged && record.invertedCells == 0;
    // cpuTime and clockTime schedules differ between ranks: rank 0 decides for all.
    int scheduled = schedule_->isWriteTime(step, time) ? 1 : 0;
    RBM_CHECK_PETSC(MPI_Bcast(&scheduled, 1, MPI_INT, 0, communicator_));
    if (valid ? scheduled != 0 : options_.writeInvalid && finite) {
        if (!valid && isRankZero())
            err_ << "\n*** WARNING (-writeInvalid): writing time " << name << " although it is not valid (" << record.reason
                 << ", " << record.invertedCells << " inverted cells): this mesh is NOT valid for a flow solver ***\n\n";
        if (!writeOnEveryRank(name, points)) {
            exitStatus = exitRunFailed;
            return false;
        }
        record.written = true;
    }
    record.wallSeconds = std::chrono::duration<double>(Clock::now() - started).count();
    if (isRankZero()) {
        out_ << io::formatStepLogLine(record, 8) << '\n';
        out_.flush();
        if (jsonLog_.isOpen()) jsonLog_.append(io::stepLogJson(record));
    }
    summary_.add(record, step, finite);
    ++stepsLogged_;
    if (valid) return true;
    ++summary_.invalidSteps;
    exitStatus = exitRunFailed;
    if (options_.writeInvalid && finite) return true;
    if (isRankZero())
        err_ << "rbmMoveMesh: time " << name << ": "
             << (record.invertedCells > 0 ? std::to_string(record.invertedCells) + " inverted cells"
                                          : "the motion solver did not converge (" + record.reason + ")")
             << ". Nothing was written for time " << name
             << "; earlier times stay as written. -writeInvalid writes the step anyway to look at it.\n";
    return false;
}

int DecomposedRun::run()
{
    const Clock::time_point runStart = Clock::now();
    if (const int status = readEverything(); status != exitSuccess) return status;
    // The collective set-up: a failure here cannot be agreed on (the other ranks wait in a
    // collective call), so it ends every rank.
    try {
        motion_ = std::make_unique<motion::PartRigidBodyMotion>(communicator_, local_.processor.mesh,
                                                                 local_.processor.pointProcAddressing, local_.boundary,
                                                                 local_.solver.coefficients);
        quality_ = std::make_unique<motion::PartQuality>(local_.processor.mesh, communicator_);
        for (const std::string& name : io::removeStaleStagingFolders(local_.folder))
            rankError() << "removed " << name << ", the unfinished time folder of an interrupted run\n";
        if (isRankZero()) jsonLog_ = io::JsonLinesWriter(jsonLogFile(), true);
        printHeader();
        if (isRankZero())
            for (const std::string& warning : motion_->warnings()) err_ << "rbmMoveMesh: warning: " << warning << '\n';
        const StepQuality initial = quality(movedPoints());
        if (isRankZero())
            out_ << "Initial mesh (time " << local_.times.startTimeName << "): worst quality "
                 << fixed(initial.worstCellQuality, 4) << ", max non-orthogonality "
                 << fixed(initial.maxNonOrthogonality, 2) << ", max skewness " << fixed(initial.maxSkewness, 3)
                 << ", inverted " << initial.invertedCellCount << "\n\n";
        schedule_ = std::make_unique<WriteSchedule>(local_.times.control, local_.times.startTime);
        int exitStatus = exitSuccess;
        for (int step = 1; step <= local_.times.stepCount; ++step)
            if (!runStep(step, exitStatus)) break;
        const double wallSeconds = std::chrono::duration<double>(Clock::now() - runStart).count();
        if (isRankZero()) summary_.print(out_, stepsLogged_, local_.times.stepCount, wallSeconds);
        printPeakMemory();
        return agreed(exitStatus, communicator_);
    } catch (const std::exception& error) {
        rankError() << error.what() << "\nrbmMoveMesh: stopping every rank (MPI_Abort).\n";
        err_.flush();
        MPI_Abort(communicator_, exitRunFailed);
        return exitRunFailed;
    }
}

} // namespace

bool isDecomposedRun(const MoveMeshOptions& options)
{
    if (!options.parallel) return false;
    std::error_code error;
    return fs::is_directory(options.caseDirectory / "processor0", error);
}

int runDecomposedMoveMesh(const MoveMeshOptions& options, MPI_Comm communicator, std::ostream& out, std::ostream& err)
{
    DecomposedRun run(options, communicator, out, err);
    return run.run();
}

} // namespace rbm::app
