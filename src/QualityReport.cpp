#include "QualityReport.hpp"

#include "CellShape.hpp"
#include "InputError.hpp"
#include "InvertedCell.hpp"
#include "ThreadCount.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

namespace rbm {

QualityEvaluator::QualityEvaluator(const PolyMesh& mesh) : QualityEvaluator(mesh, buildMeshTopology(mesh), nullptr) {}

QualityEvaluator::QualityEvaluator(const PolyMesh& mesh, MeshTopology topology, const PseudoTwoDMesh* twoD)
    : mesh_(mesh), topology_(std::move(topology))
{
    pseudoTwoD_ = detectPseudoTwoD(mesh_);
    if (twoD && pseudoTwoD_ != PseudoTwoDKind::None) {
        twoD_ = twoD;
    } else if (pseudoTwoD_ != PseudoTwoDKind::None) {
        try {
            ownTwoD_ = std::make_unique<PseudoTwoDMesh>(extractPseudoTwoD(mesh_, topology_));
            twoD_ = ownTwoD_.get();
        } catch (const InputError& error) {
            // Not a clean one-layer extrusion: the thesis metrics fall back to 3D, and the
            // report says why.
            twoDExtractionProblem_ = error.message();
        }
    }
}

const MeshGeometry& QualityEvaluator::geometryAt(std::span<const Vector3> points)
{
    if (geometryStale_) {
        updateMeshGeometry(mesh_, points, geometry_);
        geometryStale_ = false;
    }
    return geometry_;
}

const MeshTopology& QualityEvaluator::topology() const
{
    if (topologyHeld_ != TopologyHeld::whole) {
        topology_ = buildMeshTopology(mesh_);
        topologyHeld_ = TopologyHeld::whole;
    }
    return topology_;
}

const MeshTopology& QualityEvaluator::cellFaceTopology() const
{
    if (topologyHeld_ == TopologyHeld::none) {
        topology_ = buildCellFaceTopology(mesh_);
        topologyHeld_ = TopologyHeld::cellFacesOnly;
    }
    return topology_;
}

void QualityEvaluator::releaseWorkspaces()
{
    topology_ = MeshTopology{};
    topologyHeld_ = TopologyHeld::none;
    geometry_ = MeshGeometry{};
    geometryStale_ = true;
    checkMeshWorkspace_ = CheckMeshWorkspace{};
    thesisWorkspace_ = ThesisQualityWorkspace{};
    nodePositions_ = std::vector<Vector3>{};
    extremesWorkspace_ = CheckMeshExtremesWorkspace{};
    extrusionWorkspace_ = ExtrusionExtremesWorkspace{};
    cellValues_ = std::vector<double>{};
    cellInverted_ = std::vector<std::uint8_t>{};
}

QualityReport QualityEvaluator::evaluate(std::span<const Vector3> points)
{
    updateMeshGeometry(mesh_, points, geometry_);
    geometryStale_ = false;

    QualityReport report;
    report.pointCount = mesh_.pointCount();
    report.faceCount = mesh_.faceCount();
    report.internalFaceCount = mesh_.internalFaceCount();
    report.cellCount = static_cast<Label>(geometry_.cellVolumes.size());
    report.facesPerCell = report.cellCount > 0 ? (static_cast<double>(report.faceCount) + report.internalFaceCount) /
                                                     static_cast<double>(report.cellCount)
                                               : 0.0;
    report.patchCount = static_cast<Label>(mesh_.patches.size());
    report.pointZoneCount = static_cast<Label>(mesh_.pointZones.size());
    report.faceZoneCount = static_cast<Label>(mesh_.faceZones.size());
    report.cellZoneCount = static_cast<Label>(mesh_.cellZones.size());
    if (!haveCellShapeCounts_) {
        const auto counts = countCellShapes(mesh_, topology());
        for (std::size_t i = 0; i < cellShapeCounts_.size() && i < counts.size(); ++i) cellShapeCounts_[i] = counts[i];
        haveCellShapeCounts_ = true;
    }
    report.cellShapeCounts = cellShapeCounts_;
    report.pseudoTwoD = pseudoTwoD_;
    report.twoDExtractionProblem = twoDExtractionProblem_;

    report.checkMesh = computeCheckMeshQuality(mesh_, points, geometry_, checkMeshWorkspace_);

    if (twoD_) {
        // 2D node positions: the front-plane points in the plane's frame.
        const Label nodes = twoD_->nodeCount();
        nodePositions_.resize(static_cast<std::size_t>(nodes));
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(nodes)))
        for (Label n = 0; n < nodes; ++n) nodePositions_[n] = twoD_->frame.toLocal(points[twoD_->frontPointOfNode[n]]);
        report.thesis = computeThesisQuality2D(twoD_->planar, nodePositions_, thesisWorkspace_);
    } else {
        report.thesis = computeThesisQuality3D(mesh_, geometry_, thesisWorkspace_);
    }
    return report;
}

