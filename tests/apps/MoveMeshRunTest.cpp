// rbmMoveMesh's time loop (apps/MoveMeshRun), its log (io/RunLog) and atomic time folders
// (io/TimeFolderWriter). The cases are built here in temporary folders: a MeshGenerators
// mesh written with io::writePolyMesh, and controlDict / dynamicMeshDict / pointDisplacement
// text. Expected write times follow OpenFOAM v1912's Time::operator++ rules, worked out by
// hand in the comments; geometric expectations are invariants (one full period returns to
// the initial mesh; a rigid translation keeps every cell a perfect cube; a boundary that
// turns inside out forces an inverted cell).

#include "FoamDictionaryWriter.hpp"
#include "MeshGenerators.hpp"
#include "MoveMeshRun.hpp"
#include "PetscTestEnvironment.hpp"
#include "PointVectorField.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "RigidBodyMotionSolver.hpp"
#include "RunLog.hpp"
#include "ScratchFiles.hpp"
#include "TestCases.hpp"
#include "TimeFolderWriter.hpp"
#include "TimeName.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace rbm::test::moveMeshCases;

namespace {

using namespace rbm;

std::string header(const std::string& className, const std::string& location, const std::string& object)
{
    return "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class " + className + ";\n    location \"" +
           location + "\";\n    object " + object + ";\n}\n\n";
}

// system/controlDict entries, OpenFOAM spelling.
struct Control {
    std::string startFrom = "startTime";
    std::string startTime = "0";
    std::string endTime = "0.3";
    std::string deltaT = "0.05";
    std::string writeControl = "timeStep";
    std::string writeInterval = "2";
    std::string writeFormat = "ascii";
    int writePrecision = 12;
    bool compression = false;

    std::string text() const
    {
        return header("dictionary", "system", "controlDict") + "application rbmMoveMesh;\nstartFrom " + startFrom +
               ";\nstartTime " + startTime + ";\nstopAt endTime;\nendTime " + endTime + ";\ndeltaT " + deltaT +
               ";\nwriteControl " + writeControl + ";\nwriteInterval " + writeInterval + ";\nwriteFormat " +
               writeFormat + ";\nwritePrecision " + std::to_string(writePrecision) + ";\nwriteCompression " +
               (compression ? "on" : "off") + ";\ntimeFormat general;\ntimePrecision 6;\n";
    }
};

std::string dynamicMeshDict(const std::string& coefficients = "", const std::string& solver = "rigidBodyMotionSolver")
{
    return header("dictionary", "constant", "dynamicMeshDict") + "dynamicFvMesh dynamicMotionSolverFvMesh;\n" +
           "motionSolver " + solver + ";\n" + "rigidBodyMotionSolverCoeffs\n{\n" + coefficients + "\n}\n";
}

std::string pointDisplacement(const std::string& boundaryField)
{
    return header("pointVectorField", "0", "pointDisplacement") +
           "dimensions [0 1 0 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{\n" + boundaryField + "\n}\n";
}

constexpr double pi = std::numbers::pi;

// The left side of the unit square pitches about its midpoint (0, 0.5):
// angle(t) = 0.1 sin(2π t), period 1; the right side is fixed, top and bottom are free.
const std::string pitchingBoundary = R"foam(
    left
    {
        type            angularOscillatingDisplacement;
        axis            (0 0 1);
        origin          (0 0.5 0);
        angle0          0;
        amplitude       0.1;
        omega           6.283185307179586;
        value           uniform (0 0 0);
    }
    right           { type fixedValue; value uniform (0 0 0); }
    "(top|bottom)"  { type zeroGradient; }
    frontAndBack    { type empty; }
)foam";

// The left side moves right: 0.05 at t = 0.1 (valid), 2 at t = 0.2, beyond the fixed right
// side at x = 1. Top and bottom slide along their lines, so the boundary polygon's signed
// area is -(2 − 1)·1 < 0 whatever the interior does: the cell areas sum to it, so at least
// one cell is inverted at t = 0.2.
const std::string invertingBoundary = R"foam(
    left
    {
        type            uniformFixedValue;
        uniformValue    table ((0 (0 0 0)) (0.1 (0.05 0 0)) (0.2 (2 0 0)) (0.3 (2 0 0)));
        value           uniform (0 0 0);
    }
    right           { type fixedValue; value uniform (0 0 0); }
    "(top|bottom)"  { type slip; }
    frontAndBack    { type empty; }
)foam";

// A 2D case: 8 × 8 quadrilaterals on the unit square, one layer 0.1 deep.
void writeSquareCase(const fs::path& caseDir, const Control& control, const std::string& boundaryField,
                     const std::string& coefficients = "")
{
    const PolyMesh mesh = makeExtruded2D(8, 8, Vector3{0, 0, 0}, Vector3{1, 1, 0.1});
    io::writePolyMesh(caseDir / "constant" / "polyMesh", mesh, io::FoamWriteOptions{});
    writeText(caseDir / "system" / "controlDict", control.text());
    writeText(caseDir / "constant" / "dynamicMeshDict", dynamicMeshDict(coefficients));
    writeText(caseDir / "0" / "pointDisplacement", pointDisplacement(boundaryField));
}

// What a run printed and what the solver held after every step.
struct RunResult {
    int status = -1;
    std::string out;
    std::string err;
    std::vector<io::StepLogRecord> records;
    std::map<std::string, std::vector<Vector3>> points;         // by time name
    std::map<std::string, std::vector<Vector3>> displacements;  // by time name
};

RunResult runCase(const fs::path& caseDir, bool writeVtk = true, bool writeInvalid = false)
{
    app::MoveMeshOptions options;
    options.caseDirectory = caseDir;
    options.writeVtk = writeVtk;
    options.writeInvalid = writeInvalid;
    RunResult result;
    std::ostringstream out;
    std::ostringstream err;
    result.status = app::runMoveMesh(options, out, err, [&](const app::StepObservation& step) {
        result.records.push_back(step.record);
        result.points[step.record.timeName] = step.points;
        result.displacements[step.record.timeName] = step.solver.pointDisplacement();
    });
    result.out = out.str();
    result.err = err.str();
    return result;
}

