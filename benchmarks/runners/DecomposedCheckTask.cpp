#include "DecomposedCheckTask.hpp"

#include "PolyMeshReader.hpp"
#include "QualityFields.hpp"
#include "QualityReport.hpp"
#include "ShortestEdges.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rbm::benchmark {

Record runDecomposedCheckTask(const fs::path& polyMeshDir, const fs::path& decomposedCase, int ranks,
                              const fs::path& serialCase, const std::string& prefix)
{
    const PolyMesh mesh = io::readPolyMesh(polyMeshDir);
    const std::size_t pointCount = mesh.points.size();
    std::vector<Vector3> gathered(pointCount, Vector3{std::nan(""), std::nan(""), std::nan("")});
    std::vector<Vector3> serial;
    if (!serialCase.empty()) serial = io::readPolyMeshPoints(serialCase / "1");
    const std::vector<double> shortest = serial.empty() ? std::vector<double>{} : test::shortestEdgeAtEachPoint(mesh);
    double worstRelative = 0.0;
    double worstAbsolute = 0.0;
    double sharedMismatch = 0.0;  // the same global point moved differently by two processors
    for (int rank = 0; rank < ranks; ++rank) {
        const fs::path processor = decomposedCase / ("processor" + std::to_string(rank));
        const std::vector<Vector3> points = io::readPolyMeshPoints(processor / "1");
        const std::vector<Label> addressing = io::readLabelListFile(
            processor / "constant" / "polyMesh" / "pointProcAddressing", "pointProcAddressing", pointCount);
        if (addressing.size() != points.size())
            throw std::runtime_error(processor.string() + ": pointProcAddressing and points differ in length");
        for (std::size_t i = 0; i < points.size(); ++i) {
            const auto g = static_cast<std::size_t>(addressing[i]);
            if (g >= pointCount) throw std::runtime_error(processor.string() + ": pointProcAddressing out of range");
            if (std::isfinite(gathered[g].x)) sharedMismatch = std::max(sharedMismatch, norm(points[i] - gathered[g]));
            else gathered[g] = points[i];
            if (!serial.empty()) {
                const double distance = norm(points[i] - serial[g]);
                worstAbsolute = std::max(worstAbsolute, distance);
                worstRelative = std::max(worstRelative, distance / shortest[g]);
            }
        }
    }
    std::size_t missing = 0;
    for (const Vector3& point : gathered) missing += std::isfinite(point.x) ? 0 : 1;
    if (missing > 0) throw std::runtime_error(std::to_string(missing) + " points are on no processor");

    Record record;
    record.set(prefix + "SharedPointMismatch", sharedMismatch);
    if (!serial.empty()) {
        record.set(prefix + "MaxDifferenceToSerial", worstAbsolute);
        record.set(prefix + "MaxDifferenceToSerialPerShortestEdge", worstRelative);
    }
    QualityEvaluator evaluator(mesh);
    addQuality(record, evaluator.evaluate(gathered), prefix + ".");
    return record;
}

} // namespace rbm::benchmark
