#include "PetscSupport.hpp"

#include "BlockRowLayout.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rbm::motion {

void checkPetsc(PetscErrorCode code, std::string_view call)
{
    if (code == 0) return;
    const char* generic = nullptr;
    char* specific = nullptr;
    std::string message(call);
    if (PetscErrorMessage(code, &generic, &specific) == 0) {
        message += ": ";
        if (specific && specific[0] != '\0') message += specific;
        else if (generic) message += generic;
        else message += "unknown error";
    }
    message += " (PETSc error " + std::to_string(static_cast<int>(code)) + ")";
    throw PetscException(code, message);
}

PetscErrorCode petscErrorFromException(const char* function, const std::exception& error)
{
    return PetscError(PETSC_COMM_SELF, __LINE__, function, __FILE__, PETSC_ERR_LIB, PETSC_ERROR_INITIAL, "%s",
                      error.what());
}

PetscSession::PetscSession() : PetscSession(nullptr, nullptr) {}

namespace {

// A program started without mpirun is an MPI "singleton". Open MPI then starts its runtime
// daemon and probes the network interfaces, most of a one-process start (docs/parallel.md,
// "Serial start-up"), although one process needs neither. These settings skip both; a value already in the
// environment wins, and under mpirun (which sets OMPI_COMM_WORLD_SIZE or PMIX_RANK)
// nothing is changed. Other MPI implementations ignore OMPI_ variables.
void preferFastSingletonStart()
{
    if (std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK")) return;
    setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
    setenv("OMPI_MCA_pml", "ob1", 0);
    setenv("OMPI_MCA_btl", "self,vader", 0);
    // Isolated singletons all use job family 0, so concurrent ones (ctest -j) race on
    // creating and removing the same session folder /tmp/ompi.<host>.<uid>/jf.0/: about one
    // start in 80 failed with "A call to mkdir was unable to create the desired directory".
    // A single process needs no session folder.
    setenv("OMPI_MCA_orte_create_session_dirs", "0", 0);
}

// OpenBLAS (Debian's libopenblas0, pthread build) starts one thread per core. The direct
// factorisations' fronts are small (at most ~1000 rows on the 40k-node airfoil), so a second
// BLAS thread gains nothing on a quiet machine, while on a shared one its spinning costs CPU
// and wall time (docs/motionSolver.md, "Direct solver"; docs/rbmMoveMesh.md, "Threads").
// So one thread, unless the environment asks otherwise (OPENBLAS_NUM_THREADS,
// GOTO_NUM_THREADS or OMP_NUM_THREADS, which OpenBLAS reads itself). Looked up at run time:
// with another BLAS there is nothing to set.
void preferSingleThreadedBlas()
{
    for (const char* name : {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS"})
        if (std::getenv(name)) return;
    using SetThreads = void (*)(int);
    if (void* symbol = dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))
        reinterpret_cast<SetThreads>(symbol)(1);
}

} // namespace

PetscSession::PetscSession(int* argc, char*** argv)
{
    if (!isInitialized()) {
        preferFastSingletonStart();
        preferSingleThreadedBlas();
        RBM_CHECK_PETSC(PetscInitialize(argc, argv, nullptr, nullptr));
        ownsInitialization_ = true;
    }
    RBM_CHECK_PETSC(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
}

PetscSession::~PetscSession()
{
    (void)PetscPopErrorHandler();
    if (ownsInitialization_) (void)PetscFinalize();
}

bool PetscSession::isInitialized()
{
    PetscBool initialized = PETSC_FALSE;
    if (PetscInitialized(&initialized) != 0) return false;
    return initialized == PETSC_TRUE;
}

namespace {

// How many living InheritedOptions hold each copied option name.
std::map<std::string, int>& copiedOptionHolders()
{
    static std::map<std::string, int> holders;
    return holders;
}

bool isSolverOptionStem(std::string_view name)
{
    for (std::string_view stem : {"ksp_", "pc_", "snes_", "mat_", "mg_", "sub_"})
        if (name.substr(0, stem.size()) == stem) return true;
    return false;
}

bool isOptionName(const std::string& token)
{
    return token.size() > 1 && token[0] == '-' && !(std::isdigit(static_cast<unsigned char>(token[1])) || token[1] == '.');
}

} // namespace

InheritedOptions::InheritedOptions(std::string_view solverName) : prefix_("rbm_" + std::string(solverName) + "_")
{
    char* all = nullptr;
    RBM_CHECK_PETSC(PetscOptionsGetAll(nullptr, &all));
    std::vector<std::pair<std::string, std::string>> options;  // name without '-', value
    {
        std::istringstream tokens(all ? all : "");
        std::string token;
        while (tokens >> token) {
            if (isOptionName(token)) options.emplace_back(token.substr(1), std::string());
            else if (!options.empty()) options.back().second += (options.back().second.empty() ? "" : " ") + token;
        }
    }
    RBM_CHECK_PETSC(PetscFree(all));
    // Per stem the most specific source: rbm_<other solver>_ never, rbm_ over global.
    static constexpr std::string_view solverNames[] = {"linearized_", "newton_", "laplacian_", "decoupled_"};
    std::map<std::string, std::pair<int, std::string>> inherited;  // stem → (priority, value)
    for (const auto& [name, value] : options) {
        std::string_view stem = name;
        int priority = 0;
        if (stem.substr(0, 4) == "rbm_") {
            stem.remove_prefix(4);
            priority = 1;
            bool otherSolver = false;
            for (std::string_view solver : solverNames) otherSolver = otherSolver || stem.substr(0, solver.size()) == solver;
            if (otherSolver) continue;
        }
        if (!isSolverOptionStem(stem)) continue;
        const auto found = inherited.find(std::string(stem));
        if (found == inherited.end()) inherited.emplace(std::string(stem), std::pair{priority, value});
        else if (priority >= found->second.first) found->second = {priority, value};
    }
    for (const auto& [stem, source] : inherited) hold("-" + prefix_ + stem, source.second);
}

void InheritedOptions::addDefault(std::string_view stem, std::string_view value) const
{
    const std::string name = "-" + prefix_ + std::string(stem);
    if (std::find(copies_.begin(), copies_.end(), name) == copies_.end()) hold(name, std::string(value));
}

void InheritedOptions::hold(const std::string& name, const std::string& value) const
{
    int& holders = copiedOptionHolders()[name];
    if (holders == 0) {
        PetscBool set = PETSC_FALSE;
        RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &set));
        if (set == PETSC_TRUE) {  // given by the user: not ours
            copiedOptionHolders().erase(name);
            return;
        }
        RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()));
    }
    ++holders;
    copies_.push_back(name);
}

