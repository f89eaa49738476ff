#include "MemoryEstimate.hpp"

#include "MeshTopology.hpp"
#include "RbmProblem.hpp"
#include "RigidBodyMotionOptions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

namespace rbm::motion {

namespace {

// Direct factorisations, bytes per row per log2(rows): fitted to the benchmark's 2D peaks.
constexpr double directBytesPerRowLog = 130.0;
// 3D factorisations fill as nested dissection predicts, nnz(L) ∝ b² n^(4/3) (separators of
// n^(2/3) nodes, dense blocks of the b × b node blocks): 12 bytes (value and index) ×
// 11 b² n^(4/3), the constant fitted to the peaks measured with `linearSolver direct` on hex
// boxes of 15³, 19³ and 23³ unknown nodes (216, 552 and 1229 MiB above the 53 MiB of a tiny
// run: 4 480, 4 430 and 4 600 bytes per n^(4/3); the exponent from the two ends is 1.38).
// The 2D per-row formula above underestimates 3D by 6× already at 3 375 nodes.
constexpr double nestedDissectionConstant = 11.0;
constexpr double factorBytesPerValue = 12.0;
// Krylov + multigrid: assembled blocks (8), PETSc's AIJ copy (8 + 4), the hierarchy (~18).
constexpr double iterativeBytesPerValue = 8.0 + 12.0 + 18.0;
// Matrix-free linearized (MatrixFreeLinearizedSystem.hpp): the scalar displacement Laplacian,
// one value per block (its CSR copy and PETSc's AIJ, 8 + 12) and its multigrid hierarchy
// (~20), plus the Krylov vectors and the per-node rotation maps.
constexpr double matrixFreeBytesPerBlock = 8.0 + 12.0 + 20.0;
constexpr double matrixFreeBytesPerNode = 400.0;
// reducedNewton in 3D with K iterative (ReducedNewtonSolver.hpp), at its peak in the solve: per
// block of K the V-cycle's single-precision copy of K (4 bytes; K's double values, 8 bytes, and
// the aggregation's work live only during the set-up, LaplacianPreconditioner.hpp) and the
// hierarchy's transfers and coarse levels; per unknown node the reduced Hessian's data
// (ReducedHessian3D.hpp), the V-cycle's vectors (ThreeVectorMultigrid.hpp) and the Newton
// iteration's vectors (iterate, rotations, CG, line-search trial, warm start). Fitted to the
// peaks of rbmBenchmark's twist3D case at 1.25·10⁵ and 10⁶ cells (peak minus the peak before
// the solver is built; benchmarks/results/2026-11-27c-cpp2core-twist3D), within 4 %.
constexpr double reducedNewton3DBytesPerBlock = 30.0;
constexpr double reducedNewton3DBytesPerNode = 500.0;

double variantFactor(SolveVariant variant)
{
    switch (variant) {
    case SolveVariant::coupledNewton: return 2.3;
    case SolveVariant::decoupledLinearized: return 2.0;
    default: return 1.0;
    }
}

// /proc/meminfo's MemAvailable in bytes.
std::optional<double> memAvailable()
{
    std::ifstream in("/proc/meminfo");
    std::string key;
    double kibibytes = 0.0;
    std::string unit;
    while (in >> key >> kibibytes) {
        std::getline(in, unit);
        if (key == "MemAvailable:") return kibibytes * 1024.0;
    }
    return std::nullopt;
}

// A number from a cgroup file ("max", a limit of 2^60 or more, or unreadable: none).
std::optional<double> cgroupValue(const std::string& file)
{
    std::ifstream in(file);
    std::string text;
    if (!(in >> text) || text == "max") return std::nullopt;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || value >= 1152921504606846976.0) return std::nullopt;
    return value;
}

// A "key value" line of a cgroup's memory.stat.
double cgroupStat(const std::string& file, std::string_view wanted)
{
    std::ifstream in(file);
    std::string key;
    double value = 0.0;
    while (in >> key >> value) {
        if (key == wanted) return value;
    }
    return 0.0;
}

// What the memory limit of the process's cgroup leaves: limit − (usage − page cache, which the
// kernel reclaims before it fails an allocation). cgroup v2 ("0::<path>") and v1
// ("<n>:memory:<path>"); a container sees its own group as the root.
std::optional<std::pair<double, std::string>> cgroupMemoryLeft()
{
    std::ifstream in("/proc/self/cgroup");
    for (std::string line; std::getline(in, line);) {
        const std::size_t first = line.find(':');
        const std::size_t second = first == std::string::npos ? first : line.find(':', first + 1);
        if (second == std::string::npos) continue;
        const std::string controllers = line.substr(first + 1, second - first - 1);
        const std::string path = line.substr(second + 1);
        const bool v2 = line.compare(0, first, "0") == 0 && controllers.empty();
        if (!v2 && controllers.find("memory") == std::string::npos) continue;
        const std::vector<std::string> roots =
            v2 ? std::vector<std::string>{"/sys/fs/cgroup", "/sys/fs/cgroup/unified"}
               : std::vector<std::string>{"/sys/fs/cgroup/memory"};
        for (const std::string& root : roots) {
            for (const std::string& folder : {root + path, root}) {
                const std::string limitFile = folder + (v2 ? "/memory.max" : "/memory.limit_in_bytes");
                const auto limit = cgroupValue(limitFile);
                if (!limit) continue;
                const double usage = cgroupValue(folder + (v2 ? "/memory.current" : "/memory.usage_in_bytes")).value_or(0.0);
                const double cache = cgroupStat(folder + "/memory.stat", v2 ? "file" : "total_cache");
                return std::pair{std::max(0.0, *limit - std::max(0.0, usage - cache)), limitFile};
            }
        }
    }
    return std::nullopt;
}

} // namespace