// Every file and folder under `root` with its size and modification time.
std::map<std::string, std::string> listing(const fs::path& root)
{
    std::map<std::string, std::string> entries;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const std::string name = fs::relative(entry.path(), root).string();
        if (entry.is_directory()) {
            entries[name] = "folder";
        } else {
            entries[name] = std::to_string(entry.file_size()) + " bytes, modified " +
                            std::to_string(entry.last_write_time().time_since_epoch().count());
        }
    }
    return entries;
}

double largestDistance(const std::vector<Vector3>& a, const std::vector<Vector3>& b)
{
    EXPECT_EQ(a.size(), b.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) largest = std::max(largest, norm(a[i] - b[i]));
    return largest;
}

std::vector<std::map<std::string, JsonValue>> readJsonLines(const fs::path& file)
{
    std::vector<std::map<std::string, JsonValue>> lines;
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        std::map<std::string, JsonValue> object;
        EXPECT_TRUE(parseFlatJsonObject(line, object)) << "not a JSON object: " << line;
        lines.push_back(std::move(object));
    }
    return lines;
}

TEST(MoveMeshCommandLine, SeparatesItsOwnOptionsFromPetscOptions)
{
    const char* argv[] = {"rbmMoveMesh", "-case", "cases/airfoil", "-ksp_type", "cg",   "-noVTK", "-rbm_pc_type",
                          "gamg",        "-ksp_rtol", "1e-12",    "-writeInvalid", "-info", "-ksp_atol", "-1"};
    const app::CommandLine commandLine = app::parseCommandLine(static_cast<int>(std::size(argv)), argv);
    EXPECT_EQ(commandLine.options.caseDirectory, fs::path("cases/airfoil"));
    EXPECT_FALSE(commandLine.options.writeVtk);
    EXPECT_TRUE(commandLine.options.writeInvalid);
    EXPECT_FALSE(commandLine.options.parallel);
    EXPECT_FALSE(commandLine.help);
    const std::vector<std::string> petsc = {"-ksp_type", "cg",    "-rbm_pc_type", "gamg",      "-ksp_rtol",
                                            "1e-12",     "-info", "-ksp_atol",    "-1"};
    EXPECT_EQ(commandLine.petscArguments, petsc);
}

TEST(MoveMeshCommandLine, RejectsUnknownOptionsStrayWordsAndAMissingCase)
{
    const char* misspelt[] = {"rbmMoveMesh", "-noVtk"};
    EXPECT_THROW(app::parseCommandLine(2, misspelt), app::UsageError);
    const char* stray[] = {"rbmMoveMesh", "myCase"};
    EXPECT_THROW(app::parseCommandLine(2, stray), app::UsageError);
    const char* noValue[] = {"rbmMoveMesh", "-case"};
    EXPECT_THROW(app::parseCommandLine(2, noValue), app::UsageError);
    try {
        const char* argv[] = {"rbmMoveMesh", "-ksp_type", "cg", "-frobnicate"};
        app::parseCommandLine(4, argv);
        ADD_FAILURE() << "no UsageError";
    } catch (const app::UsageError& error) {
        EXPECT_TRUE(contains(error.what(), "unknown option '-frobnicate'")) << error.what();
    }
}

TEST(MoveMeshCommandLine, HelpListsOptionsDictionaryKeywordsAndExitStatuses)
{
    char program[] = "rbmMoveMesh";
    char help[] = "-help";
    char* argv[] = {program, help, nullptr};
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(app::moveMeshMain(2, argv, out, err), app::exitSuccess);
    const std::string text = out.str();
    for (const char* expected : {"-case DIR", "-noVTK", "-parallel", "-writeInvalid", "-version", "startFrom",
                                 "writeCompression", "motionSolver", "rigidBodyMotionSolver", "subSteps",
                                 "angularOscillatingDisplacement", "fixedValue", "log.jsonl", "Exit status"}) {
        EXPECT_TRUE(contains(text, expected)) << "no '" << expected << "' in:\n" << text;
    }
    EXPECT_TRUE(err.str().empty());
}

TEST(MoveMeshCommandLine, VersionNamesTheProgramAndPetsc)
{
    char program[] = "rbmMoveMesh";
    char version[] = "-version";
    char* argv[] = {program, version, nullptr};
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(app::moveMeshMain(2, argv, out, err), app::exitSuccess);
    EXPECT_EQ(out.str().rfind("rbmMoveMesh ", 0), 0u) << out.str();
    EXPECT_TRUE(contains(out.str(), "PETSc 3.")) << out.str();
}

TEST(MoveMeshCommandLine, AnUnknownOptionExitsWithTwoAndPrintsTheUsage)
{
    char program[] = "rbmMoveMesh";
    char bad[] = "-latestTime";
    char* argv[] = {program, bad, nullptr};
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(app::moveMeshMain(2, argv, out, err), app::exitBadInput);
    EXPECT_TRUE(contains(err.str(), "unknown option '-latestTime'")) << err.str();
    EXPECT_TRUE(contains(err.str(), "Usage: rbmMoveMesh")) << err.str();
}

