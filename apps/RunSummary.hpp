#pragma once
// The worst figures of a run's steps and the summary rbmMoveMesh prints at its end ("End: 20
// of 20 steps in ...", worst quality, non-orthogonality, skewness, inverted cells, iterations).

#include "RunLog.hpp"

#include <iosfwd>
#include <string>

namespace rbm::app {

struct RunSummary {
    double worstQuality = 0.0;
    double worstQualityTime = 0.0;
    bool haveQuality = false;
    double maxNonOrthogonality = 0.0;
    double maxNonOrthogonalityTime = 0.0;
    double maxSkewness = 0.0;
    double maxSkewnessTime = 0.0;
    long long maxInvertedCells = 0;
    int invalidSteps = 0;
    int maxIterations = 0;
    long long totalIterations = 0;
    double maxResidual = 0.0;
    int writtenTimes = 0;
    std::string lastWritten;

    // A logged step's figures into the extremes (`finite`: its mesh has no NaN).
    void add(const io::StepLogRecord& record, int step, bool finite);
    // The summary of `stepsRun` of `stepCount` steps that took `wallSeconds`.
    void print(std::ostream& out, int stepsRun, int stepCount, double wallSeconds) const;
};

} // namespace rbm::app
