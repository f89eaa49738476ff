#include "Decomposition.hpp"

#include "CaseFiles.hpp"
#include "Process.hpp"

#include <regex>

namespace rbm::benchmark {

std::array<int, 3> simpleSplit(int ranks)
{
    if (ranks == 2) return {2, 1, 1};
    if (ranks == 4) return {2, 2, 1};
    if (ranks == 8) return {2, 2, 2};
    return {ranks, 1, 1};
}

std::string simpleSplitText(int ranks)
{
    const std::array<int, 3> n = simpleSplit(ranks);
    return "(" + std::to_string(n[0]) + " " + std::to_string(n[1]) + " " + std::to_string(n[2]) + ")";
}

std::string decomposeParDict(int ranks)
{
    return foamHeader("dictionary", "system", "decomposeParDict") + "numberOfSubdomains " + std::to_string(ranks) +
           ";\nmethod simple;\nsimpleCoeffs\n{\n    n " + simpleSplitText(ranks) + ";\n    delta 0.001;\n}\n";
}

std::string decomposableBoundaryField(const std::string& boundaryField)
{
    static const std::regex coefficients(R"(solidBodyMotionFunction (\w+);(\s*)(\w+)Coeffs(\s*)\{)");
    return std::regex_replace(boundaryField, coefficients,
                              "solidBodyMotionFunction $1;$2$3Coeffs$4{ solidBodyMotionFunction $1;");
}

Record runDecomposePar(const OpenFoam& openfoam, const fs::path& dir, int ranks)
{
    writeText(dir / "system" / "decomposeParDict", decomposeParDict(ranks));
    for (int rank = 0; rank < 64; ++rank) fs::remove_all(dir / ("processor" + std::to_string(rank)));
    const ProcessResult result = runProcess({"/usr/bin/decomposePar", "-case", dir.string()},
                                            dir / "log.decomposePar.stderr", &openfoam.environment, dir / "log.decomposePar");
    Record record;
    record.set("decomposeParWallSeconds", result.wallSeconds);
    record.set("decomposeParPeakMemoryMiB", result.maxRssMiB);
    record.set("decomposeParExitCode", result.exitCode);
    if (result.exitCode != 0) record.set("error", "decomposePar: " + readTail(dir / "log.decomposePar", 300));
    return record;
}

void copyProcessorFolders(const fs::path& from, const fs::path& to, int ranks)
{
    fs::copy_file(from / "system" / "decomposeParDict", to / "system" / "decomposeParDict",
                  fs::copy_options::overwrite_existing);
    for (int rank = 0; rank < ranks; ++rank) {
        const std::string name = "processor" + std::to_string(rank);
        fs::remove_all(to / name);
        fs::create_directories(to / name);
        for (const char* part : {"constant", "0"})
            fs::copy(from / name / part, to / name / part, fs::copy_options::recursive);
    }
}

} // namespace rbm::benchmark