bool InheritedOptions::isHeldCopy(const std::string& name)
{
    const auto found = copiedOptionHolders().find(name);
    return found != copiedOptionHolders().end() && found->second > 0;
}

InheritedOptions::~InheritedOptions()
{
    for (const std::string& name : copies_) {
        auto found = copiedOptionHolders().find(name);
        if (found == copiedOptionHolders().end()) continue;
        if (--found->second == 0) {
            if (PetscSession::isInitialized()) (void)PetscOptionsClearValue(nullptr, name.c_str());
            copiedOptionHolders().erase(found);
        }
    }
}

namespace {

// MUMPS orders 2D systems up to this many rows with AMF (approximate minimum fill,
// ICNTL(7) = 2) instead of its automatic choice, which in Debian's MUMPS 5.5 (built with
// PORD only, no METIS or SCOTCH) is PORD's nested dissection. Both order the node graph
// (ICNTL(15): blocks of 3 unknowns). On 2D meshes AMF's analysis is several times faster and
// its factors need about as many flops, so the first solve (analysis + factorisation +
// solve) is cheaper; beyond about 10⁵ nodes, and in 3D, nested dissection's factors need
// enough fewer flops that it wins. AMD, QAMD and PETSc's CHOLMOD are slower; solutions agree
// to rounding (1e-12). The comparison (MUMPS's own timers, one core) is made on rbmBenchmark's
// airfoil, quad2D, tri2D, hex3D and tet3D cases: docs/motionSolver.md, "Direct solver".
[[maybe_unused]] constexpr int amfOrderingRowLimit = 320000;

// setDefaultLinearSolver marks a KSP whose MUMPS factorisation should use AMF with this
// composed object; configureFromOptions, which knows the options prefix, then adds
// -<prefix>mat_mumps_icntl_7 2 as an InheritedOptions default (MUMPS reads it at the
// analysis; any -mat_mumps_icntl_7 given wins).
constexpr const char* amfMarkerName = "rbm_prefer_mumps_amf";

[[maybe_unused]] void markForAmfOrdering(KSP ksp)
{
    PetscHandle<PetscContainer, PetscContainerDestroy> marker;
    RBM_CHECK_PETSC(PetscContainerCreate(PetscObjectComm(reinterpret_cast<PetscObject>(ksp)), marker.out()));
    RBM_CHECK_PETSC(PetscObjectCompose(reinterpret_cast<PetscObject>(ksp), amfMarkerName,
                                       reinterpret_cast<PetscObject>(marker.get())));
}

bool isMarkedForAmfOrdering(KSP ksp)
{
    PetscObject marker = nullptr;
    RBM_CHECK_PETSC(PetscObjectQuery(reinterpret_cast<PetscObject>(ksp), amfMarkerName, &marker));
    return marker != nullptr;
}

} // namespace

