#pragma once
// A step's HostStepReport from the figures both host solvers gather the same way (the log
// record StepAssessment's checks fill, and their verdict): the report's fields, the log line
// rbmMoveMesh prints after "Time = " and, for an invalid step, its cause and advice in the
// plugin's words. C++20, internal to rbm_host.

#include "HostMotionSolver.hpp"
#include "RunLog.hpp"
#include "StepAssessment.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace rbm::host {

// `solverAdvice`: the solver's own advice for inverted cells (MotionSolver::invertedStepAdvice).
HostStepReport hostStepReport(const io::StepLogRecord& record, const motion::StepVerdict& verdict,
                              std::vector<std::string> warnings, std::string_view solverAdvice);

} // namespace rbm::host
