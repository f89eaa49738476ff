#include "PitchingTask.hpp"

#include "CaseFiles.hpp"
#include "FoamDictionary.hpp"
#include "MeshIoTask.hpp"
#include "MeshTopology.hpp"
#include "PatchBoundaryConditions.hpp"
#include "PetscSupport.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "Process.hpp"
#include "RigidBodyMotionSolver.hpp"
#include "RunLog.hpp"
#include "StepAssessment.hpp"
#include "Variants.hpp"

#include <algorithm>
#include <iostream>
#include <limits>

namespace rbm::benchmark {

Record runPitchingTask(const std::string& variant, int steps, const fs::path& airfoilDir, const fs::path& workDir)
{
    Record record;
    record.set("task", "pitching");
    record.set("variant", variant);
    record.set("steps", steps);
    const motion::PetscSession petsc;
    auto started = Clock::now();
    const PolyMesh mesh = io::readPolyMesh(airfoilDir / "constant" / "polyMesh");
    record.set("readSeconds", secondsSince(started));
    const io::Dictionary coefficients =
        io::Dictionary::parseText(solverCoefficients(variant), "rbmBenchmark/rigidBodyMotionSolverCoeffs");
    const io::Dictionary pointDisplacement =
        io::Dictionary::parseText(pointDisplacementFile(pitchingBoundaryField("solidBodyMotionDisplacement")),
                                  "rbmBenchmark/0/pointDisplacement");
    started = Clock::now();
    motion::RigidBodyMotionSolver solver(mesh, coefficients,
                                        motion::makePatchBoundaryConditions(mesh, &pointDisplacement, workDir), workDir);
    // rbmMoveMesh's per-step check (the log line's figures and the inverted-cell policy), on
    // the solver's 2D mesh as there.
    motion::StepAssessor assessor(mesh, buildMeshTopology(mesh), solver.twoDMesh());
    record.set("constructSeconds", secondsSince(started));

    std::vector<double> solveTimes;
    std::vector<double> checkedTimes;  // solve + quality check, before the points are written
    std::vector<double> stepTimes;
    std::vector<double> solveCpuTimes;
    std::vector<double> checkedCpuTimes;
    std::vector<double> stepCpuTimes;
    Label maxInverted = 0;
    int subSteps = 0;
    int iterations = 0;
    double worstQuality = std::numeric_limits<double>::infinity();
    bool converged = true;
    double drift = 0.0;
    for (int step = 1; step <= steps; ++step) {
        const double time = static_cast<double>(step) / steps;
        const auto stepStart = Clock::now();
        const double stepCpuStart = processCpuSeconds();
        solver.updateBoundaryConditions(time);
        const motion::MotionSolveReport report = solver.solve();
        solveTimes.push_back(secondsSince(stepStart));
        solveCpuTimes.push_back(processCpuSeconds() - stepCpuStart);
        const std::vector<Vector3> points = solver.curPoints();
        io::StepLogRecord quality;
        assessor.assess(report, solver.pointDisplacement(), points, quality);
        checkedTimes.push_back(secondsSince(stepStart));
        checkedCpuTimes.push_back(processCpuSeconds() - stepCpuStart);
        io::writePolyMeshPoints(workDir, "pitching", points, writeOptions("binaryGzip"));
        stepTimes.push_back(secondsSince(stepStart));
        stepCpuTimes.push_back(processCpuSeconds() - stepCpuStart);
        maxInverted = std::max(maxInverted, static_cast<Label>(quality.invertedCells));
        // One line per step on standard error (the parent keeps it in the run's log).
        std::cerr << "step " << step << " solve " << solveTimes.back() << " s (cpu " << solveCpuTimes.back()
                  << ") iterations " << report.iterations << " sub-steps " << report.subStepCount << " residual "
                  << report.residual << " energy " << report.energy << " inverted " << quality.invertedCells
                  << " " << report.reason << '\n';
        subSteps += report.subStepCount;
        iterations += report.iterations;
        worstQuality = std::min(worstQuality, report.worstQuality);
        converged = converged && report.converged;
        if (step == steps)
            for (std::size_t p = 0; p < points.size(); ++p) drift = std::max(drift, norm(points[p] - mesh.points[p]));
    }
    fs::remove_all(workDir / "pitching");
    auto mean = [](const std::vector<double>& values, std::size_t from) {
        double sum = 0.0;
        for (std::size_t k = from; k < values.size(); ++k) sum += values[k];
        return values.size() > from ? sum / static_cast<double>(values.size() - from) : nan;
    };
    auto median = [](std::vector<double> values) {
        if (values.empty()) return nan;
        std::sort(values.begin(), values.end());
        return values[values.size() / 2];
    };
    record.set("firstStepSolveSeconds", solveTimes.empty() ? nan : solveTimes.front());
    record.set("firstStepSeconds", stepTimes.empty() ? nan : stepTimes.front());
    record.set("additionalStepSolveSeconds", mean(solveTimes, 1));
    record.set("additionalStepCheckedSeconds", mean(checkedTimes, 1));
    record.set("additionalStepCheckedCpuSeconds", mean(checkedCpuTimes, 1));
    record.set("additionalStepSeconds", mean(stepTimes, 1));
    record.set("additionalStepSolveCpuSeconds", mean(solveCpuTimes, 1));
    record.set("additionalStepCpuSeconds", mean(stepCpuTimes, 1));
    record.set("medianStepSolveSeconds", median(solveTimes));
    record.set("maxStepSolveSeconds", solveTimes.empty() ? nan : *std::max_element(solveTimes.begin(), solveTimes.end()));
    record.set("totalSeconds", mean(stepTimes, 0) * static_cast<double>(stepTimes.size()));
    record.set("maxInvertedCells", static_cast<double>(maxInverted));
    record.set("subSteps", subSteps);
    record.set("iterations", iterations);
    record.set("worstQuality", worstQuality);
    record.setFlag("converged", converged);
    record.set("driftAfterPeriod", drift);
    record.set("peakMemoryMiB", procStatusMiB("VmHWM"));
    return record;
}

} // namespace rbm::benchmark
