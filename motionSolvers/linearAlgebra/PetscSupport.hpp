#pragma once
// The thin PETSc layer of the motion solvers: every PETSc return code goes through
// checkPetsc (an exception carrying PETSc's own message, since Debian's PETSc 3.18 is a C
// build without PetscCallThrow), PETSc objects live in move-only RAII handles, and
// PetscSession initialises and finalises the library once per program.
//
// Options: every solver object has the prefix rbm_<solver>_ (rbm_linearized_,
// rbm_newton_, rbm_laplacian_, rbm_decoupled_) and reads, in increasing priority, the
// global solver options (`-ksp_type cg`, `-snes_monitor`, `-ksp_view`), the `rbm_` ones
// (`-rbm_ksp_type cg`) and its own (`-rbm_laplacian_pc_type gamg`). See InheritedOptions.

#include <petscksp.h>
#include <petscsnes.h>

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rbm::motion {

// A PETSc call failed. what() = "<call>: <PETSc's message> (PETSc error <code>)".
class PetscException : public std::runtime_error {
public:
    PetscException(PetscErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    PetscErrorCode code() const { return code_; }

private:
    PetscErrorCode code_;
};

// Throws PetscException when code is not zero; `call` names the failed call in the message.
void checkPetsc(PetscErrorCode code, std::string_view call);

// For C callbacks called by PETSc (SNES functions, line searches): turns an exception
// into a PETSc error code carrying its message, since exceptions must not cross C frames.
PetscErrorCode petscErrorFromException(const char* function, const std::exception& error);

// checkPetsc with the call's source text as its name: RBM_CHECK_PETSC(VecSet(x, 0.0)).
#define RBM_CHECK_PETSC(call) ::rbm::motion::checkPetsc((call), #call)

// Move-only owner of a PETSc object handle (Vec, Mat, KSP, SNES); destroys it once.
template <typename Handle, PetscErrorCode (*destroyFunction)(Handle*)>
class PetscHandle {
public:
    PetscHandle() = default;
    explicit PetscHandle(Handle handle) : handle_(handle) {}
    PetscHandle(const PetscHandle&) = delete;
    PetscHandle& operator=(const PetscHandle&) = delete;
    PetscHandle(PetscHandle&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
    PetscHandle& operator=(PetscHandle&& other) noexcept
    {
        if (this != &other) {
            reset();
            handle_ = std::exchange(other.handle_, nullptr);
        }
        return *this;
    }
    ~PetscHandle() { reset(); }

    // Destroying cannot throw from a destructor; a failing destroy is ignored.
    void reset() noexcept
    {
        if (handle_) (void)destroyFunction(&handle_);
        handle_ = nullptr;
    }
    Handle get() const { return handle_; }
    operator Handle() const { return handle_; }     // NOLINT: pass straight to PETSc calls
    Handle* out() { reset(); return &handle_; }     // for Create functions: VecCreate(comm, v.out())
    explicit operator bool() const { return handle_ != nullptr; }

private:
    Handle handle_ = nullptr;
};

using PetscVec = PetscHandle<Vec, VecDestroy>;
using PetscMat = PetscHandle<Mat, MatDestroy>;
using PetscKsp = PetscHandle<KSP, KSPDestroy>;
using PetscSnes = PetscHandle<SNES, SNESDestroy>;

// Initialises PETSc (and MPI) unless it already is, finalises it only if this object
// initialised it. Installs PETSc's "return" error handler so errors become exceptions
// through checkPetsc instead of tracebacks on stderr. Before initialising it sets Open MPI's
// fast singleton start and one OpenBLAS thread, unless the environment says otherwise
// (PetscSupport.cpp says why).
class PetscSession {
public:
    PetscSession();                       // no command-line options (PETSC_OPTIONS still read)
    PetscSession(int* argc, char*** argv); // command-line options such as -rbm_ksp_type
    PetscSession(const PetscSession&) = delete;
    PetscSession& operator=(const PetscSession&) = delete;
    ~PetscSession();

    static bool isInitialized();

private:
    bool ownsInitialization_ = false;
};

// The options one solver object inherits. PETSc looks options up under an object's
// prefix only, also at solve time (-ksp_view, -ksp_converged_reason), so the global
// (`-ksp_...`, `-pc_...`, `-snes_...`, `-mat_...`, `-mg_...`, `-sub_...`) and `-rbm_...`
// solver options are copied under `-rbm_<solverName>_` unless that name is set already.
// The copies live as long as some holder for that name does (reference counted).
class InheritedOptions {
public:
    explicit InheritedOptions(std::string_view solverName);
    InheritedOptions(const InheritedOptions&) = delete;
    InheritedOptions& operator=(const InheritedOptions&) = delete;
    ~InheritedOptions();

    const std::string& prefix() const { return prefix_; }  // "rbm_<solverName>_"

    // Sets -rbm_<solverName>_<stem> to value for this holder's lifetime unless that option
    // is given (in any of the forms above) or held already. Used by configureFromOptions for
    // rbm's own defaults; const as the copies are: they belong to the options database.
    void addDefault(std::string_view stem, std::string_view value) const;

    // Whether the option `name` ("-rbm_reduced_ksp_type") is one of these copies or defaults,
    // held by some living InheritedOptions, rather than the user's own.
    static bool isHeldCopy(const std::string& name);

private:
    void hold(const std::string& name, const std::string& value) const;

    std::string prefix_;
    mutable std::vector<std::string> copies_;
};

// Applies the options under options.prefix() to a solver object whose defaults are set
// (call last: command-line options override the defaults). Adds the option defaults that
// setDefaultLinearSolver asked for (MUMPS's AMF ordering) to `options`.
void configureFromOptions(KSP ksp, const InheritedOptions& options);

// One cycle of PETSc's GAMG of `matrix` as a set-up KSP (preonly) on the matrix's communicator,
// options under options.prefix() (a -<prefix>pc_type given replaces GAMG). GAMG drops couplings
// below 0.01 of the diagonal's scale from its coarsening graph unless -<prefix>pc_gamg_threshold
// says otherwise: on a boundary-layer mesh (weights 1/|d|², cells of aspect ratio up to
// thousands) its default (0, keep all) aggregates the couplings along the layers with those
// across them and the cycle barely converges (tutorials/wing3D at 27 864 cells on 2 ranks, one
// step: 134 s and 12 Newton iterations with 0, 8.6 s and 8 with 0.01; the 2·10⁵-cell cube: the
// same Newton iterations and memory either way).
PetscKsp createGamgCycle(Mat matrix, const InheritedOptions& options);
void configureFromOptions(SNES snes, const InheritedOptions& options);

// Direct factorisation package: MUMPS when PETSc has it, else PETSc's own.
void useDirectSolver(KSP ksp, PCType factorization /* PCLU or PCCHOLESKY */);

// What a system matrix is known to be; chooses default solvers and matrix storage.
enum class MatrixSymmetry {
    general,                    // e.g. the decoupled linearized system
    symmetric,                  // e.g. a Newton Hessian away from the minimum
    symmetricPositiveDefinite,  // linearized coupled matrix, graph Laplacians
};

enum class LinearSolverKind {
    automatic,  // direct factorisation for 2D and small problems, Krylov + multigrid otherwise;
                // the coupled linearized system in 3D on one rank: matrixFree
    direct,     // LU, or Cholesky for symmetric positive definite matrices (MUMPS if present)
    iterative,  // CG + GAMG (symmetric positive definite), GMRES + GAMG (symmetric), GMRES + ILU
    matrixFree, // the coupled linearized system unassembled (MatrixFreeLinearizedSystem.hpp); systems
                // that need their matrix (Newton's Hessian, the Laplacians) solve as `iterative`
};

// Direct factorisation is the automatic choice in 2D and, in 3D, up to this many scalar
// unknowns. 3D fronts are large: beyond a few tens of thousands of unknowns a 3D
// factorisation costs many times what CG + GAMG costs (docs/motionSolver.md, "Linear solvers").
inline constexpr int directSolverRowLimit = 20000;

// Sets the default Krylov method and preconditioner of ksp (before configureFromOptions).
// Returns true when the default is a direct factorisation. For 2D systems up to 320 000
// rows that MUMPS factorises, MUMPS orders with AMF (-mat_mumps_icntl_7 2, added by
// configureFromOptions) unless an option says otherwise: faster there, see
// PetscSupport.cpp.
bool setDefaultLinearSolver(KSP ksp, LinearSolverKind kind, int dimension, int rowCount, MatrixSymmetry symmetry,
                            double relativeTolerance);

class BlockRowLayout;

// A matrix with the block sparsity given in CSR form over natural block rows (columns
// sorted, diagonal included) and exact preallocation, distributed as `layout` says (see
// BlockRowLayout.hpp; sequential on one rank). Its storage follows the preconditioner
// configured on ksp: SBAIJ for Cholesky/ICC of symmetric matrices, BAIJ for
// LU/ILU/Jacobi-type preconditioners, AIJ with the block size set for everything else
// (multigrid needs AIJ). `-mat_type`, `-rbm_mat_type`, `-rbm_<solverName>_mat_type` override.
PetscMat createBlockMatrix(KSP configuredKsp, const BlockRowLayout& layout, std::span<const int> rowOffsets,
                           std::span<const int> columns, int blockSize, MatrixSymmetry symmetry,
                           const InheritedOptions& options);
// Inserts this rank's rows of the blocks (blockSize² values each, row-major, in natural
// pattern order: every rank passes all of them) and assembles (collective). Blocks below
// the diagonal (in PETSc's numbering) are skipped for SBAIJ storage.
void setBlockMatrixValues(Mat matrix, const BlockRowLayout& layout, std::span<const int> rowOffsets,
                          std::span<const int> columns, int blockSize, std::span<const double> values);

// Tells algebraic multigrid the near null space of `matrix`: orthonormal vectors in natural
// order (all rows, every rank), e.g. rigidMotionModes(). Direct solvers ignore it.
void setNearNullSpace(Mat matrix, const BlockRowLayout& layout, int blockSize,
                      const std::vector<std::vector<double>>& modes);

// One sparse linear system over a block pattern, owning its matrix and KSP. The KSP keeps
// its preconditioner (for a direct solver: the factorisation) between solve() calls until
// setMatrix() changes the values, so a constant matrix is factorised once. The system is
// distributed over solverCommunicator() (BlockRowLayout.hpp); its interface takes and
// returns whole arrays in natural order on every rank.
class BlockSystemSolver {
public:
    struct Report {
        int iterations = 0;
        bool converged = false;
        std::string reason;
        double residualNorm = -1.0;  // a caller's ‖residual‖ at the solution when it has it; −1: not computed
    };

    // rowOffsets/columns: block CSR (sorted columns, diagonal included), copied.
    // solverName selects the options prefix rbm_<solverName>_ (see InheritedOptions).
    BlockSystemSolver(std::span<const int> rowOffsets, std::span<const int> columns, int blockSize,
                      MatrixSymmetry symmetry, LinearSolverKind kind, int dimension, double relativeTolerance,
                      std::string_view solverName);
    ~BlockSystemSolver();

    int size() const { return size_; }
    int blockSize() const { return blockSize_; }
    bool isDirect() const { return direct_; }
    KSP ksp() const { return ksp_; }
    Mat matrix() const { return matrix_; }
    const BlockRowLayout& layout() const { return *layout_; }

    // Inserts the blocks (blockSize² values each, row-major, pattern order) and assembles.
    void setMatrix(std::span<const double> blockValues);
    // See the free function setNearNullSpace; call before the first solve.
    void setNearNullSpace(const std::vector<std::vector<double>>& modes);
    // Solves A x = b. With useGuess, x's input is the initial guess of an iterative method.
    Report solve(std::span<const double> rightHandSide, std::span<double> solution, bool useGuess = false);
    // solution = M⁻¹ rightHandSide: ONE application of the configured preconditioner (PCApply;
    // for GAMG or BoomerAMG one V-cycle), set up at the first call. Not a solve: a linear map
    // close to A⁻¹, for an outer flexible Krylov method.
    void applyPreconditioner(std::span<const double> rightHandSide, std::span<double> solution);
    // y = A x.
    void multiply(std::span<const double> x, std::span<double> y) const;

private:
    std::vector<int> rowOffsets_;
    std::vector<int> columns_;
    std::shared_ptr<const BlockRowLayout> layout_;
    int blockSize_;
    int size_;
    bool direct_ = false;
    InheritedOptions options_;
    PetscKsp ksp_;
    PetscMat matrix_;
    PetscVec rightHandSide_;
    PetscVec solution_;
};

// The text of a convergence reason ("CONVERGED_RTOL", "DIVERGED_LINE_SEARCH", ...).
std::string convergedReasonText(KSPConvergedReason reason);
std::string convergedReasonText(SNESConvergedReason reason);

} // namespace rbm::motion
