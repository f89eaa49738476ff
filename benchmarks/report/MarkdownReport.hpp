#pragma once
// The markdown report (standard output, --markdown).

#include "Options.hpp"
#include "Results.hpp"

#include <string>

namespace rbm::benchmark {

std::string markdownReport(const Results& results, const Options& options);

} // namespace rbm::benchmark