TEST(MoveMeshRun, WritesEveryWriteIntervalStepsInFoldersWithOpenFoamNames)
{
    TempDir dir("timeStep");
    Control control;   // deltaT 0.05 to 0.3, timeStep every 2 steps: steps 2, 4, 6
    writeSquareCase(dir.path(), control, pitchingBoundary);
    const RunResult result = runCase(dir.path());
    ASSERT_EQ(result.status, app::exitSuccess) << result.out << result.err;

    EXPECT_EQ(timeFolders(dir.path()), (std::set<std::string>{"0", "0.1", "0.2", "0.3"}));
    ASSERT_EQ(result.records.size(), 6u);
    const std::vector<Vector3> points0 = io::readPolyMeshPoints(dir.path() / "constant" / "polyMesh");
    for (const std::string name : {"0.1", "0.2", "0.3"}) {
        SCOPED_TRACE(name);
        // points: ascii with writePrecision 12 (relative 5e-13 of coordinates up to 1).
        const std::vector<Vector3> written = io::readPolyMeshPoints(dir.path() / name);
        EXPECT_LT(largestDistance(written, result.points.at(name)), 1e-11);
        // pointDisplacement: the total displacement from points0, and the boundary conditions.
        const PolyMesh mesh = io::readPolyMesh(dir.path() / "constant" / "polyMesh");
        const io::PointVectorField field = io::readPointVectorField(dir.path() / name / "pointDisplacement", mesh);
        EXPECT_LT(largestDistance(field.internalField, result.displacements.at(name)), 1e-11);
        std::vector<Vector3> moved(points0.size());
        for (std::size_t i = 0; i < moved.size(); ++i) moved[i] = points0[i] + field.internalField[i];
        EXPECT_LT(largestDistance(moved, written), 1e-11);
        ASSERT_EQ(field.boundaryField.size(), 5u);
        EXPECT_EQ(field.boundaryField[0].patchName, "left");
        EXPECT_EQ(field.boundaryField[0].type, "angularOscillatingDisplacement");
        EXPECT_EQ(field.boundaryField[0].dictionary.get<double>("amplitude"), 0.1);
        EXPECT_TRUE(field.boundaryField[0].dictionary.contains("value"));
        EXPECT_EQ(field.boundaryField[2].type, "zeroGradient");
        EXPECT_EQ(field.boundaryField[4].type, "empty");
    }
    // The motion did happen: at t = 0.3 the left side has turned by 0.1 sin(0.6π).
    const double angle = 0.1 * std::sin(2 * pi * 0.3);
    const std::vector<Vector3>& atEnd = result.points.at("0.3");
    // Point (i, j) = (0, 0) of the front plane is label 0: (0, 0) turned about (0, 0.5).
    EXPECT_NEAR(atEnd[0].x, 0.5 * std::sin(angle), 1e-12);
    EXPECT_NEAR(atEnd[0].y, 0.5 - 0.5 * std::cos(angle), 1e-12);

    // VTK: the initial mesh and every written time, listed in the .pvd.
    const std::string caseName = dir.path().filename().string();
    for (const std::string name : {"0", "0.1", "0.2", "0.3"}) {
        EXPECT_TRUE(fs::exists(dir.path() / "VTK" / (caseName + "_" + name + ".vtu"))) << name;
        EXPECT_TRUE(contains(readText(dir.path() / "VTK" / (caseName + ".pvd")), caseName + "_" + name + ".vtu"));
    }
    EXPECT_FALSE(fs::exists(dir.path() / "VTK" / (caseName + "_0.05.vtu")));
    EXPECT_TRUE(contains(result.out, "Time = 0.05 "));
    expectNoTemporaryFiles(dir.path());
}

TEST(MoveMeshRun, BinaryCompressedPointsEqualTheSolverPointsBitForBit)
{
    TempDir dir("binary");
    Control control;
    control.writeFormat = "binary";
    control.compression = true;
    control.endTime = "0.1";
    writeSquareCase(dir.path(), control, pitchingBoundary);
    const RunResult result = runCase(dir.path(), false);
    ASSERT_EQ(result.status, app::exitSuccess) << result.out << result.err;
    EXPECT_TRUE(fs::exists(dir.path() / "0.1" / "polyMesh" / "points.gz"));
    EXPECT_FALSE(fs::exists(dir.path() / "0.1" / "polyMesh" / "points"));
    EXPECT_TRUE(fs::exists(dir.path() / "0.1" / "pointDisplacement.gz"));
    EXPECT_EQ(io::readPolyMeshPoints(dir.path() / "0.1"), result.points.at("0.1"));
    EXPECT_FALSE(fs::exists(dir.path() / "VTK"));   // -noVTK
}

TEST(MoveMeshRun, RunTimeWritesWhereOpenFoamsWriteIndexGrows)
{
    // OpenFOAM v1912: write when label(((t − startTime) + deltaT/2)/writeInterval) grows.
    // deltaT 0.03, writeInterval 0.1: t = 0.03..0.3 gives (t + 0.015)/0.1 = 0.45, 0.75, 1.05,
    // 1.35, 1.65, 1.95, 2.25, 2.55, 2.85, 3.15: the index grows at 0.09, 0.21 and 0.3.
    for (const std::string writeControl : {"runTime", "adjustableRunTime"}) {
        SCOPED_TRACE(writeControl);
        TempDir dir(writeControl);
        Control control;
        control.deltaT = "0.03";
        control.writeControl = writeControl;
        control.writeInterval = "0.1";
        writeSquareCase(dir.path(), control, pitchingBoundary);
        const RunResult result = runCase(dir.path(), false);
        ASSERT_EQ(result.status, app::exitSuccess) << result.out << result.err;
        EXPECT_EQ(result.records.size(), 10u);
        EXPECT_EQ(timeFolders(dir.path()), (std::set<std::string>{"0", "0.09", "0.21", "0.3"}));
    }
}

TEST(MoveMeshRun, PitchingOverOnePeriodReturnsToTheInitialMesh)
{
    TempDir dir("period");
    Control control;
    control.endTime = "1";
    control.deltaT = "0.125";
    control.writeInterval = "8";   // only t = 1
    control.writeFormat = "binary";
    writeSquareCase(dir.path(), control, pitchingBoundary);
    const RunResult result = runCase(dir.path(), false);
    ASSERT_EQ(result.status, app::exitSuccess) << result.out << result.err;
    EXPECT_EQ(timeFolders(dir.path()), (std::set<std::string>{"0", "1"}));

    const std::vector<Vector3> points0 = io::readPolyMeshPoints(dir.path() / "constant" / "polyMesh");
    const double meshSize = std::sqrt(1.0 + 1.0 + 0.01);   // bounding-box diagonal
    // A quarter period in, the mesh has really moved (the left side by up to 0.5·0.1 rad) ...
    EXPECT_GT(largestDistance(result.points.at("0.25"), points0), 0.04);
    // ... and after the whole period it is back: the mesh depends only on the boundary's
    // position at that time (total displacement from points0), up to where each step's solve
    // stops (displacementTolerance, default 1e-6 of a node's shortest edge: cells of 0.125 here,
    // the estimate at most 5× low).
    const double solveTolerance = 5e-6 * 0.125;
    EXPECT_LT(largestDistance(result.points.at("1"), points0), solveTolerance);
    EXPECT_LT(largestDistance(io::readPolyMeshPoints(dir.path() / "1"), points0), solveTolerance);
    EXPECT_LT(solveTolerance, 1e-6 * meshSize);
}

