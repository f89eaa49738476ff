// C++20 implementation of the C++17 host interface for one rank's part (HostPartMotionSolver.hpp).
#include "HostPartMotionSolver.hpp"

#include "FoamDictionary.hpp"
#include "HostMeshConversion.hpp"
#include "HostPetscSession.hpp"
#include "HostStepReporting.hpp"
#include "InputError.hpp"
#include "PartQuality.hpp"
#include "PartRigidBodyMotion.hpp"
#include "PetscSupport.hpp"
#include "RigidBodyMotionOptions.hpp"
#include "RunLog.hpp"
#include "StepAssessment.hpp"
#include "ThreadCount.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <utility>

namespace rbm::host {

namespace {

// The host initialised MPI on MPI_COMM_WORLD and numbers its processors by their rank in it
// (OpenFOAM v1912 and 13 alike); PETSc runs on it too (PETSC_COMM_WORLD's default).
MPI_Comm hostCommunicator() { return MPI_COMM_WORLD; }

bool isFinite(const Vector3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A failure of one rank's local set-up (before any collective step), to be agreed on.
struct LocalFailure {
    bool failed = false;
    bool inputError = false;  // bad input (HostInputError) rather than another failure
    std::string file;
    int line = 0;
    std::string message;
};

// Every rank learns of the lowest failing rank's failure and throws it, so that no rank goes
// on into a collective call that the failed one never reaches.
void throwIfAnyRankFailed(const LocalFailure& mine, MPI_Comm communicator)
{
    int rank = 0;
    RBM_CHECK_PETSC(MPI_Comm_rank(communicator, &rank));
    int failing = mine.failed ? rank : INT_MAX;
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &failing, 1, MPI_INT, MPI_MIN, communicator));
    if (failing == INT_MAX) return;
    int header[4] = {mine.inputError ? 1 : 0, mine.line, static_cast<int>(mine.file.size()),
                     static_cast<int>(mine.message.size())};
    RBM_CHECK_PETSC(MPI_Bcast(header, 4, MPI_INT, failing, communicator));
    std::string file = rank == failing ? mine.file : std::string(static_cast<std::size_t>(header[2]), ' ');
    std::string message = rank == failing ? mine.message : std::string(static_cast<std::size_t>(header[3]), ' ');
    RBM_CHECK_PETSC(MPI_Bcast(file.data(), header[2], MPI_CHAR, failing, communicator));
    RBM_CHECK_PETSC(MPI_Bcast(message.data(), header[3], MPI_CHAR, failing, communicator));
    message = "processor " + std::to_string(failing) + ": " + message;
    if (header[0] != 0) throw HostInputError(file, header[1], message);
    throw std::runtime_error(message);
}

// What was not finite on any rank (empty when every displacement was finite on every rank).
std::string nonFiniteOnAnyRank(const std::vector<Vector3>& displacement, MPI_Comm communicator)
{
    long long counts[2] = {std::count_if(displacement.begin(), displacement.end(),
                                         [](const Vector3& u) { return !isFinite(u); }),
                           static_cast<long long>(displacement.size())};
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG_LONG, MPI_SUM, communicator));
    if (counts[0] == 0) return {};
    return "NaN or infinite displacement at " + std::to_string(counts[0]) + " of " + std::to_string(counts[1]) +
           " processor points";
}

} // namespace

struct HostPartMotionSolver::Impl {
    std::shared_ptr<motion::PetscSession> petsc = sharedPetscSession();
    // What the part solver refers to for its lifetime.
    PolyMesh mesh;
    std::vector<Label> globalIds;
    motion::BoundaryDescription boundary;
    io::Dictionary coefficients;
    std::unique_ptr<motion::PartRigidBodyMotion> motion;
    std::unique_ptr<motion::PartQuality> quality;
    std::vector<Vector3> displacement;  // per local point
    std::vector<Vector3> points;        // points0 + displacement, for the quality
    bool setUpWarningsGiven = false;    // the part solver's warnings() go with the first report
};

bool HostPartMotionSolver::solvesVariant(const std::string& coefficientsText, const std::string& coefficientsFile)
{
    try {
        const motion::RigidBodyMotionOptions options =
            motion::RigidBodyMotionOptions::read(io::Dictionary::parseText(coefficientsText, coefficientsFile));
        return motion::partsSolve(options);
    } catch (const InputError& error) {
        throw HostInputError(error.file(), error.line(), error.message());
    }
}

