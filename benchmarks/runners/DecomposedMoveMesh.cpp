#include "DecomposedMoveMesh.hpp"

#include "BenchmarkCases.hpp"
#include "CaseFiles.hpp"
#include "ChildTask.hpp"
#include "Decomposition.hpp"
#include "MpiRun.hpp"
#include "Process.hpp"
#include "RbmMoveMeshRun.hpp"

#include <cstdlib>
#include <fstream>

namespace rbm::benchmark {

namespace {

// The number after `key` on rbmMoveMesh's step line ("Time = 1  sub-steps 1  iterations 4 ...
// max non-orthogonality  18.83  inverted 0  wall ...").
double stepLineNumber(const std::string& line, const std::string& key)
{
    const std::size_t at = line.find(key);
    return at == std::string::npos ? nan : std::strtod(line.c_str() + at + key.size(), nullptr);
}

void addStepLine(Record& record, const fs::path& log)
{
    std::ifstream in(log);
    std::string line, step;
    while (std::getline(in, line))
        if (line.rfind("Time = ", 0) == 0 && line.find("max non-orthogonality") != std::string::npos) step = line;
    if (step.empty()) return;
    record.set("rbmLogLine", step);
    record.set("rbmLogIterations", stepLineNumber(step, "iterations"));
    record.set("rbmLogWorstQuality", stepLineNumber(step, "worst quality"));
    record.set("rbmLogMaxNonOrthogonality", stepLineNumber(step, "max non-orthogonality"));
    record.set("rbmLogInvertedCells", stepLineNumber(step, "inverted"));
    record.set("rbmLogStepWallSeconds", stepLineNumber(step, "wall"));
}

void check(Record& record, const DecomposedRunInput& input, const fs::path& caseDir, int ranks,
           const fs::path& serialCase, const std::string& prefix)
{
    Record identity;
    const Record result =
        runChild({"decomposedCheck", input.polyMeshSource.string(), caseDir.string(), std::to_string(ranks),
                  serialCase.string(), prefix},
                 input.logDir, caseDir.parent_path().filename().string() + "-" + prefix + "-check", identity);
    if (result.flag("failed")) record.set(prefix + "CheckError", result.text("error"));
    else record.merge(result);
}

} // namespace

Record runDecomposedMoveMesh(const OpenFoam& openfoam, const DecomposedRunInput& input, const fs::path& dir, int ranks)
{
    Record record;
    record.set("case", input.caseName);
    record.set("ranks", ranks);
    record.set("decomposition", "simple " + simpleSplitText(ranks));
    const fs::path rbmDir = dir / "rbm";
    const fs::path openfoamDir = dir / "openfoam";
    const std::string boundaryField = decomposableBoundaryField(input.boundaryField);
    const std::vector<std::string> floating = floatingPatchNames(input.caseName, input.polyMeshSource);
    writeMotionCase(rbmDir, input.polyMeshSource, "rbmMoveMesh", rbmDynamicMeshDict("reducedNewton", floating),
                    boundaryField, 1);
    record.merge(runDecomposePar(openfoam, rbmDir, ranks));
    if (record.number("decomposeParExitCode") != 0) return record;
    writeMotionCase(openfoamDir, input.polyMeshSource, "moveMesh",
                    laplacianDynamicMeshDict(input.diffusivity, caseMotion(input.caseName).movingPatch), boundaryField, 1);
    copyProcessorFolders(rbmDir, openfoamDir, ranks);

    const MpiRunResult rbm = runMpi(ranks, {input.rbmMoveMesh.string(), "-case", rbmDir.string(), "-parallel", "-noVTK"},
                                    rbmDir / "log.rbmMoveMesh", rbmDir / "log.rbmMoveMesh.stderr");
    addMpiRun(record, "rbm", rbm);
    addStepLine(record, rbmDir / "log.rbmMoveMesh");
    if (rbm.exitCode != 0) record.set("rbmError", readTail(rbmDir / "log.rbmMoveMesh.stderr", 300));
    else check(record, input, rbmDir, ranks, input.serialRbmCase, "rbm");

    const MpiRunResult foam = runMpi(ranks, {"/usr/bin/moveMesh", "-case", openfoamDir.string(), "-parallel"},
                                     openfoamDir / "log.moveMesh", openfoamDir / "log.moveMesh.stderr",
                                     &openfoam.environment);
    addMpiRun(record, "openfoam", foam);
    if (foam.exitCode != 0) record.set("openfoamError", readTail(openfoamDir / "log.moveMesh.stderr", 300));
    else check(record, input, openfoamDir, ranks, {}, "openfoam");
    return record;
}

} // namespace rbm::benchmark