TEST(MoveMeshRun, JsonLogHasOneParseableLinePerStep)
{
    TempDir dir("json");
    Control control;
    writeSquareCase(dir.path(), control, pitchingBoundary);
    const RunResult result = runCase(dir.path(), false);
    ASSERT_EQ(result.status, app::exitSuccess) << result.out << result.err;
    const auto lines = readJsonLines(dir.path() / "postProcessing" / "rbmMoveMesh" / "0" / "log.jsonl");
    ASSERT_EQ(lines.size(), 6u);
    const std::vector<std::string> names = {"0.05", "0.1", "0.15", "0.2", "0.25", "0.3"};
    for (std::size_t k = 0; k < lines.size(); ++k) {
        auto line = lines[k];
        SCOPED_TRACE(names[k]);
        EXPECT_EQ(line["step"].number, static_cast<double>(k + 1));
        EXPECT_EQ(line["time"].number, 0.05 * static_cast<double>(k + 1));   // startTime + k deltaT
        EXPECT_EQ(line["timeName"].text, names[k]);
        EXPECT_TRUE(line["converged"].boolean);
        EXPECT_EQ(line["invertedCells"].number, 0);
        EXPECT_GE(line["subSteps"].number, 1);
        EXPECT_GT(line["worstQuality"].number, 0.5);
        EXPECT_LE(line["worstQuality"].number, 1.0);
        EXPECT_GE(line["maxNonOrthogonality"].number, 0.0);
        EXPECT_EQ(line["written"].boolean, k % 2 == 1);   // every 2nd step
        for (const char* key : {"residual", "energy", "reason", "maxSkewness", "wallSeconds"}) {
            EXPECT_EQ(line.count(key), 1u) << key;
        }
    }
    // The readable log has the same steps.
    for (const std::string& name : names) EXPECT_TRUE(contains(result.out, "Time = " + name + " ")) << name;
}

TEST(MoveMeshRun, RigidTranslationOfA3DBoxKeepsEveryCellACube)
{
    // Every boundary point moves by (0.1, 0.05, 0): the RBM optimum moves every point alike,
    // so every cube stays a cube: pyramid ratio 1, non-orthogonality 0.
    TempDir dir("box3D");
    const PolyMesh mesh = makeHexBox(3, 3, 3, Vector3{0, 0, 0}, Vector3{1, 1, 1});
    io::writePolyMesh(dir.path() / "constant" / "polyMesh", mesh, io::FoamWriteOptions{});
    Control control;
    control.endTime = "0.1";
    control.deltaT = "0.1";
    control.writeInterval = "1";
    writeText(dir.path() / "system" / "controlDict", control.text());
    writeText(dir.path() / "constant" / "dynamicMeshDict", dynamicMeshDict());
    writeText(dir.path() / "0" / "pointDisplacement",
              pointDisplacement(R"(".*" { type fixedValue; value uniform (0.1 0.05 0); })"));
    const RunResult result = runCase(dir.path());
    ASSERT_EQ(result.status, app::exitSuccess) << result.out << result.err;
    ASSERT_EQ(result.records.size(), 1u);
    // Cells of 1/3, solved to the default displacementTolerance (1e-6 of a node's shortest edge,
    // the estimate at most 5× low): cubes to that accuracy.
    EXPECT_NEAR(result.records[0].worstQuality, 1.0, 1e-6);
    EXPECT_NEAR(result.records[0].maxNonOrthogonality, 0.0, 1e-3);
    EXPECT_EQ(result.records[0].invertedCells, 0);
    const std::vector<Vector3> written = io::readPolyMeshPoints(dir.path() / "0.1");
    for (std::size_t i = 0; i < written.size(); ++i) {
        EXPECT_NEAR(norm(written[i] - mesh.points[i] - Vector3{0.1, 0.05, 0}), 0.0, 5e-6 / 3.0) << i;
    }
    EXPECT_TRUE(fs::exists(dir.path() / "VTK" / (dir.path().filename().string() + "_0.1.vtu")));
}

TEST(MoveMeshRun, AStepWithInvertedCellsExitsWithOneAndWritesNothingForIt)
{
    TempDir dir("inverting");
    Control control;
    control.deltaT = "0.1";
    control.writeInterval = "1";
    writeSquareCase(dir.path(), control, invertingBoundary, "formulation linearized; subSteps 1;");
    const auto before = listing(dir.path());
    const RunResult result = runCase(dir.path());
    EXPECT_EQ(result.status, app::exitRunFailed) << result.out << result.err;

    // Step 1 (t = 0.1) was valid and written; step 2 (t = 0.2) inverted cells and stopped the run.
    ASSERT_EQ(result.records.size(), 2u);
    EXPECT_EQ(result.records[0].invertedCells, 0);
    EXPECT_TRUE(result.records[0].written);
    EXPECT_GT(result.records[1].invertedCells, 0);
    EXPECT_FALSE(result.records[1].written);
    EXPECT_EQ(timeFolders(dir.path()), (std::set<std::string>{"0", "0.1"}));
    const std::string caseName = dir.path().filename().string();
    EXPECT_FALSE(fs::exists(dir.path() / "VTK" / (caseName + "_0.2.vtu")));
    EXPECT_FALSE(contains(readText(dir.path() / "VTK" / (caseName + ".pvd")), "_0.2.vtu"));
    EXPECT_TRUE(contains(result.err, "time 0.2")) << result.err;
    EXPECT_TRUE(contains(result.err, std::to_string(result.records[1].invertedCells) + " inverted cell"))
        << result.err;
    EXPECT_TRUE(contains(result.err, "Nothing was written for time 0.2")) << result.err;

    // Apart from the earlier step, the VTK series and the log, the case is as it was.
    auto after = listing(dir.path());
    std::erase_if(after, [](const auto& entry) {
        const std::string& name = entry.first;
        return name.rfind("0.1", 0) == 0 || name.rfind("VTK", 0) == 0 || name.rfind("postProcessing", 0) == 0;
    });
    EXPECT_EQ(after, before);
    const auto lines = readJsonLines(dir.path() / "postProcessing" / "rbmMoveMesh" / "0" / "log.jsonl");
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_GT(lines[1].at("invertedCells").number, 0);
    EXPECT_FALSE(lines[1].at("written").boolean);
    expectNoTemporaryFiles(dir.path());
}

