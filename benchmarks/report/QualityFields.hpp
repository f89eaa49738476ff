#pragma once
// Mesh quality as fields of a record (the report's quality columns).

#include "QualityReport.hpp"
#include "Record.hpp"

#include <filesystem>
#include <string>

namespace rbm::benchmark {

namespace fs = std::filesystem;

void addQuality(Record& record, const QualityReport& report, const std::string& prefix);

// Quality of the mesh a program wrote at time 1.
void addResultQuality(Record& record, const fs::path& caseDir);

} // namespace rbm::benchmark
