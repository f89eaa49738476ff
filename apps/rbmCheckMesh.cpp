// rbmCheckMesh: the quality of an OpenFOAM case's mesh, as checkMesh measures it and with
// the thesis' metrics (section 2.7).
//
//   rbmCheckMesh [-case DIR] [-time T | -latestTime] [-json]
//
// Reads DIR/constant/polyMesh; with -time T (or -latestTime) the points of the time
// folder T (T/polyMesh/points, else the latest earlier time folder that has them, as
// OpenFOAM's pointsInstance does) over the constant topology, or the whole mesh of
// T/polyMesh when it has its own faces. Prints a checkMesh-like report, or with -json the
// same numbers as one JSON object on standard output.
//
// Exit status: 0 when the mesh is valid; 1 when it has inverted cells or one of
// checkMesh's errors (non-positive volumes, wrongly oriented face pyramids, open cells,
// zero-area faces, non-orthogonality beyond 90 degrees); 2 on bad input (message on
// standard error). checkMesh's warnings (aspect ratio above 1000, skewness above 4) are
// reported and counted in "Failed N mesh checks." as checkMesh counts them, but do not
// change the exit status.

#include "InputError.hpp"
#include "PolyMeshReader.hpp"
#include "QualityReport.hpp"
#include "TimeName.hpp"

#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

constexpr int exitInvalidMesh = 1;
constexpr int exitBadInput = 2;

const char* usage =
    "Usage: rbmCheckMesh [-case DIR] [-time T | -latestTime] [-json]\n"
    "\n"
    "Reports the quality of the mesh of an OpenFOAM case: checkMesh's measures (same\n"
    "definitions as OpenFOAM v1912) and the thesis' metrics (mean ratio, F_shape,\n"
    "non-orthogonality, skewness, inverted cells; 2D metrics for one-layer meshes).\n"
    "\n"
    "  -case DIR     case folder (default: the current folder)\n"
    "  -time T       use the points of time folder T (\"constant\" for the initial mesh)\n"
    "  -latestTime   use the points of the latest time folder\n"
    "  -json         print the figures as one JSON object\n"
    "  -help         print this message\n"
    "\n"
    "Exit status: 0 valid mesh; 1 inverted cells or checkMesh errors; 2 bad input.\n";

struct Options {
    fs::path caseDirectory = ".";
    std::optional<std::string> time;
    bool latestTime = false;
    bool json = false;
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

Options parseOptions(int argc, char** argv)
{
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string argument = argv[i];
        auto value = [&](const char* what) {
            if (i + 1 >= argc) throw UsageError(argument + " needs " + what);
            return std::string(argv[++i]);
        };
        if (argument == "-case") {
            options.caseDirectory = value("a case folder");
        } else if (argument == "-time") {
            options.time = value("a time (a time folder name or \"constant\")");
        } else if (argument == "-latestTime") {
            options.latestTime = true;
        } else if (argument == "-json") {
            options.json = true;
        } else {
            throw UsageError("unknown argument '" + argument + "'");
        }
    }
    if (options.time && options.latestTime) throw UsageError("-time and -latestTime cannot be used together");
    return options;
}

bool hasFile(const fs::path& folder, const std::string& name)
{
    return fs::is_regular_file(folder / name) || fs::is_regular_file(folder / (name + ".gz"));
}

// The time folder selected by -time / -latestTime; nullopt for constant.
std::optional<rbm::io::TimeDirectory> selectTime(const Options& options)
{
    if (!options.time && !options.latestTime) return std::nullopt;
    if (options.time && *options.time == "constant") return std::nullopt;
    const auto times = rbm::io::listTimeDirectories(options.caseDirectory);
    if (options.latestTime) {
        if (times.empty()) return std::nullopt;   // OpenFOAM falls back to constant too
        return times.back();
    }
    double wanted = 0.0;
    if (!rbm::io::parseTimeName(*options.time, wanted)) {
        throw rbm::InputError(options.caseDirectory.string(), 0,
                              "-time '" + *options.time + "' is not a number nor \"constant\"");
    }
    for (const auto& t : times) {
        if (t.name == *options.time || std::abs(t.value - wanted) <= 1e-12 * std::max(1.0, std::abs(wanted))) return t;
    }
    std::string available;
    for (const auto& t : times) available += (available.empty() ? "" : ", ") + t.name;
    throw rbm::InputError(options.caseDirectory.string(), 0,
                          "no time folder " + *options.time + " (time folders: " +
                              (available.empty() ? std::string("none") : available) + ")");
}