MemoryEstimate estimateSolveMemory(SolveVariant variant, const SolveSize& size, LinearSolverKind linearSolver,
                                   int systems)
{
    const bool scalarLaplacian =
        variant == SolveVariant::decoupledNonlinear || variant == SolveVariant::coupledLocalGlobal ||
        variant == SolveVariant::coupledReducedNewton;
    const int blockSize = size.dimension == 2 ? 3 : 6;
    MemoryEstimate estimate;
    estimate.rows = scalarLaplacian ? size.unknownNodes : size.unknownNodes * blockSize;
    estimate.direct = linearSolver == LinearSolverKind::direct ||
                      (linearSolver == LinearSolverKind::automatic &&
                       (size.dimension == 2 || estimate.rows <= directSolverRowLimit));
    const double factor = variantFactor(variant) * std::max(systems, 1);
    const bool matrixFree = variant == SolveVariant::coupledLinearized &&
                            (linearSolver == LinearSolverKind::matrixFree ||
                             (linearSolver == LinearSolverKind::automatic && size.dimension == 3));
    if (matrixFree) {
        estimate.direct = false;
        estimate.matrixFree = true;
        estimate.bytes = factor * (size.blocks * matrixFreeBytesPerBlock + size.unknownNodes * matrixFreeBytesPerNode);
    } else if (estimate.direct) {
        double bytes = estimate.rows * directBytesPerRowLog * std::log2(std::max(estimate.rows, 2.0));
        if (size.dimension == 3) {
            const double b = scalarLaplacian ? 1.0 : blockSize;
            bytes = std::max(bytes, factorBytesPerValue * nestedDissectionConstant * b * b *
                                        std::pow(size.unknownNodes, 4.0 / 3.0));
        }
        estimate.bytes = factor * bytes;
    } else {
        const double values = scalarLaplacian ? size.blocks : size.blocks * blockSize * blockSize;
        estimate.bytes = factor * values * iterativeBytesPerValue;
        if (variant == SolveVariant::coupledReducedNewton && size.dimension == 3)
            estimate.bytes = factor * (size.blocks * reducedNewton3DBytesPerBlock +
                                       size.unknownNodes * reducedNewton3DBytesPerNode);
    }
    return estimate;
}

