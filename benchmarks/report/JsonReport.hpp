#pragma once
// Every figure as JSON (--json).

#include "Options.hpp"
#include "Results.hpp"

#include <string>

namespace rbm::benchmark {

std::string jsonReport(const Results& results, const Options& options);

} // namespace rbm::benchmark
