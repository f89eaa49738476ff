#pragma once
// What both host solvers (HostMotionSolver, HostPartMotionSolver) do around one step: the solve
// on the host's displacement array, and the step's HostStepReport from the figures they gather
// the same way (the log record StepAssessment's checks fill, and their verdict): the report's
// fields, the log line rbmMoveMesh prints after "Time = " and, for an invalid step, its cause
// and advice in the plugin's words. C++20, internal to rbm_host.

#include "HostMeshConversion.hpp"
#include "HostMotionSolver.hpp"
#include "InputError.hpp"
#include "MotionSolver.hpp"
#include "RunLog.hpp"
#include "StepAssessment.hpp"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::host {

// One solve on the host's array (3 values a point): its length checked against `u`
// (std::invalid_argument, `solverName` heading the message), copied into `u`, `solve()` run
// (rbm's InputError becomes HostInputError) and `u` copied back.
template <typename Solve>
motion::MotionSolveReport solveOnHostArray(const char* solverName, double* displacement, std::size_t valueCount,
                                           std::vector<Vector3>& u, Solve&& solve)
{
    if (valueCount != 3 * u.size())
        throw std::invalid_argument(std::string(solverName) + "::solve: " + std::to_string(valueCount) +
                                    " values for " + std::to_string(u.size()) + " points (3 per point)");
    readVectors(displacement, u);
    motion::MotionSolveReport report;
    try {
        report = solve();
    } catch (const InputError& error) {
        throw HostInputError(error.file(), error.line(), error.message());
    }
    writeVectors(u, displacement);
    return report;
}

// The step's log record before the checks fill it.
io::StepLogRecord stepRecord(int step, double time, const std::string& timeName);

// `solverAdvice`: the solver's own advice for inverted cells (MotionSolver::invertedStepAdvice).
HostStepReport hostStepReport(const io::StepLogRecord& record, const motion::StepVerdict& verdict,
                              std::vector<std::string> warnings, std::string_view solverAdvice);

} // namespace rbm::host