namespace {

// 2D: each cell's q (triangles) or F_shape (quadrilaterals) and whether it is inverted, by
// threads (each writes its own slots), from the front-plane points in the plane's frame.
void evaluatePlanarCells(const PseudoTwoDMesh& twoD, std::span<const Vector3> points, std::vector<Vector3>& nodePositions,
                         std::vector<double>& cellValues, std::vector<std::uint8_t>& cellInverted)
{
    const PlanarMesh& planar = twoD.planar;
    const Label nodes = twoD.nodeCount();
    nodePositions.resize(static_cast<std::size_t>(nodes));
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(nodes)))
    for (Label n = 0; n < nodes; ++n) nodePositions[n] = twoD.frame.toLocal(points[twoD.frontPointOfNode[n]]);
    const std::span<const Vector3> positions = nodePositions;
    const Label cellCount = planar.cellCount();
    cellValues.resize(static_cast<std::size_t>(cellCount));
    cellInverted.resize(static_cast<std::size_t>(cellCount));
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(cellCount)))
    for (Label c = 0; c < cellCount; ++c) {
        const auto polygon = planar.cell(c);
        double area = 0.0;
        const Vector3 centroid = polygonCentroid(polygon, positions, area);
        cellInverted[c] = isInvertedPolygon(area, smallestEdgeTriangle(polygon, positions, centroid));
        if (polygon.size() == 3) {
            cellValues[c] = triangleMeanRatio(positions[polygon[0]], positions[polygon[1]], positions[polygon[2]]);
        } else if (polygon.size() == 4) {
            cellValues[c] = quadrilateralShape(positions[polygon[0]], positions[polygon[1]], positions[polygon[2]],
                                               positions[polygon[3]]);
        }
    }
}

// 2D: the inverted cells and the worst shape, in cell order as computeThesisQuality2D takes them.
void summarisePlanarCells(const PlanarMesh& planar, const std::vector<double>& cellValues,
                          const std::vector<std::uint8_t>& cellInverted, StepQuality& quality)
{
    // StatisticsAccumulator's minimum of each shape, then the smaller of the two.
    StatisticsAccumulator triangles;
    StatisticsAccumulator quadrilaterals;
    for (Label c = 0; c < planar.cellCount(); ++c) {
        if (cellInverted[c]) ++quality.invertedCellCount;
        const std::size_t size = planar.cell(c).size();
        if (size == 3) triangles.add(cellValues[c]);
        else if (size == 4) quadrilaterals.add(cellValues[c]);
    }
    const QualityStatistics t = triangles.result();
    const QualityStatistics q = quadrilaterals.result();
    double worst = std::numeric_limits<double>::quiet_NaN();
    if (t.count > 0) worst = t.min;
    if (q.count > 0) worst = std::isnan(worst) ? q.min : std::min(worst, q.min);
    quality.worstCellQuality = worst;
}

