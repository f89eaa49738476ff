#include "MeshIoTask.hpp"

#include "BenchmarkCases.hpp"
#include "MeshTopology.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "Process.hpp"
#include "PseudoTwoDExtraction.hpp"

#include <stdexcept>

namespace rbm::benchmark {

io::FoamWriteOptions writeOptions(const std::string& format)
{
    io::FoamWriteOptions options;
    options.binary = format == "binaryGzip";
    options.compressed = format != "ascii";
    return options;
}

const std::vector<std::string>& meshFormats()
{
    static const std::vector<std::string> formats{"ascii", "asciiGzip", "binaryGzip"};
    return formats;
}

Record runMeshIoTask(const std::string& caseName, double size, const fs::path& caseDir, const fs::path& airfoilDir)
{
    Record record;
    record.set("task", "meshio");
    record.set("case", caseName);
    record.set("requestedSize", size);
    const CaseInfo& info = caseInfo(caseName);
    PolyMesh mesh;
    auto started = Clock::now();
    if (info.generated) {
        mesh = generateMesh(info, size);
        record.set("generateSeconds", secondsSince(started));
        started = Clock::now();
        validateTopology(mesh, caseName);
        record.set("validateSeconds", secondsSince(started));
    } else {
        mesh = io::readPolyMesh(airfoilDir / "constant" / "polyMesh");
        record.set("readCommittedSeconds", secondsSince(started));
    }
    record.set("points", mesh.pointCount());
    record.set("cells", mesh.cellCount());
    record.set("faces", mesh.faceCount());
    const bool twoD = detectPseudoTwoD(mesh) != PseudoTwoDKind::None;
    record.set("nodes", twoD ? mesh.pointCount() / 2.0 : mesh.pointCount());
    for (const std::string& format : meshFormats()) {
        const fs::path polyMeshDir = caseDir / format / "constant" / "polyMesh";
        started = Clock::now();
        io::writePolyMesh(polyMeshDir, mesh, writeOptions(format));
        record.set(format + "WriteSeconds", secondsSince(started));
        record.set(format + "MiB", static_cast<double>(directoryBytes(polyMeshDir)) / 1048576.0);
        started = Clock::now();
        const PolyMesh back = io::readPolyMesh(polyMeshDir);
        record.set(format + "ReadSeconds", secondsSince(started));
        if (back.pointCount() != mesh.pointCount() || back.faceCount() != mesh.faceCount())
            throw std::runtime_error("mesh read back from " + polyMeshDir.string() + " differs from the mesh written");
        started = Clock::now();
        io::writePolyMeshPoints(caseDir / format, "1", mesh.points, writeOptions(format));
        record.set(format + "WritePointsSeconds", secondsSince(started));
        started = Clock::now();
        const std::vector<Vector3> points = io::readPolyMeshPoints(caseDir / format / "1");
        record.set(format + "ReadPointsSeconds", secondsSince(started));
        fs::remove_all(caseDir / format / "1");
    }
    record.set("peakMemoryMiB", procStatusMiB("VmHWM"));
    return record;
}

} // namespace rbm::benchmark
