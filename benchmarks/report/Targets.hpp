#pragma once
// The performance targets, judged on the results.

#include "Results.hpp"

#include <string>

namespace rbm::benchmark {

const Record* findRun(const Results& results, const std::string& caseName, const std::string& variant);

void addTarget(Results& results, const std::string& target, const std::string& measured, int met, const std::string& note);

void evaluateTargets(Results& results, double petscInitSeconds, double petscInitCpuSeconds);

} // namespace rbm::benchmark