// 3D: each cell's smallest face pyramid relative to the mean and whether it is inverted, by threads.
void evaluatePyramidCells(const PolyMesh& mesh, const MeshTopology& topology, const MeshGeometry& geometry,
                          std::vector<double>& cellValues, std::vector<std::uint8_t>& cellInverted)
{
    // The face pyramids of every cell with apex at its centre (ThesisQuality's inverted
    // cells: a pyramid or the volume <= 0), and their smallest relative to the mean pyramid.
    const Label cellCount = static_cast<Label>(geometry.cellVolumes.size());
    cellValues.resize(static_cast<std::size_t>(cellCount));
    cellInverted.resize(static_cast<std::size_t>(cellCount));
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(cellCount)))
    for (Label c = 0; c < cellCount; ++c) {
        const Vector3& centre = geometry.cellCentres[c];
        double smallest = std::numeric_limits<double>::infinity();   // 3 × the smallest pyramid
        const auto faces = topology.facesOf(c);
        for (const Label f : faces) {
            const Vector3& S = geometry.faceAreas[f];
            const Vector3& fc = geometry.faceCentres[f];
            smallest = std::min(smallest, tripleFacePyramid(S, fc, centre, mesh.owner[f] == c));
        }
        const double volume = geometry.cellVolumes[c];
        cellInverted[c] = isInvertedCell(volume, smallest);
        cellValues[c] =
            std::abs(volume) > 0.0 ? static_cast<double>(faces.size()) * (smallest / 3.0) / std::abs(volume) : 0.0;
    }
}

// 3D: the inverted cells and the smallest value, in cell order.
void summarisePyramidCells(const std::vector<double>& cellValues, const std::vector<std::uint8_t>& cellInverted,
                           StepQuality& quality)
{
    const Label cellCount = static_cast<Label>(cellValues.size());
    double worst = std::numeric_limits<double>::quiet_NaN();
    for (Label c = 0; c < cellCount; ++c) {
        if (cellInverted[c]) ++quality.invertedCellCount;
        worst = c == 0 ? cellValues[c] : std::min(worst, cellValues[c]);
    }
    quality.worstCellQuality = worst;
}

} // namespace

StepQuality QualityEvaluator::evaluateStep(std::span<const Vector3> points)
{
    StepQuality quality;
    // A one-layer extrusion between empty planes, still one to rounding: checkMesh's two extremes
    // from the 2D positions (computeExtrusionCheckMeshExtremes), without the 3D geometry, which
    // geometryAt() then computes if asked. Otherwise OpenFOAM's decompositions.
    std::optional<CheckMeshExtremes> extremes;
    if (twoD_) extremes = computeExtrusionCheckMeshExtremes(mesh_, *twoD_, points, extrusionWorkspace_);
    if (extremes) {
        geometryStale_ = true;
    } else {
        updateMeshGeometry(mesh_, points, geometry_);
        geometryStale_ = false;
        extremes = computeCheckMeshExtremes(mesh_, points, geometry_, extremesWorkspace_);
    }
    quality.maxNonOrthogonality = extremes->maxNonOrthogonality;
    quality.maxSkewness = extremes->maxSkewness;

    // Per cell by threads (each writes its own slots), then the minima and the count in cell
    // order, as computeThesisQuality2D/3D take them: the same figures for any thread count.
    if (twoD_) {
        evaluatePlanarCells(*twoD_, points, nodePositions_, cellValues_, cellInverted_);
        summarisePlanarCells(twoD_->planar, cellValues_, cellInverted_, quality);
        return quality;
    }
    evaluatePyramidCells(mesh_, cellFaceTopology(), geometry_, cellValues_, cellInverted_);
    summarisePyramidCells(cellValues_, cellInverted_, quality);
    return quality;
}

QualityReport computeQualityReport(const PolyMesh& mesh)
{
    QualityEvaluator evaluator(mesh);
    return evaluator.evaluate();
}

