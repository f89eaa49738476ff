// rbmMoveMesh -parallel on decomposed cases (apps/DecomposedMoveMeshRun.hpp), the built program
// under mpiexec against the same program's serial run of the undecomposed case. The fixtures
// (tests/data/decomposedTwist/np2, np4; tests/data/makeDecomposedTwistFixture.sh) are a column
// whose top turns 20° in two steps, its sides zeroGradient (sliding, the vertical edges on
// lines), cut by decomposePar along staircases through the sides, the edges and the top.
//
//  - Every point of every processor folder ends near the serial run's point (pointProcAddressing),
//    at both written times, with the same validity and the same worst quality, non-orthogonality
//    (its worst faces lie between processors) and inverted cells in the step lines: with the defaults within 2.5e-6 of its shortest edge (each solve stops
//    within displacementTolerance 1e-6 of the minimum, along a different path), and with
//    displacementTolerance 1e-10 within 1e-8 (the same minimum).
//  - Bad input on one processor stops every rank with exit status 2, naming that processor's
//    file, and writes nothing; so does a rank count that is not the processor folder count.

#include "ScratchFiles.hpp"
#include "ShortestEdges.hpp"

#include "PolyMeshReader.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace rbm;
using rbm::test::TempDir;

struct ProgramRun {
    int exitStatus = -1;
    std::string output;  // standard output and error
};

// `command` through the shell, its output and error captured.
ProgramRun runCommand(const std::string& command)
{
    ProgramRun run;
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return run;
    char buffer[4096];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) run.output.append(buffer, n);
    const int status = ::pclose(pipe);
    run.exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

ProgramRun runDecomposed(const fs::path& caseDir, int ranks)
{
    return runCommand(std::string(RBM_MPIEXEC) + " --allow-run-as-root --oversubscribe -n " + std::to_string(ranks) +
                      " " + RBM_MOVE_MESH + " -case " + caseDir.string() + " -parallel -noVTK");
}

ProgramRun runSerial(const fs::path& caseDir) { return runCommand(std::string(RBM_MOVE_MESH) + " -case " + caseDir.string() + " -noVTK"); }

// The worst quality, the max non-orthogonality (its faces between processors included) and the
// inverted cells of each step line.
std::vector<std::string> qualityFigures(const std::string& output)
{
    std::vector<std::string> figures;
    const std::regex line(R"(Time = \S+.*worst quality\s+(\S+)\s+max non-orthogonality\s+(\S+)\s+inverted (\d+))");
    for (std::sregex_iterator it(output.begin(), output.end(), line), end; it != end; ++it)
        figures.push_back((*it)[1].str() + " / " + (*it)[2].str() + "° / " + (*it)[3].str());
    return figures;
}

fs::path fixture(int ranks) { return fs::path(RBM_TEST_DATA_DIR) / "decomposedTwist" / ("np" + std::to_string(ranks)); }

// `coefficients`: appended to constant/dynamicMeshDict; `bound`: the largest difference allowed,
// relative to each point's shortest edge.
void checkAgainstSerial(int ranks, const std::string& coefficients, double bound)
{
    const TempDir work("twist" + std::to_string(ranks));
    const fs::path caseDir = work.path() / "case";
    fs::copy(fixture(ranks), caseDir, fs::copy_options::recursive);
    const fs::path dynamicMeshDict = caseDir / "constant" / "dynamicMeshDict";
    rbm::test::writeText(dynamicMeshDict, rbm::test::readText(dynamicMeshDict) + coefficients);
    const ProgramRun decomposed = runDecomposed(caseDir, ranks);
    ASSERT_EQ(decomposed.exitStatus, 0) << decomposed.output;
    const ProgramRun serial = runSerial(caseDir);
    ASSERT_EQ(serial.exitStatus, 0) << serial.output;
    EXPECT_EQ(qualityFigures(decomposed.output), qualityFigures(serial.output)) << decomposed.output << serial.output;
    ASSERT_EQ(qualityFigures(serial.output).size(), 2u) << serial.output;
    // The same solver described alike; in 3D `stiffening auto` is the single exponent.
    const std::string stiffening =
        "stiffening auto = power 0.8 inverseDistance (bottom lid top xMin xMax yMin yMax) while every prescribed "
        "patch moves rigidly, scaling auto = rigid";
    EXPECT_NE(serial.output.find(stiffening), std::string::npos) << serial.output;
    EXPECT_NE(decomposed.output.find(stiffening), std::string::npos) << decomposed.output;

    const PolyMesh whole = io::readPolyMesh(caseDir / "constant" / "polyMesh");
    const std::vector<double> shortest = rbm::test::shortestEdgeAtEachPoint(whole);
    for (const char* time : {"0.5", "1"}) {
        const std::vector<Vector3> expected = io::readPolyMeshPoints(caseDir / time);
        double largestMiss = 0.0, largestMove = 0.0;
        std::size_t compared = 0;
        for (int p = 0; p < ranks; ++p) {
            const fs::path processor = caseDir / ("processor" + std::to_string(p));
            const std::vector<Vector3> moved = io::readPolyMeshPoints(processor / time);
            const std::vector<Label> global = io::readLabelListFile(
                processor / "constant" / "polyMesh" / "pointProcAddressing", "pointProcAddressing", moved.size());
            ASSERT_EQ(global.size(), moved.size());
            for (std::size_t k = 0; k < moved.size(); ++k) {
                const Label g = global[k];
                largestMiss = std::max(largestMiss, norm(moved[k] - expected[g]) / shortest[g]);
                largestMove = std::max(largestMove, norm(expected[g] - whole.points[g]) / shortest[g]);
                ++compared;
            }
        }
        EXPECT_GE(compared, whole.points.size()) << "every point is in some processor folder";
        EXPECT_LT(largestMiss, bound) << "time " << time;
        EXPECT_GT(largestMove, 1.0) << "the mesh moved by more than a cell at time " << time;
    }
}

