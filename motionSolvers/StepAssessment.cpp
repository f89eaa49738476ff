#include "StepAssessment.hpp"

#include "InvertedCell.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rbm::motion {

namespace {

bool isFinite(const Vector3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string general(double value)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    return buffer;
}

} // namespace

PyramidQuality cellPyramidQuality(const PolyMesh& mesh, const MeshTopology& topology, const MeshGeometry& geometry,
                                  Label cell)
{
    const auto c = static_cast<std::size_t>(cell);
    const Vector3& centre = geometry.cellCentres[c];
    double smallest = std::numeric_limits<double>::infinity();
    const auto faces = topology.facesOf(cell);
    for (const Label face : faces) {
        const auto f = static_cast<std::size_t>(face);
        smallest = std::min(smallest,
                            tripleFacePyramid(geometry.faceAreas[f], geometry.faceCentres[f], centre, mesh.owner[f] == cell) /
                                3.0);
    }
    const double volume = geometry.cellVolumes[c];
    PyramidQuality quality;
    quality.inverted = isInvertedCell(volume, smallest);
    quality.ratio = std::abs(volume) > 0.0 ? static_cast<double>(faces.size()) * smallest / std::abs(volume) : 0.0;
    return quality;
}

StepAssessor::StepAssessor(const PolyMesh& mesh)
    : mesh_(mesh), evaluator_(mesh)
{}

StepAssessor::StepAssessor(const PolyMesh& mesh, MeshTopology topology, const PseudoTwoDMesh* twoD)
    : mesh_(mesh), evaluator_(mesh, std::move(topology), twoD)
{}

StepAssessor::~StepAssessor() = default;

QualityReport StepAssessor::evaluate(std::span<const Vector3> points) { return evaluator_.evaluate(points); }

double StepAssessor::worstCellQuality(const QualityReport& report) const
{
    if (report.thesis.dimension == 2) {
        double worst = std::numeric_limits<double>::quiet_NaN();
        if (report.thesis.triangleMeanRatio.count > 0) worst = report.thesis.triangleMeanRatio.min;
        if (report.thesis.quadrilateralShape.count > 0)
            worst = std::isnan(worst) ? report.thesis.quadrilateralShape.min
                                      : std::min(worst, report.thesis.quadrilateralShape.min);
        return worst;
    }
    const MeshGeometry& geometry = evaluator_.geometry();
    double worst = std::numeric_limits<double>::quiet_NaN();
    const Label cellCount = static_cast<Label>(geometry.cellVolumes.size());
    for (Label c = 0; c < cellCount; ++c) {
        const double ratio = cellPyramidQuality(mesh_, evaluator_.cellFaceTopology(), geometry, c).ratio;
        worst = (c == 0) ? ratio : std::min(worst, ratio);
    }
    return worst;
}

StepVerdict recordSolve(const MotionSolveReport& solve, std::string nonFiniteText, io::StepLogRecord& record)
{
    // A solve that produced NaN or infinite values failed whatever it reports.
    StepVerdict verdict;
    verdict.finite = nonFiniteText.empty() && std::isfinite(solve.residual);
    if (!verdict.finite) verdict.nonFiniteText = nonFiniteText.empty() ? "a residual of " + general(solve.residual)
                                                                       : std::move(nonFiniteText);
    record.subSteps = solve.subStepCount;
    record.iterations = solve.iterations;
    record.residual = solve.residual;
    record.energy = solve.energy;
    record.converged = solve.converged && verdict.finite;
    record.reason = verdict.finite ? solve.reason : solve.reason + "; " + verdict.nonFiniteText;
    return verdict;
}

void recordQuality(const StepQuality* quality, StepVerdict& verdict, io::StepLogRecord& record)
{
    if (quality) {
        record.worstQuality = quality->worstCellQuality;
        record.maxNonOrthogonality = quality->maxNonOrthogonality;
        record.maxSkewness = quality->maxSkewness;
        record.invertedCells = quality->invertedCellCount;
    } else {
        record.worstQuality = std::numeric_limits<double>::quiet_NaN();
        record.maxNonOrthogonality = std::numeric_limits<double>::quiet_NaN();
        record.maxSkewness = std::numeric_limits<double>::quiet_NaN();
        record.invertedCells = 0;
    }
    verdict.valid = record.converged && record.invertedCells == 0;
}

StepVerdict StepAssessor::assess(const MotionSolveReport& solve, std::span<const Vector3> displacement,
                                 std::span<const Vector3> points, io::StepLogRecord& record)
{
    std::string nonFiniteText;
    const auto nonFinite = std::count_if(displacement.begin(), displacement.end(),
                                         [](const Vector3& u) { return !isFinite(u); });
    if (nonFinite > 0) {
        const auto first = std::find_if(displacement.begin(), displacement.end(),
                                        [](const Vector3& u) { return !isFinite(u); });
        nonFiniteText = "NaN or infinite displacement at " + std::to_string(nonFinite) + " of " +
                        std::to_string(points.size()) + " points (first: point " +
                        std::to_string(first - displacement.begin()) + ")";
    }
    StepVerdict verdict = recordSolve(solve, std::move(nonFiniteText), record);
    if (verdict.finite) {
        const StepQuality quality = evaluator_.evaluateStep(points);
        recordQuality(&quality, verdict, record);
    } else {
        recordQuality(nullptr, verdict, record);
    }
    return verdict;
}

std::string invalidStepCause(const StepVerdict& verdict, const io::StepLogRecord& record)
{
    if (!verdict.finite) {
        const std::string solverReason = record.reason.substr(0, record.reason.rfind("; " + verdict.nonFiniteText));
        return "the motion solver produced " + verdict.nonFiniteText + " (solver's reason: " + solverReason + ")";
    }
    if (record.invertedCells > 0) {
        std::string cause = "the moved mesh has " + std::to_string(record.invertedCells) + " inverted cell" +
                            (record.invertedCells == 1 ? "" : "s");
        if (!record.converged) cause += " and the solve did not converge (" + record.reason + ")";
        return cause;
    }
    return "the motion solver did not converge (" + record.reason + ")";
}

std::string invalidStepAdvice(const StepVerdict& verdict, const io::StepLogRecord& record, std::string_view goOnAnyway,
                              std::string_view solverAdvice)
{
    if (!verdict.finite)
        return "A boundary displacement far larger than the mesh, or a linear solver that diverged, does this; "
               "-rbm_newton_snes_monitor, -rbm_linearized_ksp_monitor or -ksp_monitor show the iterations.";
    if (record.invertedCells > 0 && !solverAdvice.empty())
        return std::string(solverAdvice) + " " + std::string(goOnAnyway) + ".";
    if (record.invertedCells > 0)
        return "More sub-steps (subSteps in rigidBodyMotionSolverCoeffs) or the nonlinear formulation may help; " +
               std::string(goOnAnyway) + ".";
    return "More sub-steps or iterations (subSteps, maxIterations in rigidBodyMotionSolverCoeffs) or another linear "
           "solver (linearSolver, petscOptions) may help; -rbm_newton_snes_monitor, -rbm_linearized_ksp_monitor or "
           "-ksp_monitor show the iterations; " +
           std::string(goOnAnyway) + ".";
}

} // namespace rbm::motion