namespace {

// OpenFOAM's default stream formatting: 6 significant digits, general notation.
std::string number(double value)
{
    std::ostringstream os;
    os.precision(6);
    os << value;
    return os.str();
}

std::string vector(const Vector3& v) { return "(" + number(v.x) + " " + number(v.y) + " " + number(v.z) + ")"; }

std::string directions(const std::array<int, 3>& d)
{
    return "(" + std::to_string(d[0]) + " " + std::to_string(d[1]) + " " + std::to_string(d[2]) + ")";
}

const char* pseudoTwoDName(PseudoTwoDKind kind)
{
    switch (kind) {
    case PseudoTwoDKind::Empty: return "empty";
    case PseudoTwoDKind::Wedge: return "wedge";
    default: return "none";
    }
}

std::string padded(const std::string& text, std::size_t width)
{
    return text.size() >= width ? text : text + std::string(width - text.size(), ' ');
}

std::string rightAligned(const std::string& text, std::size_t width)
{
    return text.size() >= width ? text : std::string(width - text.size(), ' ') + text;
}

void appendStatisticsRow(std::ostringstream& os, const std::string& name, const QualityStatistics& s)
{
    os << "    " << padded(name, 28) << rightAligned(std::to_string(s.count), 9);
    if (s.count == 0) {
        os << rightAligned("-", 13) << rightAligned("-", 13) << rightAligned("-", 13) << rightAligned("-", 13) << '\n';
        return;
    }
    os << rightAligned(number(s.mean), 13) << rightAligned(number(s.standardDeviation), 13)
       << rightAligned(number(s.min), 13) << rightAligned(number(s.max), 13) << '\n';
}

// Mesh stats and the number of cells of each shape.
void appendMeshStats(std::ostringstream& os, const QualityReport& r)
{
    os << "Mesh stats\n"
       << "    points:           " << r.pointCount << '\n'
       << "    faces:            " << r.faceCount << '\n'
       << "    internal faces:   " << r.internalFaceCount << '\n'
       << "    cells:            " << r.cellCount << '\n'
       << "    faces per cell:   " << number(r.facesPerCell) << '\n'
       << "    boundary patches: " << r.patchCount << '\n'
       << "    point zones:      " << r.pointZoneCount << '\n'
       << "    face zones:       " << r.faceZoneCount << '\n'
       << "    cell zones:       " << r.cellZoneCount << "\n\n";

    os << "Overall number of cells of each type:\n"
       << "    hexahedra:     " << r.cellShapeCounts[static_cast<int>(CellShape::Hexahedron)] << '\n'
       << "    prisms:        " << r.cellShapeCounts[static_cast<int>(CellShape::Prism)] << '\n'
       << "    pyramids:      " << r.cellShapeCounts[static_cast<int>(CellShape::Pyramid)] << '\n'
       << "    tetrahedra:    " << r.cellShapeCounts[static_cast<int>(CellShape::Tetrahedron)] << '\n'
       << "    polyhedra:     " << r.cellShapeCounts[static_cast<int>(CellShape::Polyhedron)] << "\n\n";
}

// Whether the mesh is 2D (and so where the thesis metrics are measured).
void appendDimension(std::ostringstream& os, const QualityReport& r)
{
    if (r.thesis.dimension == 2) {
        os << "Mesh is 2D: one layer of cells between " << pseudoTwoDName(r.pseudoTwoD)
           << " planes; thesis metrics on the 2D mesh.\n\n";
    } else if (r.pseudoTwoD != PseudoTwoDKind::None) {
        os << "Mesh has " << pseudoTwoDName(r.pseudoTwoD)
           << " patches but is not a clean one-layer extrusion; thesis metrics in 3D.\n    "
           << r.twoDExtractionProblem << "\n\n";
    } else {
        os << "Mesh is 3D.\n\n";
    }
}

// checkMesh's geometry: bounding box, directions, closedness, face areas and cell volumes.
void appendGeometrySizes(std::ostringstream& os, const CheckMeshQuality& q)
{
    os << "Checking geometry (checkMesh's definitions)...\n"
       << "    Overall domain bounding box " << vector(q.boundingBoxMin) << " " << vector(q.boundingBoxMax) << '\n'
       << "    Mesh has " << q.geometricDimensionCount() << " geometric (non-empty/wedge) directions "
       << directions(q.geometricDirections) << '\n'
       << "    Mesh has " << q.solutionDimensionCount() << " solution (non-empty) directions "
       << directions(q.solutionDirections) << '\n';

    double largestOpenness = 0.0;
    for (int i = 0; i < 3; ++i) largestOpenness = std::max(largestOpenness, std::abs(q.boundaryOpenness[i]));
    if (largestOpenness > CheckMeshQuality::closedThreshold) {
        os << " ***Boundary openness " << vector(q.boundaryOpenness) << " possible hole in boundary description.\n";
    } else {
        os << "    Boundary openness " << vector(q.boundaryOpenness) << " OK.\n";
    }
    if (q.openCellCount > 0) {
        os << " ***Open cells found, max cell openness: " << number(q.maxCellOpenness) << ", number of open cells "
           << q.openCellCount << '\n';
    } else if (q.highAspectRatioCellCount > 0) {
        os << " ***High aspect ratio cells found, Max aspect ratio: " << number(q.maxAspectRatio)
           << ", number of cells " << q.highAspectRatioCellCount << '\n';
    } else {
        os << "    Max cell openness = " << number(q.maxCellOpenness) << " OK.\n"
           << "    Max aspect ratio = " << number(q.maxAspectRatio) << " OK.\n";
    }
    if (q.zeroAreaFaceCount > 0) {
        os << " ***Zero or negative face area detected.  Minimum area: " << number(q.minFaceArea) << '\n';
    } else {
        os << "    Minimum face area = " << number(q.minFaceArea) << ". Maximum face area = " << number(q.maxFaceArea)
           << ".  Face area magnitudes OK.\n";
    }
    if (q.nonPositiveVolumeCellCount > 0) {
        os << " ***Zero or negative cell volume detected.  Minimum negative volume: " << number(q.minCellVolume)
           << ", Number of negative volume cells: " << q.nonPositiveVolumeCellCount << '\n';
    } else {
        os << "    Min volume = " << number(q.minCellVolume) << ". Max volume = " << number(q.maxCellVolume)
           << ".  Total volume = " << number(q.totalVolume) << ".  Cell volumes OK.\n";
    }
}

// checkMesh's geometry: non-orthogonality, face pyramids, skewness, weights and volume ratios.
void appendGeometryShapes(std::ostringstream& os, const CheckMeshQuality& q)
{
    if (q.internalFaceCount > 0) {
        os << "    Mesh non-orthogonality Max: " << number(q.maxNonOrthogonality)
           << " average: " << number(q.averageNonOrthogonality) << '\n';
    }
    if (q.severelyNonOrthogonalFaceCount > 0) {
        os << "   *Number of severely non-orthogonal (> " << number(CheckMeshQuality::nonOrthogonalityThreshold)
           << " degrees) faces: " << q.severelyNonOrthogonalFaceCount << ".\n";
    }
    if (q.nonOrthogonalityErrorCount > 0) {
        os << " ***Number of non-orthogonality errors: " << q.nonOrthogonalityErrorCount << ".\n";
    } else {
        os << "    Non-orthogonality check OK.\n";
    }
    if (q.incorrectlyOrientedPyramidCount > 0) {
        os << " ***Error in face pyramids: " << q.incorrectlyOrientedPyramidCount << " faces are incorrectly oriented.\n";
    } else {
        os << "    Face pyramids OK.\n";
    }
    if (q.severelySkewFaceCount > 0) {
        os << " ***Max skewness = " << number(q.maxSkewness) << ", " << q.severelySkewFaceCount
           << " highly skew faces detected which may impair the quality of the results\n";
    } else {
        os << "    Max skewness = " << number(q.maxSkewness) << " OK.\n";
    }
    if (q.internalFaceCount > 0) {
        os << "    Face interpolation weight : minimum: " << number(q.minFaceWeight)
           << " average: " << number(q.averageFaceWeight) << '\n'
           << "    Face volume ratio : minimum: " << number(q.minVolumeRatio)
           << " average: " << number(q.averageVolumeRatio) << '\n';
    }
}

// The thesis' metrics table and the inverted cells.
void appendThesisMetrics(std::ostringstream& os, const ThesisQuality& t)
{
    os << "\nThesis quality metrics (" << t.dimension << "D, thesis section 2.7):\n"
       << "    " << padded("metric", 28) << rightAligned("count", 9) << rightAligned("mean", 13)
       << rightAligned("std", 13) << rightAligned("min", 13) << rightAligned("max", 13) << '\n';
    if (t.dimension == 2) {
        appendStatisticsRow(os, "mean ratio q (triangles)", t.triangleMeanRatio);
        appendStatisticsRow(os, "F_shape (quadrilaterals)", t.quadrilateralShape);
    }
    appendStatisticsRow(os, "non-orthogonality [deg]", t.nonOrthogonality);
    appendStatisticsRow(os, "skewness", t.skewness);
    if (t.dimension == 2 && t.otherPolygonCount > 0) {
        os << "    polygons with 5+ nodes (no shape metric): " << t.otherPolygonCount << '\n';
    }
    if (t.invertedCellCount > 0) {
        os << " ***Inverted cells: " << t.invertedCellCount << " of " << t.cellCount << '\n';
    } else {
        os << "    Inverted cells: 0\n";
    }
}

// The last line: failed checks, inverted cells or OK.
void appendVerdict(std::ostringstream& os, const QualityReport& r)
{
    const CheckMeshQuality& q = r.checkMesh;
    const int failed = q.failedCheckCount();
    os << '\n';
    if (failed > 0) {
        os << "Failed " << failed << " mesh checks.\n";
    } else if (!r.isValid()) {
        os << "Failed: the mesh has inverted cells.\n";
    } else {
        os << "Mesh OK.\n";
    }
}

} // namespace

