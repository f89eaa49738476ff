// C++20 implementation of the C++17 host interface (HostMotionSolver.hpp).
#include "HostMotionSolver.hpp"

#include "BoundaryDescription.hpp"
#include "FoamDictionary.hpp"
#include "InputError.hpp"
#include "PetscSupport.hpp"
#include "PolyMesh.hpp"
#include "RigidBodyMotionSolver.hpp"
#include "RunLog.hpp"
#include "StepAssessment.hpp"
#include "ThreadCount.hpp"

#include <chrono>
#include <mutex>

namespace rbm::host {

using motion::PetscSession;

namespace {

// One PETSc session for every solver of the process: PETSc is initialised by the first
// solver (after the host initialised MPI, if it does) and finalised with the last one, while
// the host's MPI is still up (OpenFOAM finalises MPI after its meshes are destroyed).
std::shared_ptr<PetscSession> sharedPetscSession()
{
    static std::mutex mutex;
    static std::weak_ptr<PetscSession> current;
    const std::lock_guard<std::mutex> lock(mutex);
    std::shared_ptr<PetscSession> session = current.lock();
    if (!session) {
        session = std::make_shared<PetscSession>();
        current = session;
    }
    return session;
}

PolyMesh toPolyMesh(const HostMesh& host)
{
    if (host.points.size() % 3 != 0) throw std::invalid_argument("HostMesh: points is not a multiple of 3 long");
    if (host.faceOffsets.empty() || host.faceOffsets.size() != host.owner.size() + 1)
        throw std::invalid_argument("HostMesh: faceOffsets needs one entry per face and one more");
    PolyMesh mesh;
    mesh.points.resize(host.points.size() / 3);
    for (std::size_t p = 0; p < mesh.points.size(); ++p)
        mesh.points[p] = {host.points[3 * p], host.points[3 * p + 1], host.points[3 * p + 2]};
    mesh.faceOffsets.assign(host.faceOffsets.begin(), host.faceOffsets.end());
    mesh.facePoints.assign(host.faceVertices.begin(), host.faceVertices.end());
    mesh.owner.assign(host.owner.begin(), host.owner.end());
    mesh.neighbour.assign(host.neighbour.begin(), host.neighbour.end());
    for (const HostPatch& patch : host.patches)
        mesh.patches.push_back({patch.name, patch.type, patch.groups, patch.startFace, patch.faceCount, patch.entries});
    return mesh;
}

motion::BoundaryDescription toBoundaryDescription(const PolyMesh& mesh, const std::vector<HostPatchBoundary>& boundary)
{
    if (boundary.size() != mesh.patches.size())
        throw std::invalid_argument("HostMotionSolver: " + std::to_string(boundary.size()) +
                                    " patch boundaries given for " + std::to_string(mesh.patches.size()) + " patches");
    motion::BoundaryDescription description(boundary.size());
    for (std::size_t p = 0; p < boundary.size(); ++p) {
        const HostPatchBoundary& host = boundary[p];
        motion::BoundaryPatchDescription& patch = description[p];
        patch.meshPoints = patchMeshPoints(mesh, static_cast<Label>(p));
        switch (host.nodeClass) {
        case HostNodeClass::prescribed: patch.nodeClass = motion::BoundaryNodeClass::prescribed; break;
        case HostNodeClass::free: patch.nodeClass = motion::BoundaryNodeClass::free; break;
        case HostNodeClass::ignored: patch.nodeClass = motion::BoundaryNodeClass::ignored; break;
        case HostNodeClass::coupled: patch.nodeClass = motion::BoundaryNodeClass::coupled; break;
        case HostNodeClass::sliding:
            patch.nodeClass = motion::BoundaryNodeClass::sliding;
            patch.mirror = host.mirror;
            if (host.slidingNormals.size() != 3 * patch.meshPoints.size())
                throw std::invalid_argument("HostMotionSolver: sliding patch " + mesh.patches[p].name + " has " +
                                            std::to_string(host.slidingNormals.size()) + " normal components for " +
                                            std::to_string(patch.meshPoints.size()) + " points");
            patch.slidingNormals.resize(patch.meshPoints.size());
            for (std::size_t k = 0; k < patch.meshPoints.size(); ++k)
            {
                const Vector3 n{host.slidingNormals[3 * k], host.slidingNormals[3 * k + 1], host.slidingNormals[3 * k + 2]};
                const double length = norm(n);
                patch.slidingNormals[k] = length > 0.0 ? n / length : n;
            }
            break;
        }
    }
    return description;
}

} // namespace

struct HostMotionSolver::Impl {
    std::shared_ptr<PetscSession> petsc = sharedPetscSession();
    PolyMesh mesh;
    std::unique_ptr<motion::RigidBodyMotionSolver> solver;
    std::unique_ptr<motion::StepAssessor> assessor;
};

HostMotionSolver::HostMotionSolver(const HostMesh& mesh, const std::string& coefficientsText,
                                   const std::string& coefficientsFile, const std::vector<HostPatchBoundary>& boundary,
                                   const std::string& caseDirectory)
    : impl_(std::make_unique<Impl>())
{
    applyHostThreadCountPolicy();
    try {
        impl_->mesh = toPolyMesh(mesh);
        const io::Dictionary coefficients = io::Dictionary::parseText(coefficientsText, coefficientsFile);
        impl_->solver = std::make_unique<motion::RigidBodyMotionSolver>(
            impl_->mesh, coefficients, toBoundaryDescription(impl_->mesh, boundary), caseDirectory);
        impl_->assessor = std::make_unique<motion::StepAssessor>(impl_->mesh);
    } catch (const InputError& error) {
        throw HostInputError(error.file(), error.line(), error.message());
    }
}

HostMotionSolver::~HostMotionSolver()
{
    // PETSc objects before the session that may finalise PETSc.
    if (impl_) impl_->solver.reset();
}

std::size_t HostMotionSolver::pointCount() const { return impl_->mesh.points.size(); }
int HostMotionSolver::dimension() const { return impl_->solver->dimension(); }

HostStepReport HostMotionSolver::solve(int step, double time, const std::string& timeName, double* displacement,
                                       std::size_t valueCount)
{
    const auto started = std::chrono::steady_clock::now();
    motion::RigidBodyMotionSolver& solver = *impl_->solver;
    std::vector<Vector3>& u = solver.pointDisplacement();
    if (valueCount != 3 * u.size())
        throw std::invalid_argument("HostMotionSolver::solve: " + std::to_string(valueCount) + " values for " +
                                    std::to_string(u.size()) + " points (3 per point)");
    // Only the prescribed points' values matter to solve(); the others are its result.
    for (std::size_t p = 0; p < u.size(); ++p) u[p] = {displacement[3 * p], displacement[3 * p + 1], displacement[3 * p + 2]};
    motion::MotionSolveReport solve;
    try {
        solve = solver.solve();
    } catch (const InputError& error) {
        throw HostInputError(error.file(), error.line(), error.message());
    }
    for (std::size_t p = 0; p < u.size(); ++p) {
        displacement[3 * p] = u[p].x;
        displacement[3 * p + 1] = u[p].y;
        displacement[3 * p + 2] = u[p].z;
    }

    io::StepLogRecord record;
    record.step = step;
    record.time = time;
    record.timeName = timeName;
    const motion::StepVerdict verdict = impl_->assessor->assess(solve, u, solver.curPoints(), record);
    record.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    HostStepReport report;
    report.subSteps = record.subSteps;
    report.iterations = record.iterations;
    report.residual = record.residual;
    report.energy = record.energy;
    report.converged = record.converged;
    report.reason = record.reason;
    report.invertedCells = record.invertedCells;
    report.worstQuality = record.worstQuality;
    report.maxNonOrthogonality = record.maxNonOrthogonality;
    report.maxSkewness = record.maxSkewness;
    report.wallSeconds = record.wallSeconds;
    report.warnings = solve.warnings;
    report.finite = verdict.finite;
    report.valid = verdict.valid;
    report.logLine = "rigidBodyMotionSolver: " + io::formatStepFigures(record);
    if (!verdict.valid)
        report.problem = motion::invalidStepCause(verdict, record) + ". " +
                         motion::invalidStepAdvice(verdict, record,
                                                   "writeInvalid yes; in rigidBodyMotionSolverCoeffs goes on anyway",
                                                   solver.invertedStepAdvice());
    return report;
}

} // namespace rbm::host
