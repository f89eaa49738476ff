#pragma once
// Everything a benchmark run measured, and the growth exponents fitted to it.

#include "Record.hpp"

#include <utility>
#include <vector>

namespace rbm::benchmark {

struct Results {
    Record machine;
    std::vector<Record> meshIo;
    std::vector<Record> runs;
    std::vector<Record> wholeProcess;
    std::vector<Record> pitching;
    std::vector<Record> openfoam;
    std::vector<Record> decomposed;  // twist3D over N ranks, both programs (--ranks)
    std::vector<Record> fits;
    std::vector<Record> targets;
};

bool usable(const Record& run);

// Least-squares slope of log(y) over log(x).
double fittedExponent(const std::vector<std::pair<double, double>>& samples);

void computeFits(Results& results);

} // namespace rbm::benchmark