std::string formatQualityReport(const QualityReport& r)
{
    std::ostringstream os;
    appendMeshStats(os, r);
    appendDimension(os, r);
    appendGeometrySizes(os, r.checkMesh);
    appendGeometryShapes(os, r.checkMesh);
    appendThesisMetrics(os, r.thesis);
    appendVerdict(os, r);
    return os.str();
}

namespace {

// Shortest round-trip representation; null for NaN and infinities (JSON has neither).
std::string jsonNumber(double value)
{
    if (!std::isfinite(value)) return "null";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string jsonVector(const Vector3& v)
{
    return "[" + jsonNumber(v.x) + ", " + jsonNumber(v.y) + ", " + jsonNumber(v.z) + "]";
}

std::string jsonDirections(const std::array<int, 3>& d)
{
    return "[" + std::to_string(d[0]) + ", " + std::to_string(d[1]) + ", " + std::to_string(d[2]) + "]";
}

std::string jsonStatistics(const QualityStatistics& s)
{
    if (s.count == 0) return "{\"count\": 0, \"mean\": null, \"standardDeviation\": null, \"min\": null, \"max\": null}";
    return "{\"count\": " + std::to_string(s.count) + ", \"mean\": " + jsonNumber(s.mean) +
           ", \"standardDeviation\": " + jsonNumber(s.standardDeviation) + ", \"min\": " + jsonNumber(s.min) +
           ", \"max\": " + jsonNumber(s.max) + "}";
}

std::string jsonString(const std::string& text)
{
    std::string out = "\"";
    for (char c : text) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char escaped[8];
                std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
                out += escaped;
            } else {
                out += c;
            }
        }
    }
    return out + "\"";
}