TEST(MoveMeshRun, WriteInvalidWritesTheInvalidStepWithAWarningAndGoesOn)
{
    TempDir dir("writeInvalid");
    Control control;
    control.deltaT = "0.1";
    control.writeInterval = "1";
    writeSquareCase(dir.path(), control, invertingBoundary, "formulation linearized; subSteps 1;");
    const RunResult result = runCase(dir.path(), true, true);
    EXPECT_EQ(result.status, app::exitRunFailed) << result.out << result.err;
    ASSERT_EQ(result.records.size(), 3u);
    EXPECT_EQ(timeFolders(dir.path()), (std::set<std::string>{"0", "0.1", "0.2", "0.3"}));
    EXPECT_TRUE(contains(result.err, "WARNING")) << result.err;
    EXPECT_TRUE(contains(result.err, "writing time 0.2")) << result.err;
    EXPECT_TRUE(contains(result.out, "INVALID")) << result.out;
    // What was written is what the solver computed, inverted cells and all.
    EXPECT_LT(largestDistance(io::readPolyMeshPoints(dir.path() / "0.2"), result.points.at("0.2")), 1e-11);
    expectNoTemporaryFiles(dir.path());
}

TEST(MoveMeshRun, VtkFilesHoldTheNodeClassesAndTheCellQualityOfTheStep)
{
    // The inverted step written with -writeInvalid: its cell fields must agree with the step's
    // log figures, which come from the quality report, not from the VTK code.
    TempDir dir("vtkFields");
    Control control;
    control.deltaT = "0.1";
    control.writeInterval = "1";
    control.endTime = "0.2";
    writeSquareCase(dir.path(), control, invertingBoundary, "formulation linearized; subSteps 1;");
    const RunResult result = runCase(dir.path(), true, true);
    ASSERT_EQ(result.records.size(), 2u);
    const std::string caseName = dir.path().filename().string();
    for (std::size_t k = 0; k < 2; ++k) {
        const io::StepLogRecord& record = result.records[k];
        SCOPED_TRACE(record.timeName);
        vtkNew<vtkXMLUnstructuredGridReader> reader;
        const fs::path file = dir.path() / "VTK" / (caseName + "_" + record.timeName + ".vtu");
        reader->SetFileName(file.c_str());
        reader->Update();
        vtkUnstructuredGrid* grid = reader->GetOutput();
        ASSERT_EQ(grid->GetNumberOfCells(), 64);
        ASSERT_EQ(grid->GetNumberOfPoints(), 162);
        vtkDataArray* inverted = grid->GetCellData()->GetArray("inverted");
        vtkDataArray* quality = grid->GetCellData()->GetArray("quality");
        vtkDataArray* nonOrthogonality = grid->GetCellData()->GetArray("nonOrthogonality");
        vtkDataArray* nodeClass = grid->GetPointData()->GetArray("nodeClass");
        vtkDataArray* displacement = grid->GetPointData()->GetArray("pointDisplacement");
        ASSERT_TRUE(inverted && quality && nonOrthogonality && nodeClass && displacement);
        double invertedCount = 0.0;
        double worst = 1e300;
        double largestAngle = 0.0;
        for (vtkIdType c = 0; c < 64; ++c) {
            invertedCount += inverted->GetTuple1(c);
            worst = std::min(worst, quality->GetTuple1(c));
            largestAngle = std::max(largestAngle, nonOrthogonality->GetTuple1(c));
        }
        EXPECT_EQ(invertedCount, static_cast<double>(record.invertedCells));
        EXPECT_NEAR(worst, record.worstQuality, 1e-12);
        EXPECT_NEAR(largestAngle, record.maxNonOrthogonality, 1e-9);
        // Point labels of makeExtruded2D: i + 9 j on the front plane. (0, 0) is on the left
        // side (prescribed beats sliding), (1, 0) on the sliding bottom, (1, 1) inside.
        EXPECT_EQ(nodeClass->GetTuple1(0), 2.0);
        EXPECT_EQ(nodeClass->GetTuple1(1), 1.0);
        EXPECT_EQ(nodeClass->GetTuple1(10), 0.0);
        EXPECT_EQ(nodeClass->GetTuple1(8), 2.0);   // (8, 0): on the fixed right side
        // The left side's displacement is the table's: (0.05, 0) at 0.1, (2, 0) at 0.2.
        EXPECT_NEAR(displacement->GetComponent(0, 0), k == 0 ? 0.05 : 2.0, 1e-12);
        EXPECT_NEAR(grid->GetPoint(0)[0], k == 0 ? 0.05 : 2.0, 1e-12);
    }
    EXPECT_EQ(result.records[0].invertedCells, 0);
    EXPECT_GT(result.records[1].invertedCells, 0);
}

// Bad input: exit status 2, a message naming the problem, the case exactly as it was.
struct BadInput {
    std::string name;
    std::string expectedMessage;
    std::function<void(const fs::path&)> spoil;
};

// GoogleTest prints a parameter with this (the default dumps its bytes into the test name).
void PrintTo(const BadInput& bad, std::ostream* out) { *out << bad.name; }

class MoveMeshRunBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(MoveMeshRunBadInput, ExitsWithTwoAndLeavesTheCaseAsItWas)
{
    const BadInput& bad = GetParam();
    TempDir dir("bad" + bad.name);
    writeSquareCase(dir.path(), Control{}, pitchingBoundary);
    bad.spoil(dir.path());
    const auto before = listing(dir.path());
    const RunResult result = runCase(dir.path());
    EXPECT_EQ(result.status, app::exitBadInput) << result.out << result.err;
    EXPECT_TRUE(contains(result.err, bad.expectedMessage)) << result.err;
    EXPECT_TRUE(contains(result.err, "Nothing was written")) << result.err;
    EXPECT_TRUE(result.records.empty());
    EXPECT_EQ(listing(dir.path()), before);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MoveMeshRunBadInput,
    ::testing::Values(
        BadInput{"DeltaTZero", "deltaT",
                 [](const fs::path& caseDir) {
                     Control control;
                     control.deltaT = "0";
                     writeText(caseDir / "system" / "controlDict", control.text());
                 }},
        BadInput{"UnknownSolver", "Unknown motionSolver type laplacianMotionSolver",
                 [](const fs::path& caseDir) {
                     writeText(caseDir / "constant" / "dynamicMeshDict", dynamicMeshDict("", "laplacianMotionSolver"));
                 }},
        BadInput{"UnknownPatch", "wing",
                 [](const fs::path& caseDir) {
                     writeText(caseDir / "0" / "pointDisplacement",
                               pointDisplacement(pitchingBoundary + "\n    wing { type fixedValue; value uniform (0 0 0); }"));
                 }},
        BadInput{"UnknownCoefficient", "subStep",
                 [](const fs::path& caseDir) {
                     writeText(caseDir / "constant" / "dynamicMeshDict", dynamicMeshDict("subStep 4;"));
                 }},
        BadInput{"MissingPointDisplacement", "pointDisplacement",
                 [](const fs::path& caseDir) { fs::remove(caseDir / "0" / "pointDisplacement"); }},
        BadInput{"MissingDynamicMeshDict", "dynamicMeshDict",
                 [](const fs::path& caseDir) { fs::remove(caseDir / "constant" / "dynamicMeshDict"); }}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

TEST(MoveMeshRun, RestartFromTheLatestTimeContinuesTheRun)
{
    // Run A: 0 → 0.2, then restarted from its latest time to 0.4. Run B: 0 → 0.4 at once.
    // A restart has none of the solver's history (the secant's last results, the last Newton
    // corrections), so the two runs reach each step's minimum along different paths: compared
    // where both go on to round-off (displacementTolerance 0; with the default they stop within
    // a millionth of the shortest edges, differently).
    const std::string toRoundOff = "displacementTolerance 0;";
    TempDir a("restartA");
    TempDir b("restartB");
    Control control;
    control.deltaT = "0.1";
    control.writeInterval = "1";
    control.endTime = "0.2";
    writeSquareCase(a.path(), control, pitchingBoundary, toRoundOff);
    ASSERT_EQ(runCase(a.path(), false).status, app::exitSuccess);
    control.startFrom = "latestTime";
    control.endTime = "0.4";
    writeText(a.path() / "system" / "controlDict", control.text());
    const RunResult restarted = runCase(a.path(), false);
    ASSERT_EQ(restarted.status, app::exitSuccess) << restarted.out << restarted.err;
    EXPECT_TRUE(contains(restarted.out, "Warm start    : 0.2/pointDisplacement")) << restarted.out;
    ASSERT_EQ(restarted.records.size(), 2u);
    EXPECT_EQ(restarted.records[0].timeName, "0.3");
    EXPECT_EQ(timeFolders(a.path()), (std::set<std::string>{"0", "0.1", "0.2", "0.3", "0.4"}));
    EXPECT_EQ(readJsonLines(a.path() / "postProcessing" / "rbmMoveMesh" / "0.2" / "log.jsonl").size(), 2u);

    control.startFrom = "startTime";
    writeSquareCase(b.path(), control, pitchingBoundary, toRoundOff);
    const RunResult straight = runCase(b.path(), false);
    ASSERT_EQ(straight.status, app::exitSuccess) << straight.out << straight.err;
    EXPECT_LT(largestDistance(restarted.points.at("0.4"), straight.points.at("0.4")), 1e-9);
}

TEST(MoveMeshRun, TimeNamesGainDigitsWhenNeededAndConditionsComeFromTheEarliestField)
{
    // startTime 1 has no folder: the boundary conditions come from 0/pointDisplacement. With
    // deltaT 1e-7, 1.0000001 has the 6-digit name "1" (|1 − 1.0000001| = 1e-7 is more than
    // OpenFOAM's tolerance max(min(1e-6, 0.1 deltaT), 1e-15) = 1e-8), 7 digits still give "1",
    // 8 give "1.0000001": OpenFOAM raises timePrecision to 8.
    TempDir dir("precision");
    Control control;
    control.startTime = "1";
    control.endTime = "1.0000002";
    control.deltaT = "1e-07";
    control.writeInterval = "1";
    writeSquareCase(dir.path(), control, pitchingBoundary);
    const RunResult result = runCase(dir.path(), false);
    ASSERT_EQ(result.status, app::exitSuccess) << result.out << result.err;
    EXPECT_TRUE(contains(result.out, "Boundary      : 0/pointDisplacement")) << result.out;
    EXPECT_TRUE(contains(result.err, "Increased the timePrecision from 6 to 8")) << result.err;
    EXPECT_EQ(timeFolders(dir.path()), (std::set<std::string>{"0", "1.0000001", "1.0000002"}));
    EXPECT_TRUE(fs::exists(dir.path() / "postProcessing" / "rbmMoveMesh" / "1" / "log.jsonl"));
}

TEST(MoveMeshRun, ParallelOptionOnOneProcessRunsNormally)
{
    TempDir dir("parallel");
    Control control;
    control.endTime = "0.05";
    writeSquareCase(dir.path(), control, pitchingBoundary);
    const std::string caseArgument = dir.path().string();
    const char* argv[] = {"rbmMoveMesh", "-parallel", "-noVTK", "-case", caseArgument.c_str(), nullptr};
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(app::moveMeshMain(5, const_cast<char**>(argv), out, err), app::exitSuccess) << out.str() << err.str();
    EXPECT_TRUE(contains(out.str(), "Time = 0.05 ")) << out.str();
}

// The left side turns by 0.3 rad at t = 0.05 (about its midpoint): Newton needs several
// iterations from the linearized start, a Krylov method without preconditioner many.
const std::string turningBoundary = R"foam(
    left
    {
        type            angularOscillatingDisplacement;
        axis            (0 0 1);
        origin          (0 0.5 0);
        angle0          0;
        amplitude       0.3;
        omega           31.41592653589793;
        value           uniform (0 0 0);
    }
    right           { type fixedValue; value uniform (0 0 0); }
    "(top|bottom)"  { type zeroGradient; }
    frontAndBack    { type empty; }
)foam";

struct FailingSolve {
    std::string name;
    std::string coefficients;        // rigidBodyMotionSolverCoeffs
    std::string boundary;            // boundaryField
    std::vector<std::string> expected;  // in the message
    bool writeInvalid = false;
};

void PrintTo(const FailingSolve& failing, std::ostream* out) { *out << failing.name; }

class MoveMeshRunFailingSolve : public ::testing::TestWithParam<FailingSolve> {};

// The run stops at the first step with exit status 1 and PETSc's reason in the message;
// nothing is written for the step: no time folder, no .vtu, constant/, system/ and 0/ as
// they were (only the run's log and the initial mesh's VTK file are new).
TEST_P(MoveMeshRunFailingSolve, StopsWithPetscsReasonAndWritesNothingForTheStep)
{
    const FailingSolve& failing = GetParam();
    TempDir dir("failing" + failing.name);
    Control control;
    control.endTime = "0.1";
    control.writeInterval = "1";
    writeSquareCase(dir.path(), control, failing.boundary, failing.coefficients);
    const auto before = listing(dir.path());
    const RunResult result = runCase(dir.path(), true, failing.writeInvalid);
    EXPECT_EQ(result.status, app::exitRunFailed) << result.out << result.err;
    for (const std::string& part : failing.expected) EXPECT_TRUE(contains(result.err, part)) << part << "\n" << result.err;
    EXPECT_TRUE(contains(result.err, "rbmMoveMesh: time 0.05: ")) << result.err;
    EXPECT_TRUE(contains(result.err, "Nothing was written for time 0.05")) << result.err;
    ASSERT_EQ(result.records.size(), 1u);
    EXPECT_FALSE(result.records[0].converged);
    EXPECT_FALSE(result.records[0].written);
    EXPECT_EQ(timeFolders(dir.path()), std::set<std::string>{"0"});
    auto after = listing(dir.path());
    const std::string caseName = dir.path().filename().string();
    EXPECT_TRUE(after.count("VTK/" + caseName + "_0.vtu"));
    EXPECT_FALSE(after.count("VTK/" + caseName + "_0.05.vtu"));
    std::erase_if(after, [](const auto& entry) {
        return entry.first.rfind("VTK", 0) == 0 || entry.first.rfind("postProcessing", 0) == 0;
    });
    EXPECT_EQ(after, before);
    // The log records the failed step with the reason.
    const auto lines = readJsonLines(dir.path() / "postProcessing" / "rbmMoveMesh" / "0" / "log.jsonl");
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_FALSE(lines[0].at("converged").boolean);
    EXPECT_TRUE(contains(lines[0].at("reason").text, failing.expected.front())) << lines[0].at("reason").text;
    expectNoTemporaryFiles(dir.path());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MoveMeshRunFailingSolve,
    ::testing::Values(
        // SNES stopped after one Newton step.
        FailingSolve{"NewtonIterationLimit", "algorithm newton; petscOptions \"-rbm_newton_snes_max_it 1\";",
                     turningBoundary, {"DIVERGED_MAX_IT", "the motion solver did not converge"}},
        // The default (reduced Newton) stopped after one step.
        FailingSolve{"ReducedNewtonIterationLimit", "maxIterations 1;", turningBoundary,
                     {"DIVERGED_MAX_IT", "the motion solver did not converge"}},
        // Newton's linear solves fail: CG without preconditioner, 2 iterations.
        FailingSolve{"NewtonLinearSolveFails",
                     "algorithm newton; "
                     "petscOptions \"-rbm_newton_ksp_type cg -rbm_newton_pc_type none -rbm_newton_ksp_max_it 2\";",
                     turningBoundary, {"DIVERGED_LINEAR_SOLVE", "the motion solver did not converge"}},
        // The linearized system with CG, no preconditioner, 2 iterations.
        FailingSolve{"LinearizedKrylovIterationLimit",
                     "formulation linearized; subSteps 1; petscOptions \"-rbm_linearized_ksp_type cg "
                     "-rbm_linearized_pc_type none -rbm_linearized_ksp_max_it 2\";",
                     turningBoundary, {"DIVERGED_ITS", "did not converge"}},
        // A boundary displacement of 1e300: the energy overflows, SNES reports the NaN/Inf
        // norm; not written even with -writeInvalid.
        FailingSolve{"NewtonOverflow", "algorithm newton;", R"foam(
    left            { type fixedValue; value uniform (1e300 0 0); }
    right           { type fixedValue; value uniform (0 0 0); }
    "(top|bottom)"  { type zeroGradient; }
    frontAndBack    { type empty; }
)foam",
                     {"DIVERGED_FNORM_NAN", "a residual of inf", "not even with -writeInvalid"}, true},
        FailingSolve{"ReducedNewtonOverflow", "", R"foam(
    left            { type fixedValue; value uniform (1e300 0 0); }
    right           { type fixedValue; value uniform (0 0 0); }
    "(top|bottom)"  { type zeroGradient; }
    frontAndBack    { type empty; }
)foam",
                     {"DIVERGED_FNORM_NAN", "NaN or infinite displacement", "not even with -writeInvalid"}, true},
        // The linearized solve of the same: a direct factorisation "converges" (CONVERGED_ITS)
        // to an infinite residual.
        FailingSolve{"LinearizedOverflow", "formulation linearized; subSteps 1;", R"foam(
    left            { type fixedValue; value uniform (1e300 0 0); }
    right           { type fixedValue; value uniform (0 0 0); }
    "(top|bottom)"  { type zeroGradient; }
    frontAndBack    { type empty; }
)foam",
                     {"residual of inf", "not even with -writeInvalid"}, true}),
    [](const ::testing::TestParamInfo<FailingSolve>& info) { return info.param.name; });