void configureFromOptions(KSP ksp, const InheritedOptions& options)
{
    if (isMarkedForAmfOrdering(ksp)) options.addDefault("mat_mumps_icntl_7", "2");
    RBM_CHECK_PETSC(KSPSetOptionsPrefix(ksp, options.prefix().c_str()));
    RBM_CHECK_PETSC(KSPSetFromOptions(ksp));
}

PetscKsp createGamgCycle(Mat matrix, const InheritedOptions& options)
{
    PetscKsp cycle;
    RBM_CHECK_PETSC(KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(matrix)), cycle.out()));
    RBM_CHECK_PETSC(KSPSetOperators(cycle, matrix, matrix));
    RBM_CHECK_PETSC(KSPSetType(cycle, KSPPREONLY));
    PC preconditioner = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(cycle, &preconditioner));
    RBM_CHECK_PETSC(PCSetType(preconditioner, PCGAMG));
    options.addDefault("pc_gamg_threshold", "0.01");
    configureFromOptions(cycle, options);
    RBM_CHECK_PETSC(KSPSetUp(cycle));
    return cycle;
}

void configureFromOptions(SNES snes, const InheritedOptions& options)
{
    KSP ksp = nullptr;
    RBM_CHECK_PETSC(SNESGetKSP(snes, &ksp));
    if (isMarkedForAmfOrdering(ksp)) options.addDefault("mat_mumps_icntl_7", "2");
    RBM_CHECK_PETSC(SNESSetOptionsPrefix(snes, options.prefix().c_str()));
    RBM_CHECK_PETSC(SNESSetFromOptions(snes));
}

void useDirectSolver(KSP ksp, PCType factorization)
{
    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPSetType(ksp, KSPPREONLY));
    RBM_CHECK_PETSC(KSPGetPC(ksp, &pc));
    RBM_CHECK_PETSC(PCSetType(pc, factorization));
#if defined(PETSC_HAVE_MUMPS)
    RBM_CHECK_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
}

bool setDefaultLinearSolver(KSP ksp, LinearSolverKind kind, int dimension, int rowCount, MatrixSymmetry symmetry,
                            double relativeTolerance)
{
    const bool direct = kind == LinearSolverKind::direct ||
                        (kind == LinearSolverKind::automatic && (dimension == 2 || rowCount <= directSolverRowLimit));
    RBM_CHECK_PETSC(KSPSetTolerances(ksp, relativeTolerance, PETSC_DEFAULT, PETSC_DEFAULT, 10000));
    if (direct) {
        useDirectSolver(ksp, symmetry == MatrixSymmetry::symmetricPositiveDefinite ? PCCHOLESKY : PCLU);
#if defined(PETSC_HAVE_MUMPS)
        if (dimension == 2 && rowCount <= amfOrderingRowLimit) markForAmfOrdering(ksp);
#endif
        return true;
    }
    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(ksp, &pc));
    switch (symmetry) {
    case MatrixSymmetry::symmetricPositiveDefinite:
        RBM_CHECK_PETSC(KSPSetType(ksp, KSPCG));
        RBM_CHECK_PETSC(PCSetType(pc, PCGAMG));
        break;
    case MatrixSymmetry::symmetric:
        RBM_CHECK_PETSC(KSPSetType(ksp, KSPGMRES));
        RBM_CHECK_PETSC(PCSetType(pc, PCGAMG));
        break;
    case MatrixSymmetry::general:
        RBM_CHECK_PETSC(KSPSetType(ksp, KSPGMRES));
        RBM_CHECK_PETSC(PCSetType(pc, PCILU));
        break;
    }
    return false;
}