// The mesh with its reference points (those of constant/polyMesh, or of the time folder
// that has its own topology) and, for a time folder with only points, the moved points.
// The 2D extraction is done on the reference points, which are valid, and the moved points
// are measured through it, so folded cells still count as inverted 2D cells.
struct LoadedMesh {
    rbm::PolyMesh mesh;
    std::optional<std::vector<rbm::Vector3>> movedPoints;
    std::string description;
};

LoadedMesh loadMesh(const Options& options)
{
    const fs::path constantMesh = options.caseDirectory / "constant" / "polyMesh";
    const auto time = selectTime(options);
    LoadedMesh loaded;
    if (time) {
        const fs::path timeMesh = options.caseDirectory / time->name / "polyMesh";
        if (hasFile(timeMesh, "faces")) {
            loaded.mesh = rbm::io::readPolyMesh(timeMesh);
            loaded.description = timeMesh.string();
            return loaded;
        }
        loaded.mesh = rbm::io::readPolyMesh(constantMesh);
        // pointsInstance: the latest time folder up to the selected one that has points.
        const auto times = rbm::io::listTimeDirectories(options.caseDirectory);
        for (auto it = times.rbegin(); it != times.rend(); ++it) {
            if (it->value > time->value) continue;
            const fs::path folder = options.caseDirectory / it->name / "polyMesh";
            if (!hasFile(folder, "points")) continue;
            auto points = rbm::io::readPolyMeshPoints(folder);
            if (points.size() != loaded.mesh.points.size()) {
                throw rbm::InputError(folder.string() + "/points", 0,
                                      "has " + std::to_string(points.size()) + " points but " +
                                          constantMesh.string() + " has " +
                                          std::to_string(loaded.mesh.points.size()));
            }
            loaded.movedPoints = std::move(points);
            loaded.description = constantMesh.string() + " with the points of " + folder.string();
            return loaded;
        }
        loaded.description = constantMesh.string() + " (time " + time->name + " has no points of its own)";
        return loaded;
    }
    loaded.mesh = rbm::io::readPolyMesh(constantMesh);
    loaded.description = constantMesh.string();
    return loaded;
}

} // namespace

int main(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i) {
        const std::string argument = argv[i];
        if (argument == "-help" || argument == "--help" || argument == "-h") {
            std::cout << usage;
            return 0;
        }
    }
    try {
        const Options options = parseOptions(argc, argv);
        const LoadedMesh loaded = loadMesh(options);
        rbm::QualityEvaluator evaluator(loaded.mesh);
        const rbm::QualityReport report =
            loaded.movedPoints ? evaluator.evaluate(*loaded.movedPoints) : evaluator.evaluate();
        if (options.json) {
            std::cout << rbm::qualityReportJson(report);
        } else {
            std::cout << "Mesh: " << loaded.description << "\n\n" << rbm::formatQualityReport(report);
        }
        return report.isValid() ? 0 : exitInvalidMesh;
    } catch (const UsageError& error) {
        std::cerr << "rbmCheckMesh: " << error.what() << "\n\n" << usage;
        return exitBadInput;
    } catch (const rbm::InputError& error) {
        std::cerr << "rbmCheckMesh: " << error.what() << '\n';
        return exitBadInput;
    } catch (const std::exception& error) {
        std::cerr << "rbmCheckMesh: " << error.what() << '\n';
        return exitBadInput;
    }
}
