#include "OpenFoamMoveMesh.hpp"

#include "BenchmarkCases.hpp"
#include "CaseFiles.hpp"
#include "Process.hpp"
#include "QualityFields.hpp"

namespace rbm::benchmark {

OpenFoam detectOpenFoam(const fs::path& logDir)
{
    OpenFoam openfoam;
    const fs::path bashrc = "/usr/share/openfoam/etc/bashrc";
    if (!fs::exists("/usr/bin/moveMesh") || !fs::exists(bashrc) || !fs::exists("/bin/bash")) return openfoam;
    const ProcessResult result = runProcess(
        {"/bin/bash", "-c", "source " + bashrc.string() + " >/dev/null 2>&1; env -0"}, logDir / "openfoam-env.stderr");
    if (result.exitCode != 0) return openfoam;
    std::size_t start = 0;
    while (start < result.output.size()) {
        const std::size_t end = result.output.find('\0', start);
        const std::string entry = result.output.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (!entry.empty()) openfoam.environment.push_back(entry);
        if (entry.rfind("WM_PROJECT_VERSION=", 0) == 0) openfoam.version = entry.substr(19);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    openfoam.available = !openfoam.environment.empty();
    return openfoam;
}

std::string laplacianDynamicMeshDict(const std::string& diffusivity, const std::string& movingPatch)
{
    const std::string diffusivityText = diffusivity == "uniform" ? "uniform" : "inverseDistance (" + movingPatch + ")";
    return "dynamicFvMesh dynamicMotionSolverFvMesh;\nmotionSolverLibs (\"libfvMotionSolvers.so\");\n"
           "motionSolver displacementLaplacian;\ndisplacementLaplacianCoeffs\n{\n    diffusivity " +
           diffusivityText + ";\n}\n";
}

Record runOpenFoamMoveMesh(const OpenFoam& openfoam, const std::string& caseName, const fs::path& polyMeshSource,
                           const fs::path& dir, const std::string& diffusivity, const std::string& boundaryField,
                           int steps, const std::string& label)
{
    Record record;
    record.set("program", "moveMesh (OpenFOAM " + openfoam.version + ")");
    record.set("case", caseName);
    record.set("run", label);
    record.set("motionSolver", "displacementLaplacian, diffusivity " + diffusivity + ", GAMG 1e-8");
    record.set("steps", steps);
    writeMotionCase(dir, polyMeshSource, "moveMesh", laplacianDynamicMeshDict(diffusivity, caseMotion(caseName).movingPatch),
                    boundaryField, steps);
    const ProcessResult result = runProcess({"/usr/bin/moveMesh", "-case", dir.string()}, dir / "log.moveMesh.stderr",
                                            &openfoam.environment, dir / "log.moveMesh");
    record.set("wallSeconds", result.wallSeconds);
    record.set("cpuSeconds", result.userSeconds + result.systemSeconds);
    record.set("peakMemoryMiB", result.maxRssMiB);
    record.set("exitCode", result.exitCode);
    if (result.exitCode != 0) record.set("error", readTail(dir / "log.moveMesh.stderr"));
    else if (steps == 1) addResultQuality(record, dir);
    return record;
}

} // namespace rbm::benchmark