namespace {

bool isType(PetscObject object, const char* type)
{
    PetscBool match = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscObjectTypeCompare(object, type, &match));
    return match == PETSC_TRUE;
}

} // namespace

PetscMat createBlockMatrix(KSP configuredKsp, const BlockRowLayout& layout, std::span<const int> rowOffsets,
                           std::span<const int> columns, int blockSize, MatrixSymmetry symmetry,
                           const InheritedOptions& options)
{
    const int blockRows = static_cast<int>(rowOffsets.size()) - 1;
    if (blockRows != layout.rowCount())
        throw std::invalid_argument("createBlockMatrix: the pattern does not match the row layout");
    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(configuredKsp, &pc));
    const PetscObject pcObject = reinterpret_cast<PetscObject>(pc);
    const bool symmetric = symmetry != MatrixSymmetry::general;
    // MATAIJ, MATBAIJ and MATSBAIJ become the sequential or the MPI type by communicator.
    MatType type = MATAIJ;
    if (symmetric && (isType(pcObject, PCCHOLESKY) || isType(pcObject, PCICC))) {
        type = MATSBAIJ;
    } else if (isType(pcObject, PCLU) || isType(pcObject, PCILU) || isType(pcObject, PCJACOBI) ||
               isType(pcObject, PCPBJACOBI) || isType(pcObject, PCBJACOBI) || isType(pcObject, PCSOR) ||
               isType(pcObject, PCNONE) || isType(pcObject, PCCHOLESKY) || isType(pcObject, PCICC)) {
        type = blockSize > 1 ? MATBAIJ : MATAIJ;
    }
    PetscMat matrix;
    RBM_CHECK_PETSC(MatCreate(layout.communicator(), matrix.out()));
    RBM_CHECK_PETSC(MatSetSizes(matrix, layout.ownedRowCount() * blockSize, layout.ownedRowCount() * blockSize,
                                blockRows * blockSize, blockRows * blockSize));
    RBM_CHECK_PETSC(MatSetBlockSize(matrix, blockSize));
    RBM_CHECK_PETSC(MatSetType(matrix, type));
    RBM_CHECK_PETSC(MatSetOptionsPrefix(matrix, options.prefix().c_str()));
    RBM_CHECK_PETSC(MatSetFromOptions(matrix));

    // Exact preallocation, per owned row: blocks in this rank's columns (the "diagonal"
    // part of an MPI matrix) and in other ranks' columns, all and upper triangle only.
    const int owned = layout.ownedRowCount();
    std::vector<PetscInt> local(owned), remote(owned), upperLocal(owned), upperRemote(owned);
    for (int k = 0; k < owned; ++k) {
        const int row = layout.ownedRows()[k];
        const int petscRow = layout.petscRow(row);
        for (int position = rowOffsets[row]; position < rowOffsets[row + 1]; ++position) {
            const int petscColumn = layout.petscRow(columns[position]);
            const bool isLocal = petscColumn >= layout.ownedBegin() && petscColumn < layout.ownedEnd();
            ++(isLocal ? local : remote)[k];
            if (petscColumn >= petscRow) ++(isLocal ? upperLocal : upperRemote)[k];
        }
    }
    RBM_CHECK_PETSC(MatXAIJSetPreallocation(matrix, blockSize, local.data(), remote.data(), upperLocal.data(),
                                            upperRemote.data()));
    RBM_CHECK_PETSC(MatSetOption(matrix, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    const PetscObject matrixObject = reinterpret_cast<PetscObject>(matrix.get());
    if (isType(matrixObject, MATSEQSBAIJ) || isType(matrixObject, MATMPISBAIJ))
        RBM_CHECK_PETSC(MatSetOption(matrix, MAT_IGNORE_LOWER_TRIANGULAR, PETSC_TRUE));
    if (symmetric) {
        RBM_CHECK_PETSC(MatSetOption(matrix, MAT_SYMMETRIC, PETSC_TRUE));
        RBM_CHECK_PETSC(MatSetOption(matrix, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
    }
    if (symmetry == MatrixSymmetry::symmetricPositiveDefinite) RBM_CHECK_PETSC(MatSetOption(matrix, MAT_SPD, PETSC_TRUE));
    return matrix;
}

void setBlockMatrixValues(Mat matrix, const BlockRowLayout& layout, std::span<const int> rowOffsets,
                          std::span<const int> columns, int blockSize, std::span<const double> values)
{
    const std::size_t area = static_cast<std::size_t>(blockSize) * blockSize;
    if (values.size() != area * columns.size())
        throw std::invalid_argument("setBlockMatrixValues: value array does not match the pattern");
    const bool upperOnly = isType(reinterpret_cast<PetscObject>(matrix), MATSEQSBAIJ) ||
                           isType(reinterpret_cast<PetscObject>(matrix), MATMPISBAIJ);
    for (const int row : layout.ownedRows()) {
        const PetscInt petscRow = layout.petscRow(row);
        for (int position = rowOffsets[row]; position < rowOffsets[row + 1]; ++position) {
            const PetscInt petscColumn = layout.petscRow(columns[position]);
            if (upperOnly && petscColumn < petscRow) continue;
            RBM_CHECK_PETSC(MatSetValuesBlocked(matrix, 1, &petscRow, 1, &petscColumn, values.data() + area * position,
                                                INSERT_VALUES));
        }
    }
    RBM_CHECK_PETSC(MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY));
    RBM_CHECK_PETSC(MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY));
}

void setNearNullSpace(Mat matrix, const BlockRowLayout& layout, int blockSize,
                      const std::vector<std::vector<double>>& modes)
{
    if (modes.empty()) return;
    std::vector<PetscVec> vectors;
    std::vector<Vec> handles;
    for (const std::vector<double>& mode : modes) {
        vectors.push_back(layout.createVector(blockSize));
        layout.scatter(mode, vectors.back(), blockSize);
        handles.push_back(vectors.back());
    }
    PetscHandle<MatNullSpace, MatNullSpaceDestroy> nullSpace;
    RBM_CHECK_PETSC(MatNullSpaceCreate(layout.communicator(), PETSC_FALSE, static_cast<PetscInt>(handles.size()),
                                       handles.data(), nullSpace.out()));
    RBM_CHECK_PETSC(MatSetNearNullSpace(matrix, nullSpace));
}

BlockSystemSolver::BlockSystemSolver(std::span<const int> rowOffsets, std::span<const int> columns, int blockSize,
                                     MatrixSymmetry symmetry, LinearSolverKind kind, int dimension,
                                     double relativeTolerance, std::string_view solverName)
    : rowOffsets_(rowOffsets.begin(), rowOffsets.end()), columns_(columns.begin(), columns.end()),
      layout_(std::make_shared<const BlockRowLayout>(solverCommunicator(), rowOffsets, columns)),
      blockSize_(blockSize), size_((static_cast<int>(rowOffsets.size()) - 1) * blockSize), options_(solverName)
{
    RBM_CHECK_PETSC(KSPCreate(layout_->communicator(), ksp_.out()));
    direct_ = setDefaultLinearSolver(ksp_, kind, dimension, size_, symmetry, relativeTolerance);
    configureFromOptions(ksp_.get(), options_);
    matrix_ = createBlockMatrix(ksp_, *layout_, rowOffsets_, columns_, blockSize_, symmetry, options_);
    RBM_CHECK_PETSC(KSPSetOperators(ksp_, matrix_, matrix_));
    rightHandSide_ = layout_->createVector(blockSize_);
    solution_ = layout_->createVector(blockSize_);
    // The configured method may differ from the default (options): report what is used.
    KSPType type = nullptr;
    RBM_CHECK_PETSC(KSPGetType(ksp_, &type));
    PetscBool preonly = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscStrcmp(type, KSPPREONLY, &preonly));
    // Direct: one application of a factorisation. `preonly` with another preconditioner
    // (e.g. -rbm_reduced_pc_type gamg alone, over the direct default's preonly) is one cycle,
    // not a factor to back-substitute with (asking PETSc for its factor would stop with
    // "No method getfactoredmatrix for PC of type gamg").
    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(ksp_, &pc));
    const PetscObject pcObject = reinterpret_cast<PetscObject>(pc);
    direct_ = preonly == PETSC_TRUE && (isType(pcObject, PCLU) || isType(pcObject, PCCHOLESKY));
}