TEST(DecomposedMoveMeshRun, TwoProcessorsMoveAsTheSerialRun) { checkAgainstSerial(2, "", 2.5e-6); }
TEST(DecomposedMoveMeshRun, FourProcessorsMoveAsTheSerialRun) { checkAgainstSerial(4, "", 2.5e-6); }

const std::string tightSolves = "rigidBodyMotionSolverCoeffs { displacementTolerance 1e-10; }\n";
TEST(DecomposedMoveMeshRun, TwoProcessorsFindTheSerialRunsMinimum) { checkAgainstSerial(2, tightSolves, 1e-8); }
TEST(DecomposedMoveMeshRun, FourProcessorsFindTheSerialRunsMinimum) { checkAgainstSerial(4, tightSolves, 1e-8); }

TEST(DecomposedMoveMeshRun, BadInputOnOneProcessorStopsEveryRankAndWritesNothing)
{
    const TempDir work("badProcessor");
    const fs::path caseDir = work.path() / "case";
    fs::copy(fixture(4), caseDir, fs::copy_options::recursive);
    const fs::path broken = caseDir / "processor2" / "0" / "pointDisplacement";
    std::string text = rbm::test::readText(broken);
    text.replace(text.find("angularOscillatingDisplacement"), 30, "angularOscilatingDisplacement");
    rbm::test::writeText(broken, text);
    const ProgramRun run = runDecomposed(caseDir, 4);
    EXPECT_EQ(run.exitStatus, 2) << run.output;
    EXPECT_NE(run.output.find("[processor2]"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("angularOscilatingDisplacement"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("processor2/0/pointDisplacement"), std::string::npos) << run.output;
    for (int p = 0; p < 4; ++p)
        for (const char* time : {"0.5", "1"})
            EXPECT_FALSE(fs::exists(caseDir / ("processor" + std::to_string(p)) / time)) << p << " " << time;
}

// Each "patch P ... leave its plane by up to D" warning: P at time T, and D.
std::vector<std::pair<std::string, double>> planeDepartures(const std::string& output)
{
    std::vector<std::pair<std::string, double>> departures;
    const std::regex line(R"(warning: time (\S+): patch (\S+) \(in floatingPatches\) was planar; its points now leave its plane by up to (\S+))");
    for (std::sregex_iterator it(output.begin(), output.end(), line), end; it != end; ++it)
        departures.emplace_back((*it)[1].str() + " " + (*it)[2].str(), std::stod((*it)[3].str()));
    return departures;
}

// The floating sides leave their planes; the decomposed run says so as the serial one does,
// the distance taken over all the ranks' points.
TEST(DecomposedMoveMeshRun, FloatingPlanesLeftAreWarnedAsInASerialRun)
{
    const TempDir work("floating");
    const fs::path caseDir = work.path() / "case";
    fs::copy(fixture(4), caseDir, fs::copy_options::recursive);
    const fs::path dynamicMeshDict = caseDir / "constant" / "dynamicMeshDict";
    rbm::test::writeText(dynamicMeshDict, rbm::test::readText(dynamicMeshDict) +
                                              "rigidBodyMotionSolverCoeffs { floatingPatches (xMin xMax yMin yMax); }\n");
    const ProgramRun decomposed = runDecomposed(caseDir, 4);
    ASSERT_EQ(decomposed.exitStatus, 0) << decomposed.output;
    const ProgramRun serial = runSerial(caseDir);
    ASSERT_EQ(serial.exitStatus, 0) << serial.output;
    const auto expected = planeDepartures(serial.output);
    const auto found = planeDepartures(decomposed.output);
    ASSERT_EQ(expected.size(), 8u) << serial.output;  // four sides at two times
    ASSERT_EQ(found.size(), expected.size()) << decomposed.output;
    for (std::size_t k = 0; k < expected.size(); ++k) {
        EXPECT_EQ(found[k].first, expected[k].first);
        EXPECT_NEAR(found[k].second, expected[k].second, 1e-4 * expected[k].second) << expected[k].first;
    }
}

TEST(DecomposedMoveMeshRun, SubStepsAreRefusedNamingTheDictionary)
{
    const TempDir work("subSteps");
    const fs::path caseDir = work.path() / "case";
    fs::copy(fixture(2), caseDir, fs::copy_options::recursive);
    const fs::path dynamicMeshDict = caseDir / "constant" / "dynamicMeshDict";
    rbm::test::writeText(dynamicMeshDict,
                         rbm::test::readText(dynamicMeshDict) + "rigidBodyMotionSolverCoeffs { subSteps 4; }\n");
    const ProgramRun run = runDecomposed(caseDir, 2);
    EXPECT_EQ(run.exitStatus, 2) << run.output;
    EXPECT_NE(run.output.find("subSteps 4 is not applied on a decomposed case"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("dynamicMeshDict"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(caseDir / "processor0" / "0.5"));
}

TEST(DecomposedMoveMeshRun, RanksMustMatchTheProcessorFolders)
{
    const TempDir work("rankCount");
    const fs::path caseDir = work.path() / "case";
    fs::copy(fixture(4), caseDir, fs::copy_options::recursive);
    const ProgramRun run = runDecomposed(caseDir, 2);
    EXPECT_EQ(run.exitStatus, 2) << run.output;
    EXPECT_NE(run.output.find("4 processor folders but 2 MPI ranks"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(caseDir / "processor0" / "0.5"));
}

} // namespace
