#include "MotionOutput.hpp"

#include "FoamDictionaryWriter.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"

#include <algorithm>
#include <filesystem>

namespace rbm::app {

void stageMeshMotion(io::TimeFolderWriter& folder, const std::string& timeName, const PolyMesh& mesh,
                     const std::vector<Vector3>& points, const std::vector<Vector3>& displacement,
                     const io::PointVectorField& field, const std::vector<std::uint8_t>& prescribedPatches,
                     const io::ControlDict& control)
{
    io::FoamWriteOptions pointOptions;
    pointOptions.binary = control.binary;
    pointOptions.precision = control.writePrecision;
    pointOptions.compressed = control.writeCompression;
    std::filesystem::create_directories(folder.staging() / "polyMesh");
    io::writePointsFile(folder.staging() / "polyMesh" / "points", points, timeName + "/polyMesh", pointOptions);

    std::vector<io::PointPatchFieldEntry> boundaryField = field.boundaryField;
    std::vector<Vector3> patchValues;
    for (std::size_t p = 0; p < boundaryField.size(); ++p) {
        io::PointPatchFieldEntry& entry = boundaryField[p];
        if (entry.type == "empty" || entry.type == "wedge") continue;
        if (!prescribedPatches[p] && !entry.dictionary.contains("value")) continue;
        const std::vector<Label> labels = io::patchPointLabels(mesh, static_cast<Label>(p));
        patchValues.resize(labels.size());
        for (std::size_t i = 0; i < labels.size(); ++i) patchValues[i] = displacement[static_cast<std::size_t>(labels[i])];
        entry.dictionary.set(io::vectorFieldEntry("value", patchValues));
    }
    io::PointVectorFieldWriteOptions fieldOptions;
    fieldOptions.dimensions = field.dimensions;
    fieldOptions.precision = std::max(control.writePrecision, 10);   // as the points: thin cells need the digits
    fieldOptions.compressed = control.writeCompression;
    fieldOptions.location = timeName;
    io::writePointVectorField(folder.staging() / "pointDisplacement", displacement, boundaryField, fieldOptions);
}

} // namespace rbm::app
