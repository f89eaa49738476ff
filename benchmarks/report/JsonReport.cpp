#include "JsonReport.hpp"

#include <sstream>

namespace rbm::benchmark {

std::string jsonReport(const Results& results, const Options& options)
{
    std::ostringstream out;
    out << "{\n  \"command\": " << Record::quoted("build/bin/" + options.commandLine) << ",\n";
    out << "  \"machine\": " << results.machine.toJson("  ") << ",\n";
    out << "  \"runs\": " << jsonArray(results.runs, "  ") << ",\n";
    out << "  \"growthExponents\": " << jsonArray(results.fits, "  ") << ",\n";
    out << "  \"meshIO\": " << jsonArray(results.meshIo, "  ") << ",\n";
    out << "  \"wholeProcess\": " << jsonArray(results.wholeProcess, "  ") << ",\n";
    out << "  \"pitching\": " << jsonArray(results.pitching, "  ") << ",\n";
    out << "  \"openfoam\": " << jsonArray(results.openfoam, "  ") << ",\n";
    out << "  \"decomposed\": " << jsonArray(results.decomposed, "  ") << ",\n";
    out << "  \"targets\": " << jsonArray(results.targets, "  ") << "\n}\n";
    return out.str();
}

} // namespace rbm::benchmark
