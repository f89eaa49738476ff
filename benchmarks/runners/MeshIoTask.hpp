#pragma once
// The mesh-I/O measurement of a case and size (a child run): generate or read the mesh, write it
// in each format and read it back.

#include "FoamListIO.hpp"
#include "Record.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

io::FoamWriteOptions writeOptions(const std::string& format);

const std::vector<std::string>& meshFormats();

// Writes the mesh in ascii, ascii+gzip and binary+gzip to <caseDir>/<format>/constant/polyMesh
// and reads each back; also the points of a moved mesh (<format>/1/polyMesh/points).
Record runMeshIoTask(const std::string& caseName, double size, const fs::path& caseDir, const fs::path& airfoilDir);

} // namespace rbm::benchmark
