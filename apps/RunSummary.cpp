#include "RunSummary.hpp"

#include "NumberText.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

namespace rbm::app {

void RunSummary::add(const io::StepLogRecord& record, int step, bool finite)
{
    if (std::isfinite(record.worstQuality) && (!haveQuality || record.worstQuality < worstQuality)) {
        worstQuality = record.worstQuality;
        worstQualityTime = record.time;
        haveQuality = true;
    }
    if (finite && (step == 1 || record.maxNonOrthogonality > maxNonOrthogonality)) {
        maxNonOrthogonality = record.maxNonOrthogonality;
        maxNonOrthogonalityTime = record.time;
    }
    if (finite && (step == 1 || record.maxSkewness > maxSkewness)) {
        maxSkewness = record.maxSkewness;
        maxSkewnessTime = record.time;
    }
    maxInvertedCells = std::max(maxInvertedCells, record.invertedCells);
    maxIterations = std::max(maxIterations, record.iterations);
    totalIterations += record.iterations;
    if (std::isfinite(record.residual)) maxResidual = std::max(maxResidual, record.residual);
    if (record.written) {
        ++writtenTimes;
        lastWritten = record.timeName;
    }
}

void RunSummary::print(std::ostream& out, int stepsRun, int stepCount, double wallSeconds) const
{
    const RunSummary& e = *this;
    out << "\nEnd: " << stepsRun << " of " << stepCount << (stepCount == 1 ? " step" : " steps") << " in "
         << fixed(wallSeconds, 2) << " s";
    if (stepsRun > 0) out << " (" << fixed(wallSeconds / stepsRun, 3) << " s per step)";
    out << ", " << e.writtenTimes << (e.writtenTimes == 1 ? " time" : " times") << " written";
    if (!e.lastWritten.empty()) out << " (last " << e.lastWritten << ")";
    out << "\n";
    if (stepsRun > 0) {
        out << "  worst quality          " << (e.haveQuality ? fixed(e.worstQuality, 4) : std::string("n/a"));
        if (e.haveQuality) out << "  at time " << general(e.worstQualityTime);
        out << "\n  max non-orthogonality  " << fixed(e.maxNonOrthogonality, 2) << "  at time "
             << general(e.maxNonOrthogonalityTime) << "\n  max skewness           " << fixed(e.maxSkewness, 3)
             << "  at time " << general(e.maxSkewnessTime) << "\n  inverted cells         " << e.maxInvertedCells
             << " (most in one step; " << e.invalidSteps << " invalid step" << (e.invalidSteps == 1 ? "" : "s")
             << ")\n  iterations             " << e.totalIterations << " in total, at most " << e.maxIterations
             << " in one step; largest final residual " << general(e.maxResidual, 3) << "\n";
    }
    out.flush();
}

} // namespace rbm::app
