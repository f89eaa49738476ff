#pragma once
// rbm's rigid body motion solver for a host program that evaluates its own boundary
// conditions (the OpenFOAM plugin, openfoam/): the narrow interface between a host compiled
// as C++17 (OpenFOAM v1912's headers do not compile as C++20) and rbm's C++20 core.
//
// This header must stay C++17: standard library types and plain arrays only, nothing of rbm
// but this namespace. HostMotionSolver.cpp (C++20) implements it with RigidBodyMotionSolver
// (MotionSolver.hpp's host-described boundary) and StepAssessment (the per-step checks and log
// line rbmMoveMesh prints too).
//
// Per time step the host
//   1. writes the displacement of every point into a 3 × pointCount array (x0 y0 z0 x1 ...),
//      relative to points0; only the prescribed points' values are read,
//   2. calls solve(), which overwrites the free and sliding points' values with rbm's solution
//      (total displacement from points0, warm-started from the previous step) and returns
//      the step's figures, log line and verdict,
//   3. moves its mesh to points0 + displacement.
// The solver object keeps the cell-neighbour graph, the RBM problem, the PETSc objects (with
// their symbolic factorisation) and the last solution between steps.

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rbm::host {

struct HostPatch {
    std::string name;
    std::string type;                 // "patch", "wall", "empty", "wedge", "symmetryPlane", ...
    std::vector<std::string> groups;  // inGroups
    int startFace = 0;
    int faceCount = 0;
    // The patch dictionary's other entries as in constant/polyMesh/boundary ("keyword", "value
    // text"); read for cyclic patches: neighbourPatch, transform, rotationAxis, rotationCentre.
    std::vector<std::pair<std::string, std::string>> entries;
};

// The mesh at its reference points (points0), in OpenFOAM's face-based form.
struct HostMesh {
    std::vector<double> points;       // 3 × pointCount: x0 y0 z0 x1 y1 z1 ...
    std::vector<int> faceOffsets{0};  // face f: faceVertices[faceOffsets[f] .. faceOffsets[f+1])
    std::vector<int> faceVertices;
    std::vector<int> owner;           // one per face
    std::vector<int> neighbour;       // one per internal face (internal faces first)
    std::vector<HostPatch> patches;
};

enum class HostNodeClass {
    prescribed,  // the host gives the displacement before every solve
    sliding,     // unknown, held on the plane normal to slidingNormals through its reference position
    free,        // unknown, moves like an interior point
    ignored,     // empty / wedge planes of a pseudo-2D mesh: rbm solves in 2D and moves both planes
    coupled,     // a plain cyclic patch: unknown, tied to its partner points on the neighbour patch
};

// How the host's boundary conditions constrain one patch (one per mesh patch, in patch order).
struct HostPatchBoundary {
    HostNodeClass nodeClass = HostNodeClass::free;
    // Sliding: 3 per patch point in the patch's localPoints order (unit normals); empty otherwise.
    std::vector<double> slidingNormals;
    // Sliding: a mirror plane (symmetry, symmetryPlane) rather than a slip wall.
    bool mirror = false;
};

// Bad input (a coefficient, a mesh rbm cannot solve on): the file, its line (0 when not
// known) and the message, which names the dictionary entry.
class HostInputError : public std::runtime_error {
public:
    HostInputError(std::string file, int line, const std::string& message)
        : std::runtime_error(message), file_(std::move(file)), line_(line)
    {}
    const std::string& file() const { return file_; }
    int line() const { return line_; }

private:
    std::string file_;
    int line_;
};

// What one solve() did.
struct HostStepReport {
    int subSteps = 0;
    int iterations = 0;
    double residual = 0.0;
    double energy = 0.0;
    bool converged = false;
    std::string reason;            // the solver's converged / diverged reason
    long long invertedCells = 0;
    double worstQuality = 0.0;     // as rbmMoveMesh's log line
    double maxNonOrthogonality = 0.0;
    double maxSkewness = 0.0;
    double wallSeconds = 0.0;      // solve and checks
    bool finite = true;            // no NaN or infinite displacement or residual
    bool valid = true;             // converged, finite and no inverted cell
    std::string logLine;           // "rigidBodyMotionSolver: " + rbmMoveMesh's figures for this step
                                   // (no "Time = ": the host prints its own)
    std::string problem;           // why the step is not valid (empty when it is), with advice
    std::vector<std::string> warnings;  // to show the user (a floating patch leaving its plane, ...)
};

class HostMotionSolver {
public:
    // `coefficientsText`: the coefficient dictionary's text in OpenFOAM syntax (the entries of
    // rigidBodyMotionSolverCoeffs, RigidBodyMotionOptions.hpp); `coefficientsFile`: its name
    // for messages. `boundary`: one entry per mesh patch. Initialises PETSc (and MPI unless
    // the host did) the first time; PETSc is finalised when the last solver is destroyed.
    // Throws HostInputError for bad coefficients or a mesh/boundary rbm cannot solve on,
    // std::runtime_error for other failures.
    HostMotionSolver(const HostMesh& mesh, const std::string& coefficientsText, const std::string& coefficientsFile,
                     const std::vector<HostPatchBoundary>& boundary, const std::string& caseDirectory);
    ~HostMotionSolver();
    HostMotionSolver(const HostMotionSolver&) = delete;
    HostMotionSolver& operator=(const HostMotionSolver&) = delete;

    std::size_t pointCount() const;
    // 2 for a pseudo-2D mesh (solved on one plane), 3 otherwise.
    int dimension() const;

    // Steps 1-2 above. `displacement`: 3 × pointCount() values, read at the prescribed points
    // and written everywhere. `step` (1 for the run's first) and `timeName` are for the log
    // line. Throws std::invalid_argument for a wrong length, std::runtime_error for a PETSc
    // failure; inverted cells and non-convergence are reported, not thrown.
    HostStepReport solve(int step, double time, const std::string& timeName, double* displacement,
                         std::size_t valueCount);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace rbm::host
