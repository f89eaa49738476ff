#include "Results.hpp"

#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <string>

namespace rbm::benchmark {

bool usable(const Record& run)
{
    return !run.flag("failed") && !run.flag("skipped");
}

double fittedExponent(const std::vector<std::pair<double, double>>& samples)
{
    std::vector<std::pair<double, double>> logs;
    for (const auto& [x, y] : samples)
        if (x > 0.0 && y > 0.0 && std::isfinite(y)) logs.emplace_back(std::log(x), std::log(y));
    if (logs.size() < 2) return nan;
    double meanX = 0.0;
    double meanY = 0.0;
    for (const auto& [x, y] : logs) {
        meanX += x;
        meanY += y;
    }
    meanX /= static_cast<double>(logs.size());
    meanY /= static_cast<double>(logs.size());
    double covariance = 0.0;
    double variance = 0.0;
    for (const auto& [x, y] : logs) {
        covariance += (x - meanX) * (y - meanY);
        variance += (x - meanX) * (x - meanX);
    }
    return variance > 0.0 ? covariance / variance : nan;
}

void computeFits(Results& results)
{
    std::map<std::pair<std::string, std::string>, std::vector<const Record*>> groups;
    std::vector<std::pair<std::string, std::string>> order;
    for (const Record& run : results.runs) {
        if (!usable(run) || run.text("case") == "airfoil") continue;
        const auto key = std::make_pair(run.text("case"), run.text("variant"));
        if (!groups.count(key)) order.push_back(key);
        groups[key].push_back(&run);
    }
    for (const auto& key : order) {
        const auto& runs = groups[key];
        if (runs.size() < 2) continue;
        Record fit;
        fit.set("case", key.first);
        fit.set("variant", key.second);
        double minNodes = std::numeric_limits<double>::infinity();
        double maxNodes = 0.0;
        for (const char* metric : {"stepComputeSeconds", "stepComputeCpuSeconds", "firstSolveSeconds",
                                   "firstSolveCpuSeconds", "repeatSolveSeconds", "stepTotalSeconds",
                                   "stepTotalCpuSeconds", "peakMemoryMiB"}) {
            std::vector<std::pair<double, double>> samples;
            for (const Record* run : runs) {
                samples.emplace_back(run->number("nodes"), run->number(metric));
                minNodes = std::min(minNodes, run->number("nodes"));
                maxNodes = std::max(maxNodes, run->number("nodes"));
            }
            std::string name = metric;
            name = "exponent" + std::string(1, static_cast<char>(std::toupper(name[0]))) +
                   name.substr(1, name.find("Seconds") == std::string::npos ? std::string::npos : name.find("Seconds") - 1);
            fit.set(name, fittedExponent(samples));
        }
        fit.set("minNodes", minNodes);
        fit.set("maxNodes", maxNodes);
        fit.set("sizes", static_cast<double>(runs.size()));
        results.fits.push_back(fit);
    }
}

} // namespace rbm::benchmark