HostPartMotionSolver::HostPartMotionSolver(const HostMesh& localMesh, const std::vector<int>& globalPointLabels,
                                           const std::string& coefficientsText, const std::string& coefficientsFile,
                                           const std::vector<HostPatchBoundary>& boundary)
    : impl_(std::make_unique<Impl>())
{
    applyHostThreadCountPolicy();
    Impl& impl = *impl_;
    LocalFailure failure;
    try {
        impl.mesh = toPolyMesh(localMesh);
        if (globalPointLabels.size() != impl.mesh.points.size())
            throw std::invalid_argument("HostPartMotionSolver: " + std::to_string(globalPointLabels.size()) +
                                        " global point labels for " + std::to_string(impl.mesh.points.size()) +
                                        " local points");
        impl.globalIds.assign(globalPointLabels.begin(), globalPointLabels.end());
        impl.boundary = toBoundaryDescription(impl.mesh, boundary, "HostPartMotionSolver");
        impl.coefficients = io::Dictionary::parseText(coefficientsText, coefficientsFile);
        motion::checkPartIsSolvable(impl.coefficients, impl.mesh, impl.boundary);
    } catch (const InputError& error) {
        failure = {true, true, error.file(), error.line(), error.message()};
    } catch (const std::exception& error) {
        failure = {true, false, coefficientsFile, 0, error.what()};
    }
    throwIfAnyRankFailed(failure, hostCommunicator());

    // Collective from here: every rank has its input checked.
    try {
        impl.motion = std::make_unique<motion::PartRigidBodyMotion>(hostCommunicator(), impl.mesh, impl.globalIds,
                                                                    impl.boundary, impl.coefficients);
    } catch (const InputError& error) {
        throw HostInputError(error.file(), error.line(), error.message());
    }
    impl.quality = std::make_unique<motion::PartQuality>(impl.mesh, hostCommunicator());
    impl.displacement.assign(impl.mesh.points.size(), Vector3{});
}

HostPartMotionSolver::~HostPartMotionSolver()
{
    // PETSc objects before the session that may finalise PETSc.
    if (impl_) impl_->motion.reset();
}

std::size_t HostPartMotionSolver::pointCount() const { return impl_->mesh.points.size(); }
long long HostPartMotionSolver::globalPointCount() const { return impl_->motion->part().globalNodeCount(); }

HostStepReport HostPartMotionSolver::solve(int step, double time, const std::string& timeName, double* displacement,
                                           std::size_t valueCount)
{
    const auto started = std::chrono::steady_clock::now();
    Impl& impl = *impl_;
    std::vector<Vector3>& u = impl.displacement;
    const motion::MotionSolveReport solve = solveOnHostArray("HostPartMotionSolver", displacement, valueCount, u,
                                                             [&impl, &u] { return impl.motion->solve(u); });
    io::StepLogRecord record = stepRecord(step, time, timeName);
    // Every rank takes the same branch: the finiteness is agreed, and the quality is collective.
    motion::StepVerdict verdict = motion::recordSolve(solve, nonFiniteOnAnyRank(u, hostCommunicator()), record);
    if (verdict.finite) {
        impl.points.resize(u.size());
        for (std::size_t p = 0; p < u.size(); ++p) impl.points[p] = impl.mesh.points[p] + u[p];
        const StepQuality quality = impl.quality->evaluateStep(impl.points);
        impl.quality->releaseWorkspaces();
        motion::recordQuality(&quality, verdict, record);
    } else {
        motion::recordQuality(nullptr, verdict, record);
    }
    record.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::vector<std::string> warnings = solve.warnings;
    if (!impl.setUpWarningsGiven) {
        const std::vector<std::string>& setUp = impl.motion->warnings();
        warnings.insert(warnings.begin(), setUp.begin(), setUp.end());
        impl.setUpWarningsGiven = true;
    }
    // The general advice (more sub-steps, ...) names remedies the part solver does not have.
    return hostStepReport(record, verdict, std::move(warnings),
                          "The solve on the processors' parts of a decomposed mesh takes each step whole: it has "
                          "neither sub-steps nor their halving nor the untangling of inverted cells, which the "
                          "whole-mesh solver has.");
}

} // namespace rbm::host