// The JSON members before "checkMesh": the mesh's sizes, cell types and dimension.
void appendJsonMesh(std::ostringstream& os, const QualityReport& r)
{
    os << "  \"mesh\": {\"points\": " << r.pointCount << ", \"faces\": " << r.faceCount
       << ", \"internalFaces\": " << r.internalFaceCount << ", \"cells\": " << r.cellCount
       << ", \"facesPerCell\": " << jsonNumber(r.facesPerCell) << ", \"boundaryPatches\": " << r.patchCount
       << ", \"pointZones\": " << r.pointZoneCount << ", \"faceZones\": " << r.faceZoneCount
       << ", \"cellZones\": " << r.cellZoneCount << "},\n"
       << "  \"cellTypes\": {\"hexahedra\": " << r.cellShapeCounts[static_cast<int>(CellShape::Hexahedron)]
       << ", \"prisms\": " << r.cellShapeCounts[static_cast<int>(CellShape::Prism)]
       << ", \"pyramids\": " << r.cellShapeCounts[static_cast<int>(CellShape::Pyramid)]
       << ", \"tetrahedra\": " << r.cellShapeCounts[static_cast<int>(CellShape::Tetrahedron)]
       << ", \"polyhedra\": " << r.cellShapeCounts[static_cast<int>(CellShape::Polyhedron)] << "},\n"
       << "  \"dimension\": " << r.thesis.dimension << ",\n"
       << "  \"pseudoTwoD\": " << jsonString(pseudoTwoDName(r.pseudoTwoD)) << ",\n";
    if (!r.twoDExtractionProblem.empty()) {
        os << "  \"twoDExtractionProblem\": " << jsonString(r.twoDExtractionProblem) << ",\n";
    }
}

