#include "MarkdownReport.hpp"

#include "BenchmarkCases.hpp"
#include "Format.hpp"
#include "MeshIoTask.hpp"
#include "RbmMoveMeshRun.hpp"
#include "Variants.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace rbm::benchmark {

std::string markdownReport(const Results& results, const Options& options)
{
    std::ostringstream out;
    const Record& machine = results.machine;
    out << "# rbm benchmark, " << machine.text("date") << "\n\n";
    out << "Command: `build/bin/" << options.commandLine << "`\n\n";
    out << "Machine: " << count(machine.number("nproc")) << " cores (" << machine.text("cpuModel") << "), "
        << fixed(machine.number("memoryGiB"), 1) << " GiB memory, " << machine.text("kernel")
        << ". Load average at start: " << machine.text("loadAverageAtStart") << "; at end: "
        << machine.text("loadAverageAtEnd") << " (the machine is shared: timings include that noise).\n";
    out << "Build: " << machine.text("compiler") << ", assertions " << machine.text("assertions") << ", PETSc "
        << machine.text("petsc") << ", rbm commit " << machine.text("gitCommit")
        << (machine.flag("gitDirty") ? " with uncommitted changes" : "") << ". OpenFOAM: "
        << (machine.text("openfoam").empty() ? "not used" : machine.text("openfoam")) << ".\n\n";
    if (machine.has("partialAt"))
        out << "**Partial report**, written at " << machine.text("partialAt")
            << " after a decomposed run; the benchmark had not finished.\n\n";
    out << "N = RBM nodes (2D: nodes of one plane; 3D: mesh points). Times in seconds, one child process per run;\n"
           "*1st solve* includes the factorisation or preconditioner set-up, *repeat* is the same solve again with\n"
           "the matrices kept (the cost of a further time step); *step* = read + graph + problem + assembly +\n"
           "1st solve + quality + write (PETSc start-up, " +
               seconds(machine.number("petscInitSeconds")) +
               " s, not included). Peak = the child's VmHWM.\n\n";

    for (const std::string& caseName : options.cases) {
        bool any = false;
        for (const Record& run : results.runs) any = any || run.text("case") == caseName;
        if (!any) continue;
        out << "## " << caseName << ": " << caseInfo(caseName).description << "\n\n";
        out << "| N | cells | variant | read | graph | problem | assembly | 1st solve | repeat | quality | write | "
               "**step** | step CPU | iterations (Krylov) | peak MiB | inverted | min shape | max non-orth |\n";
        out << "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Record& run : results.runs) {
            if (run.text("case") != caseName) continue;
            out << "| " << count(run.number("nodes")) << " | " << count(run.number("cells")) << " | " << run.text("variant");
            if (run.flag("failed")) {
                out << " | failed: " << run.text("error") << " |||||||||||||||\n";
                continue;
            }
            if (run.flag("skipped")) {
                out << " | skipped: " << run.text("skipReason") << " |||||||||||||||\n";
                continue;
            }
            out << " | " << seconds(run.number("readSeconds")) << " | " << seconds(run.number("graphSeconds")) << " | "
                << seconds(run.number("problemSeconds")) << " | " << seconds(run.number("assembleSeconds")) << " | "
                << seconds(run.number("firstSolveSeconds")) << " | " << seconds(run.number("repeatSolveSeconds")) << " | "
                << seconds(run.number("qualitySeconds")) << " | " << seconds(run.number("writeSeconds")) << " | **"
                << seconds(run.number("stepTotalSeconds")) << "** | " << seconds(run.number("stepTotalCpuSeconds"))
                << " | " << count(run.number("iterations")) << " ("
                << count(run.number("linearIterations")) << ")" << (run.flag("converged") ? "" : " not converged")
                << " | " << count(run.number("peakMemoryMiB")) << " | " << count(run.number("invertedCells")) << " | "
                << fixed(run.number("minShapeQuality"), 3) << " | " << fixed(run.number("maxNonOrthogonality"), 1)
                << " |\n";
        }
        out << "\n";
    }

    if (!results.fits.empty()) {
        out << "## Growth with N (least-squares slope of log time over log N)\n\n";
        out << "| case | variant | N range | step (compute) | same, CPU | 1st solve | same, CPU | repeat solve | "
               "step incl. I/O | same, CPU | peak memory |\n";
        out << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Record& fit : results.fits)
            out << "| " << fit.text("case") << " | " << fit.text("variant") << " | " << count(fit.number("minNodes"))
                << " – " << count(fit.number("maxNodes")) << " | " << fixed(fit.number("exponentStepCompute"), 2) << " | "
                << fixed(fit.number("exponentStepComputeCpu"), 2) << " | " << fixed(fit.number("exponentFirstSolve"), 2)
                << " | " << fixed(fit.number("exponentFirstSolveCpu"), 2) << " | "
                << fixed(fit.number("exponentRepeatSolve"), 2)
                << " | " << fixed(fit.number("exponentStepTotal"), 2) << " | " << fixed(fit.number("exponentStepTotalCpu"), 2)
                << " | " << fixed(fit.number("exponentPeakMemoryMiB"), 2)
                << " |\n";
        out << "\n*step (compute)* = graph + problem + assembly + 1st solve.\n\n";
    }

    if (!results.meshIo.empty()) {
        out << "## Mesh input/output (writePolyMesh, readPolyMesh, points of a moved mesh)\n\n";
        out << "| case | N | cells | format | write mesh | read mesh | write points | read points | MiB |\n";
        out << "|---|---:|---:|---|---:|---:|---:|---:|---:|\n";
        for (const Record& record : results.meshIo) {
            if (record.flag("failed")) {
                out << "| " << record.text("case") << " | failed: " << record.text("error") << " ||||||||\n";
                continue;
            }
            for (const std::string& format : meshFormats())
                out << "| " << record.text("case") << " | " << count(record.number("nodes")) << " | "
                    << count(record.number("cells")) << " | " << format << " | "
                    << seconds(record.number(format + "WriteSeconds")) << " | "
                    << seconds(record.number(format + "ReadSeconds")) << " | "
                    << seconds(record.number(format + "WritePointsSeconds")) << " | "
                    << seconds(record.number(format + "ReadPointsSeconds")) << " | " << fixed(record.number(format + "MiB"), 1)
                    << " |\n";
        }
        out << "\n";
    }

    bool anyAirfoilProcess = false, anyTwistProcess = false;
    for (const Record& record : results.wholeProcess) {
        anyAirfoilProcess = anyAirfoilProcess || record.text("case") == "airfoil";
        anyTwistProcess = anyTwistProcess || record.text("case") == "twist3D";
    }
    if (anyTwistProcess) {
        out << "## twist3D, one step with the defaults, whole programs (rbmMoveMesh -noVTK against moveMesh)\n\n";
        out << "rbmMoveMesh with `" << solverCoefficients("reducedNewton")
            << "` and `floatingPatches (sides);` (the sides free, as OpenFOAM's zeroGradient leaves them; without "
               "it rbm slides them on their planes), every other entry at its default (`stiffening auto` included, "
               "which the in-process rows above leave out): start, read, set-up, solve, quality check, write. "
               "OpenFOAM: the moveMesh run of the table below. Ratio = rbm / OpenFOAM.\n\n";
        out << "| N | cells | rbm wall s | rbm CPU s | rbm peak MiB | exit | inverted | max non-orth | moveMesh wall s | "
               "moveMesh CPU s | moveMesh peak MiB | ratio (CPU) |\n";
        out << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Record& record : results.wholeProcess) {
            if (record.text("case") != "twist3D") continue;
            out << "| " << count(record.number("nodes")) << " | " << count(record.number("cells")) << " | "
                << seconds(record.number("wallSeconds")) << " | " << seconds(record.number("cpuSeconds")) << " | "
                << count(record.number("peakMemoryMiB")) << " | " << count(record.number("exitCode")) << " | "
                << count(record.number("invertedCells")) << " | " << fixed(record.number("maxNonOrthogonality"), 1) << " | "
                << seconds(record.number("openfoamWallSeconds")) << " | " << seconds(record.number("openfoamCpuSeconds"))
                << " | " << count(record.number("openfoamPeakMemoryMiB")) << " | "
                << fixed(record.number("cpuSeconds") / record.number("openfoamCpuSeconds"), 2) << " |\n";
        }
        out << "\n";
    }
    if (!results.decomposed.empty()) {
        out << "## twist3D decomposed over N ranks (decomposePar, method simple), whole programs\n\n"
               "`mpirun -np N rbmMoveMesh -case <case> -parallel -noVTK` (each rank reads and writes its processor "
               "folder only; the serial run's dictionary: reduced Newton, `floatingPatches (sides)`, the rest "
               "default) and `mpirun -np N moveMesh -case <case> -parallel` on the same processor folders, one step "
               "each. Per-rank peak = each rank's VmHWM at exit (its wrapper's wait4: ru_maxrss); largest and sum over "
               "the ranks; serial = the single-process runs above. CPU = the ranks' user + system time, summed. With "
               "more ranks than cores the ranks share them (oversubscribed): wall times then include waiting. "
               "difference = max over every processor's points of |decomposed − serial rbmMoveMesh| / the point's "
               "shortest edge. Non-orthogonality and inverted cells: the processors' points gathered into the whole "
               "mesh and evaluated as the serial results are (rbm's own step line in brackets).\n\n";
        out << "| cells | ranks | decomposition | rbm wall s | rbm CPU s | rbm rank peaks MiB | rbm largest / sum MiB | rbm "
               "serial MiB | largest / serial | moveMesh wall s | moveMesh CPU s | moveMesh rank peaks MiB | moveMesh "
               "largest / sum MiB | moveMesh serial MiB | largest / serial | difference to serial | rbm max non-orth "
               "(step line) | rbm inverted | moveMesh max non-orth | moveMesh inverted |\n";
        out << "|---:|---:|---|---:|---:|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Record& record : results.decomposed) {
            std::ostringstream difference;
            difference << std::setprecision(2) << record.number("rbmMaxDifferenceToSerialPerShortestEdge");
            out << "| " << count(record.number("cells")) << " | " << count(record.number("ranks")) << " | "
                << record.text("decomposition") << " | ";
            if (record.number("decomposeParExitCode") != 0) {
                out << record.text("error") << " ||||||||||||||||\n";
                continue;
            }
            out << seconds(record.number("rbmWallSeconds")) << " | " << seconds(record.number("rbmCpuSeconds")) << " | "
                << record.text("rbmRankPeaksMiB") << " | " << count(record.number("rbmRankPeakMaxMiB")) << " / "
                << count(record.number("rbmRankPeakSumMiB")) << " | " << count(record.number("rbmSerialPeakMiB")) << " | "
                << fixed(record.number("rbmRankPeakOverSerial"), 3) << " | " << seconds(record.number("openfoamWallSeconds"))
                << " | " << seconds(record.number("openfoamCpuSeconds")) << " | " << record.text("openfoamRankPeaksMiB")
                << " | " << count(record.number("openfoamRankPeakMaxMiB")) << " / "
                << count(record.number("openfoamRankPeakSumMiB")) << " | " << count(record.number("openfoamSerialPeakMiB"))
                << " | " << fixed(record.number("openfoamRankPeakOverSerial"), 3) << " | " << difference.str() << " | "
                << fixed(record.number("rbm.maxNonOrthogonality"), 2) << " ("
                << fixed(record.number("rbmLogMaxNonOrthogonality"), 2) << ") | " << count(record.number("rbm.invertedCells"))
                << " | " << fixed(record.number("openfoam.maxNonOrthogonality"), 2) << " | "
                << count(record.number("openfoam.invertedCells")) << " |\n";
            for (const char* program : {"rbm", "openfoam"}) {
                const std::string error = record.text(std::string(program) + "Error") + record.text(std::string(program) + "CheckError");
                if (!error.empty()) out << "\n" << program << ", " << count(record.number("ranks")) << " ranks: " << error << "\n";
            }
        }
        out << "\n";
    }
    if (anyAirfoilProcess) {
        out << "## Airfoil, one 4° step, whole program (rbmMoveMesh -noVTK: start, read, solve, quality, write)\n\n";
        out << "| variant | coefficients | wall s | CPU s | peak MiB | exit | inverted | min shape | max non-orth |\n";
        out << "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Record& record : results.wholeProcess) {
            if (record.text("case") != "airfoil") continue;
            out << "| " << record.text("variant") << " | `" << record.text("coefficients") << "` | "
                << seconds(record.number("wallSeconds")) << " | " << seconds(record.number("cpuSeconds")) << " | " << count(record.number("peakMemoryMiB")) << " | "
                << count(record.number("exitCode")) << " | " << count(record.number("invertedCells")) << " | "
                << fixed(record.number("minShapeQuality"), 3) << " | " << fixed(record.number("maxNonOrthogonality"), 1)
                << " |\n";
        }
        out << "\n*fast MPI start*: the same run with " << fastMpiStartText()
            << " in the environment (Open MPI's singleton start-up without its daemon and network probes).\n\n";
    }

    if (!results.pitching.empty()) {
        out << "## Airfoil pitching (5° pitch + 0.05 plunge, one period), RigidBodyMotionSolver in one process\n\n";
        out << "| variant | steps | set-up | 1st step | additional step: solve (CPU) | + quality (CPU) | + quality + write (CPU) | "
               "max step | sub-steps | max inverted | drift after period |\n";
        out << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Record& record : results.pitching) {
            if (record.flag("failed")) {
                out << "| " << record.text("variant") << " | failed: " << record.text("error") << " ||||||||||\n";
                continue;
            }
            out << "| " << record.text("variant") << " | " << count(record.number("steps")) << " | "
                << seconds(record.number("constructSeconds")) << " | " << seconds(record.number("firstStepSeconds"))
                << " | " << seconds(record.number("additionalStepSolveSeconds")) << " ("
                << seconds(record.number("additionalStepSolveCpuSeconds")) << ") | "
                << seconds(record.number("additionalStepCheckedSeconds")) << " ("
                << seconds(record.number("additionalStepCheckedCpuSeconds")) << ") | "
                << seconds(record.number("additionalStepSeconds")) << " ("
                << seconds(record.number("additionalStepCpuSeconds")) << ") | "
                << seconds(record.number("maxStepSolveSeconds")) << " | " << count(record.number("subSteps")) << " | "
                << count(record.number("maxInvertedCells")) << " | " << std::setprecision(2)
                << record.number("driftAfterPeriod") << " |\n";
        }
        out << "\n";
    }

    if (!results.openfoam.empty()) {
        out << "## OpenFOAM moveMesh (displacementLaplacian) on the same mesh and motion\n\n";
        out << "| case | N | run | moveMesh wall s | CPU s | peak MiB | inverted | max non-orth | rbm step (linearized) | "
               "ratio | rbm step (fastest nonlinear) | ratio |\n";
        out << "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Record& record : results.openfoam) {
            out << "| " << record.text("case") << " | " << count(record.number("nodes")) << " | " << record.text("run")
                << " | " << seconds(record.number("wallSeconds")) << " | " << seconds(record.number("cpuSeconds")) << " | "
                << count(record.number("peakMemoryMiB")) << " | ";
            if (record.number("exitCode") != 0) {
                out << "failed: " << record.text("error") << " ||||||||\n";
                continue;
            }
            out << count(record.number("invertedCells")) << " | " << fixed(record.number("maxNonOrthogonality"), 1)
                << " | " << seconds(record.number("rbmLinearizedSeconds")) << " | "
                << fixed(record.number("ratioLinearized"), 2) << " | " << seconds(record.number("rbmNonlinearSeconds"))
                << " | " << fixed(record.number("ratioNonlinear"), 2) << " |\n";
        }
        out << "\nmoveMesh wall = the whole process (start, read, solve, write; no quality check). rbm step = the "
               "in-process pipeline above plus PETSc start-up (pitching rows: time per additional step, solve and "
               "quality check: OpenFOAM's pitching case writes at its end only, so rbm's per-step output is left out "
               "here; with it, the pitching table's last time column). Ratio = rbm / OpenFOAM.\n\n";
    }

    if (!results.targets.empty()) {
        out << "## Targets\n\n| target | measured | met | note |\n|---|---|---|---|\n";
        for (const Record& target : results.targets)
            out << "| " << target.text("target") << " | " << target.text("measured") << " | " << target.text("met")
                << " | " << target.text("note") << " |\n";
        out << "\n";
    }
    return out.str();
}

} // namespace rbm::benchmark