BlockSystemSolver::~BlockSystemSolver() = default;

void BlockSystemSolver::setNearNullSpace(const std::vector<std::vector<double>>& modes)
{
    motion::setNearNullSpace(matrix_, *layout_, blockSize_, modes);
}

void BlockSystemSolver::setMatrix(std::span<const double> blockValues)
{
    setBlockMatrixValues(matrix_, *layout_, rowOffsets_, columns_, blockSize_, blockValues);
}

BlockSystemSolver::Report BlockSystemSolver::solve(std::span<const double> rightHandSide, std::span<double> solution,
                                                   bool useGuess)
{
    if (static_cast<int>(rightHandSide.size()) != size_ || static_cast<int>(solution.size()) != size_)
        throw std::invalid_argument("BlockSystemSolver::solve: vector sizes do not match the matrix");
    layout_->scatter(rightHandSide, rightHandSide_, blockSize_);
    if (useGuess) layout_->scatter(solution, solution_, blockSize_);
    RBM_CHECK_PETSC(KSPSetInitialGuessNonzero(ksp_, useGuess ? PETSC_TRUE : PETSC_FALSE));
    RBM_CHECK_PETSC(KSPSolve(ksp_, rightHandSide_, solution_));
    Report report;
    PetscInt iterations = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    RBM_CHECK_PETSC(KSPGetIterationNumber(ksp_, &iterations));
    RBM_CHECK_PETSC(KSPGetConvergedReason(ksp_, &reason));
    report.iterations = direct_ ? 0 : static_cast<int>(iterations);
    report.converged = reason > 0;
    report.reason = convergedReasonText(reason);
    layout_->gather(solution_, solution, blockSize_);
    return report;
}