// The JSON "checkMesh" object.
void appendJsonCheckMesh(std::ostringstream& os, const CheckMeshQuality& q)
{
    os << "  \"checkMesh\": {\n"
       << "    \"boundingBox\": {\"min\": " << jsonVector(q.boundingBoxMin) << ", \"max\": " << jsonVector(q.boundingBoxMax)
       << "},\n"
       << "    \"geometricDirections\": " << jsonDirections(q.geometricDirections) << ",\n"
       << "    \"solutionDirections\": " << jsonDirections(q.solutionDirections) << ",\n"
       << "    \"boundaryOpenness\": " << jsonVector(q.boundaryOpenness) << ",\n"
       << "    \"maxCellOpenness\": " << jsonNumber(q.maxCellOpenness) << ",\n"
       << "    \"openCells\": " << q.openCellCount << ",\n"
       << "    \"maxAspectRatio\": " << jsonNumber(q.maxAspectRatio) << ",\n"
       << "    \"highAspectRatioCells\": " << q.highAspectRatioCellCount << ",\n"
       << "    \"minFaceArea\": " << jsonNumber(q.minFaceArea) << ",\n"
       << "    \"maxFaceArea\": " << jsonNumber(q.maxFaceArea) << ",\n"
       << "    \"zeroAreaFaces\": " << q.zeroAreaFaceCount << ",\n"
       << "    \"minVolume\": " << jsonNumber(q.minCellVolume) << ",\n"
       << "    \"maxVolume\": " << jsonNumber(q.maxCellVolume) << ",\n"
       << "    \"totalVolume\": " << jsonNumber(q.totalVolume) << ",\n"
       << "    \"nonPositiveVolumeCells\": " << q.nonPositiveVolumeCellCount << ",\n"
       << "    \"maxNonOrthogonality\": " << jsonNumber(q.maxNonOrthogonality) << ",\n"
       << "    \"averageNonOrthogonality\": " << jsonNumber(q.averageNonOrthogonality) << ",\n"
       << "    \"severelyNonOrthogonalFaces\": " << q.severelyNonOrthogonalFaceCount << ",\n"
       << "    \"nonOrthogonalityErrors\": " << q.nonOrthogonalityErrorCount << ",\n"
       << "    \"incorrectlyOrientedFaces\": " << q.incorrectlyOrientedPyramidCount << ",\n"
       << "    \"maxSkewness\": " << jsonNumber(q.maxSkewness) << ",\n"
       << "    \"severelySkewFaces\": " << q.severelySkewFaceCount << ",\n"
       << "    \"minFaceWeight\": " << jsonNumber(q.minFaceWeight) << ",\n"
       << "    \"averageFaceWeight\": " << jsonNumber(q.averageFaceWeight) << ",\n"
       << "    \"minVolumeRatio\": " << jsonNumber(q.minVolumeRatio) << ",\n"
       << "    \"averageVolumeRatio\": " << jsonNumber(q.averageVolumeRatio) << ",\n"
       << "    \"failedChecks\": " << q.failedCheckCount() << "\n"
       << "  },\n";
}

// The JSON "thesis" object.
void appendJsonThesis(std::ostringstream& os, const ThesisQuality& t)
{
    os << "  \"thesis\": {\n"
       << "    \"dimension\": " << t.dimension << ",\n"
       << "    \"cells\": " << t.cellCount << ",\n";
    if (t.dimension == 2) {
        os << "    \"triangleMeanRatio\": " << jsonStatistics(t.triangleMeanRatio) << ",\n"
           << "    \"quadrilateralShape\": " << jsonStatistics(t.quadrilateralShape) << ",\n"
           << "    \"otherPolygons\": " << t.otherPolygonCount << ",\n";
    }
    os << "    \"nonOrthogonality\": " << jsonStatistics(t.nonOrthogonality) << ",\n"
       << "    \"skewness\": " << jsonStatistics(t.skewness) << ",\n"
       << "    \"invertedCells\": " << t.invertedCellCount << "\n"
       << "  },\n";
}

} // namespace

std::string qualityReportJson(const QualityReport& r)
{
    std::ostringstream os;
    os << "{\n";
    appendJsonMesh(os, r);
    appendJsonCheckMesh(os, r.checkMesh);
    appendJsonThesis(os, r.thesis);
    os << "  \"invertedCells\": " << r.thesis.invertedCellCount << ",\n"
       << "  \"failedChecks\": " << r.checkMesh.failedCheckCount() << ",\n"
       << "  \"valid\": " << (r.isValid() ? "true" : "false") << "\n"
       << "}\n";
    return os.str();
}

} // namespace rbm
