#include "QualityFields.hpp"

#include "PolyMeshReader.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rbm::benchmark {

void addQuality(Record& record, const QualityReport& report, const std::string& prefix)
{
    record.set(prefix + "invertedCells", static_cast<double>(report.invertedCellCount()));
    record.setFlag(prefix + "valid", report.isValid());
    record.set(prefix + "maxNonOrthogonality", report.checkMesh.maxNonOrthogonality);
    record.set(prefix + "maxSkewness", report.checkMesh.maxSkewness);
    record.set(prefix + "maxAspectRatio", report.checkMesh.maxAspectRatio);
    double shape = nan;
    const ThesisQuality& thesis = report.thesis;
    if (thesis.dimension == 2) {
        if (thesis.triangleMeanRatio.count > 0) shape = thesis.triangleMeanRatio.min;
        if (thesis.quadrilateralShape.count > 0)
            shape = std::isnan(shape) ? thesis.quadrilateralShape.min : std::min(shape, thesis.quadrilateralShape.min);
    }
    record.set(prefix + "minShapeQuality", shape);
}

void addResultQuality(Record& record, const fs::path& caseDir)
{
    try {
        const PolyMesh mesh = io::readPolyMesh(caseDir / "constant" / "polyMesh");
        const std::vector<Vector3> points = io::readPolyMeshPoints(caseDir / "1");
        QualityEvaluator evaluator(mesh);
        addQuality(record, evaluator.evaluate(points), "");
    } catch (const std::exception& error) {
        record.set("qualityError", error.what());
    }
}

} // namespace rbm::benchmark