void BlockSystemSolver::applyPreconditioner(std::span<const double> rightHandSide, std::span<double> solution)
{
    if (static_cast<int>(rightHandSide.size()) != size_ || static_cast<int>(solution.size()) != size_)
        throw std::invalid_argument("BlockSystemSolver::applyPreconditioner: vector sizes do not match the matrix");
    RBM_CHECK_PETSC(KSPSetUp(ksp_));
    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(ksp_, &pc));
    layout_->scatter(rightHandSide, rightHandSide_, blockSize_);
    RBM_CHECK_PETSC(PCApply(pc, rightHandSide_, solution_));
    layout_->gather(solution_, solution, blockSize_);
}

void BlockSystemSolver::multiply(std::span<const double> x, std::span<double> y) const
{
    layout_->scatter(x, solution_, blockSize_);
    RBM_CHECK_PETSC(MatMult(matrix_, solution_, rightHandSide_));
    layout_->gather(rightHandSide_, y, blockSize_);
}

std::string convergedReasonText(KSPConvergedReason reason)
{
    const char* text = KSPConvergedReasons[reason];
    return text ? text : "KSP reason " + std::to_string(static_cast<int>(reason));
}

std::string convergedReasonText(SNESConvergedReason reason)
{
    const char* text = SNESConvergedReasons[reason];
    return text ? text : "SNES reason " + std::to_string(static_cast<int>(reason));
}

} // namespace rbm::motion