SolveSize solveSizeOf(const RbmProblem& problem)
{
    SolveSize size;
    size.dimension = problem.dimension();
    size.unknownNodes = problem.unknownNodeCount();
    size.blocks = problem.blockPattern().blockCount();
    return size;
}

SolveSize estimateSolveSize(const MeshTopology& topology, std::span<const std::uint8_t> prescribed, bool pseudoTwoD)
{
    const Label pointCount = topology.pointCount;
    auto isUnknown = [&](Label point) {
        return static_cast<std::size_t>(point) >= prescribed.size() || prescribed[static_cast<std::size_t>(point)] == 0;
    };
    // Neighbours of each unknown point through its cells, counted with a stamp per point.
    std::vector<Label> stamp(static_cast<std::size_t>(pointCount), -1);
    double unknownPoints = 0.0;
    double blocks = 0.0;
    for (Label p = 0; p < pointCount; ++p) {
        const auto cells = topology.cellsOf(p);
        if (!isUnknown(p) || cells.empty()) continue;   // points no cell uses do not move
        unknownPoints += 1.0;
        double neighbours = 0.0;
        stamp[static_cast<std::size_t>(p)] = p;
        for (const Label cell : cells) {
            for (const Label q : topology.pointsOf(cell)) {
                Label& seen = stamp[static_cast<std::size_t>(q)];
                if (seen == p) continue;
                seen = p;
                if (isUnknown(q)) neighbours += 1.0;
            }
        }
        blocks += 1.0 + neighbours;
    }
    SolveSize size;
    size.dimension = pseudoTwoD ? 2 : 3;
    size.unknownNodes = pseudoTwoD ? unknownPoints / 2.0 : unknownPoints;
    size.blocks = pseudoTwoD ? blocks / 4.0 : blocks;
    return size;
}

SolveVariant solveVariantOf(const RigidBodyMotionOptions& options)
{
    const bool linearized = options.formulation == RbmFormulation::linearized;
    if (options.coupling == RbmCoupling::decoupled)
        return linearized ? SolveVariant::decoupledLinearized : SolveVariant::decoupledNonlinear;
    if (linearized) return SolveVariant::coupledLinearized;
    switch (options.algorithm) {
    case RbmAlgorithm::localGlobal: return SolveVariant::coupledLocalGlobal;
    case RbmAlgorithm::reducedNewton: return SolveVariant::coupledReducedNewton;
    case RbmAlgorithm::newton: break;
    }
    return SolveVariant::coupledNewton;
}

int linearSystemsAtOnce(const RigidBodyMotionOptions& options)
{
    return options.formulation == RbmFormulation::linearized && options.subSteps != 1 ? 2 : 1;
}

std::optional<AvailableMemory> availableMemory()
{
    std::optional<AvailableMemory> available;
    if (const auto bytes = memAvailable()) available = AvailableMemory{*bytes, "MemAvailable in /proc/meminfo"};
    if (const auto left = cgroupMemoryLeft(); left && (!available || left->first < available->bytes)) {
        available = AvailableMemory{left->first, "the memory limit of the cgroup, " + left->second};
    }
    return available;
}

std::string formatBytes(double bytes)
{
    char text[64];
    if (bytes >= 1024.0 * 1024.0 * 1024.0) std::snprintf(text, sizeof text, "%.2f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
    else if (bytes >= 1024.0 * 1024.0) std::snprintf(text, sizeof text, "%.0f MiB", bytes / (1024.0 * 1024.0));
    else std::snprintf(text, sizeof text, "%.1f KiB", bytes / 1024.0);
    return text;
}

} // namespace rbm::motion