TEST(MoveMeshRun, ABoundaryConditionGivingAnInfiniteDisplacementIsBadInputNamingThePatch)
{
    // uniformFixedValue polynomial: x = 1e308 t², infinite at t = 2.
    TempDir dir("infiniteBoundary");
    Control control;
    control.deltaT = "2";
    control.endTime = "2";
    control.writeInterval = "1";
    writeSquareCase(dir.path(), control, R"foam(
    left
    {
        type            uniformFixedValue;
        uniformValue    polynomial (((1e308 0 0) (2 0 0)));
        value           uniform (0 0 0);
    }
    right           { type fixedValue; value uniform (0 0 0); }
    "(top|bottom)"  { type zeroGradient; }
    frontAndBack    { type empty; }
)foam");
    const auto before = listing(dir.path());
    const RunResult result = runCase(dir.path(), false, true);
    EXPECT_EQ(result.status, app::exitBadInput) << result.out << result.err;
    // 0/pointDisplacement, the line of the patch's entry (header 9 lines, then 4), the patch.
    const std::string file = (dir.path() / "0" / "pointDisplacement").string();
    EXPECT_TRUE(contains(result.err, file + ":15: the boundary condition of patch left (type uniformFixedValue) gives "
                                            "the displacement (inf 0 0) at time 2"))
        << result.err;
    EXPECT_TRUE(contains(result.err, "expected finite numbers")) << result.err;
    EXPECT_TRUE(contains(result.err, "Nothing was written for this time")) << result.err;
    EXPECT_TRUE(result.records.empty());
    auto after = listing(dir.path());
    std::erase_if(after, [](const auto& entry) { return entry.first.rfind("postProcessing", 0) == 0; });
    EXPECT_EQ(after, before);
}

