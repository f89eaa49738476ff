#include "Record.hpp"


namespace rbm::benchmark {

std::string jsonArray(const std::vector<Record>& records, const std::string& indent)
{
    std::string out = "[";
    for (std::size_t k = 0; k < records.size(); ++k)
        out += (k ? ",\n" : "\n") + indent + "  " + records[k].toJson(indent + "  ");
    return out + (records.empty() ? "]" : "\n" + indent + "]");
}

std::optional<Record> recordFromOutput(const std::string& output)
{
    const std::string begin = "RBM_BENCHMARK_RECORD_BEGIN\n";
    const std::string end = "RBM_BENCHMARK_RECORD_END";
    const std::size_t from = output.find(begin);
    const std::size_t to = output.find(end);
    if (from == std::string::npos || to == std::string::npos || to < from) return std::nullopt;
    return Record::fromLines(output.substr(from + begin.size(), to - from - begin.size()));
}

} // namespace rbm::benchmark
