#include "HostStepReporting.hpp"

#include <utility>

namespace rbm::host {

io::StepLogRecord stepRecord(int step, double time, const std::string& timeName)
{
    io::StepLogRecord record;
    record.step = step;
    record.time = time;
    record.timeName = timeName;
    return record;
}

HostStepReport hostStepReport(const io::StepLogRecord& record, const motion::StepVerdict& verdict,
                              std::vector<std::string> warnings, std::string_view solverAdvice)
{
    HostStepReport report;
    report.subSteps = record.subSteps;
    report.iterations = record.iterations;
    report.residual = record.residual;
    report.energy = record.energy;
    report.converged = record.converged;
    report.reason = record.reason;
    report.invertedCells = record.invertedCells;
    report.worstQuality = record.worstQuality;
    report.maxNonOrthogonality = record.maxNonOrthogonality;
    report.maxSkewness = record.maxSkewness;
    report.wallSeconds = record.wallSeconds;
    report.warnings = std::move(warnings);
    report.finite = verdict.finite;
    report.valid = verdict.valid;
    report.logLine = "rigidBodyMotionSolver: " + io::formatStepFigures(record);
    if (!verdict.valid)
        report.problem = motion::invalidStepCause(verdict, record) + ". " +
                         motion::invalidStepAdvice(verdict, record,
                                                   "writeInvalid yes; in rigidBodyMotionSolverCoeffs goes on anyway",
                                                   solverAdvice);
    return report;
}

} // namespace rbm::host