// Sets an environment variable for one scope.
class ScopedEnvironment {
public:
    ScopedEnvironment(const char* name, const char* value) : name_(name)
    {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value, 1);
    }
    ~ScopedEnvironment()
    {
        if (old_) ::setenv(name_.c_str(), old_->c_str(), 1);
        else ::unsetenv(name_.c_str());
    }

private:
    std::string name_;
    std::optional<std::string> old_;
};

TEST(MoveMeshRun, ALinearized2DSolveWhoseFactorisationDoesNotFitRunsMatrixFree)
{
    // The 8 × 8 square, coupled linearized: the direct estimate is 189 × 130 × log2(189) bytes
    // = 181.4 KiB; matrix-free needs 40 bytes a block and 400 a node, 43.2 KiB.
    const std::string linearized = "coupling coupled; formulation linearized; subSteps 1;";
    TempDir reference("memoryReference");
    writeSquareCase(reference.path(), Control{}, pitchingBoundary, linearized);
    const RunResult expected = runCase(reference.path(), false);
    ASSERT_EQ(expected.status, app::exitSuccess) << expected.err;
    EXPECT_FALSE(contains(expected.out, "Memory        :"));

    TempDir dir("memoryFallback");
    writeSquareCase(dir.path(), Control{}, pitchingBoundary, linearized);
    const ScopedEnvironment limit("RBM_AVAILABLE_MEMORY_MB", "0.1");   // 102.4 KiB
    const RunResult result = runCase(dir.path(), false);
    ASSERT_EQ(result.status, app::exitSuccess) << result.out << result.err;
    EXPECT_TRUE(contains(result.out, "Memory        : the direct factorisation would need about 181.4 KiB, only "
                                     "102.4 KiB is available (RBM_AVAILABLE_MEMORY_MB): solving matrix-free "
                                     "(linearSolver matrixFree, about 43.2 KiB)"))
        << result.out;
    // The same minimum: every written time within the Krylov tolerance of the direct run.
    ASSERT_EQ(result.points.size(), expected.points.size());
    double largest = 0.0;
    for (const auto& [time, points] : expected.points)
        for (std::size_t p = 0; p < points.size(); ++p) largest = std::max(largest, norm(result.points.at(time)[p] - points[p]));
    EXPECT_LT(largest, 1e-9);

    // The solver the run really used.
    TempDir observed("memoryFallbackObserved");
    writeSquareCase(observed.path(), Control{}, pitchingBoundary, linearized);
    app::MoveMeshOptions options;
    options.caseDirectory = observed.path();
    options.writeVtk = false;
    std::ostringstream out, err;
    std::optional<motion::LinearSolverKind> used;
    EXPECT_EQ(app::runMoveMesh(options, out, err,
                               [&](const app::StepObservation& step) {
                                   if (const auto* rbm = dynamic_cast<const motion::RigidBodyMotionSolver*>(&step.solver))
                                       used = rbm->options().linearSolver;
                               }),
              app::exitSuccess);
    EXPECT_EQ(used, motion::LinearSolverKind::matrixFree);

    // Asked for explicitly, the direct solver is not replaced: the run stops and names the way out.
    TempDir forced("memoryForcedDirect");
    writeSquareCase(forced.path(), Control{}, pitchingBoundary, linearized + " linearSolver direct;");
    const RunResult stopped = runCase(forced.path(), false);
    EXPECT_EQ(stopped.status, app::exitRunFailed);
    EXPECT_TRUE(contains(stopped.err, "With 'linearSolver matrixFree;' in rigidBodyMotionSolverCoeffs")) << stopped.err;
}

TEST(MoveMeshRun, ASolveLargerThanTheMemoryStopsBeforeAssemblingAndSaysHowMuchItNeeds)
{
    // The 8 × 8 square, coupled Newton (direct in 2D): 81 planar nodes, the 18 on the left and
    // right sides prescribed, 63 unknown, 189 rows. Estimate (MemoryEstimate.hpp):
    // 2.3 × 189 × 130 × log2(189) = 427 350 bytes = 417.3 KiB.
    TempDir dir("memory");
    writeSquareCase(dir.path(), Control{}, pitchingBoundary, "algorithm newton;");
    const auto before = listing(dir.path());
    {
        const ScopedEnvironment limit("RBM_AVAILABLE_MEMORY_MB", "0.25");
        const RunResult result = runCase(dir.path());
        EXPECT_EQ(result.status, app::exitRunFailed) << result.out << result.err;
        EXPECT_TRUE(contains(result.err, "the solve needs about 417.3 KiB of memory, but only 256.0 KiB is available "
                                         "(RBM_AVAILABLE_MEMORY_MB)"))
            << result.err;
        EXPECT_TRUE(contains(result.err, "direct factorisation of 189 unknowns (63 nodes in 2D)")) << result.err;
        EXPECT_TRUE(contains(result.err, "Nothing was written.")) << result.err;
        EXPECT_TRUE(result.records.empty());
        EXPECT_EQ(listing(dir.path()), before);
    }
    {
        const ScopedEnvironment limit("RBM_AVAILABLE_MEMORY_MB", "0.5");   // 512 KiB: enough
        const RunResult result = runCase(dir.path(), false);
        EXPECT_EQ(result.status, app::exitSuccess) << result.out << result.err;
    }
    {
        const ScopedEnvironment limit("RBM_AVAILABLE_MEMORY_MB", "plenty");
        const RunResult result = runCase(dir.path(), false);
        EXPECT_EQ(result.status, app::exitBadInput) << result.out << result.err;
        EXPECT_TRUE(contains(result.err, "RBM_AVAILABLE_MEMORY_MB: expected a number of MiB")) << result.err;
    }
}

} // namespace
