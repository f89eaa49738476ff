#include "RbmMoveMeshRun.hpp"

#include "BenchmarkCases.hpp"
#include "CaseFiles.hpp"
#include "PolyMeshReader.hpp"
#include "Process.hpp"
#include "QualityFields.hpp"
#include "Variants.hpp"

namespace rbm::benchmark {

std::string rbmDynamicMeshDict(const std::string& variant, const std::vector<std::string>& floatingPatches)
{
    std::string floating;
    for (const std::string& name : floatingPatches) floating += (floating.empty() ? "" : " ") + name;
    return "dynamicFvMesh dynamicMotionSolverFvMesh;\nmotionSolver rigidBodyMotionSolver;\n"
           "rigidBodyMotionSolverCoeffs\n{\n    " +
           solverCoefficients(variant) + (floating.empty() ? "" : "\n    floatingPatches (" + floating + ");") + "\n}\n";
}

std::vector<std::string> floatingPatchNames(const std::string& caseName, const fs::path& polyMeshSource)
{
    std::vector<std::string> names;
    for (const Patch& patch : io::readBoundaryFile(polyMeshSource / "boundary"))
        if (patchRole(caseName, patch) == PatchRole::free) names.push_back(patch.name);
    return names;
}

const std::vector<std::string>& fastMpiStartEnvironment()
{
    static const std::vector<std::string> settings{"OMPI_MCA_ess_singleton_isolated=1", "OMPI_MCA_pml=ob1",
                                                   "OMPI_MCA_btl=self,vader"};
    return settings;
}

std::string fastMpiStartText()
{
    std::string text;
    for (const std::string& setting : fastMpiStartEnvironment()) text += (text.empty() ? "`" : " `") + setting + "`";
    return text;
}

Record runRbmMoveMesh(const fs::path& program, const std::string& caseName, const fs::path& polyMeshSource,
                      const fs::path& dir, const std::string& variant, const std::string& boundaryField, int steps,
                      bool fastMpiStart)
{
    Record record;
    record.set("program", "rbmMoveMesh");
    record.set("case", caseName);
    record.set("variant", variant + (fastMpiStart ? " + fast MPI start" : ""));
    if (fastMpiStart) record.set("environment", "OMPI_MCA_ess_singleton_isolated=1 OMPI_MCA_pml=ob1 OMPI_MCA_btl=self,vader");
    record.set("coefficients", solverCoefficients(variant));
    record.set("steps", steps);
    const std::vector<std::string> floating = floatingPatchNames(caseName, polyMeshSource);
    std::string floatingText;
    for (const std::string& name : floating) floatingText += (floatingText.empty() ? "" : " ") + name;
    if (!floatingText.empty()) record.set("floatingPatches", floatingText);
    writeMotionCase(dir, polyMeshSource, "rbmMoveMesh", rbmDynamicMeshDict(variant, floating), boundaryField, steps);
    const std::vector<std::string> environment = environmentWith(fastMpiStartEnvironment());
    const ProcessResult result = runProcess({program.string(), "-case", dir.string(), "-noVTK"},
                                            dir / "log.rbmMoveMesh.stderr", fastMpiStart ? &environment : nullptr,
                                            dir / "log.rbmMoveMesh");
    record.set("wallSeconds", result.wallSeconds);
    record.set("cpuSeconds", result.userSeconds + result.systemSeconds);
    record.set("peakMemoryMiB", result.maxRssMiB);
    record.set("exitCode", result.exitCode);
    if (result.exitCode != 0) record.set("error", readTail(dir / "log.rbmMoveMesh.stderr", 300));
    if (steps == 1) addResultQuality(record, dir);
    return record;
}

} // namespace rbm::benchmark
