#include "VtkWriter.hpp"

#include "CellShape.hpp"
#include "VtkMessageCapture.hpp"
#include "WholeFile.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <iomanip>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace rbm::io {

namespace fs = std::filesystem;

namespace {

vtkNew<vtkDoubleArray> makeArray(const VtkField& field, std::size_t expectedTuples, const char* where)
{
    if (field.components < 1 || field.values.size() != expectedTuples * static_cast<std::size_t>(field.components)) {
        throw std::runtime_error("VTK " + std::string(where) + " field '" + field.name + "' has " +
                                 std::to_string(field.values.size()) + " values; expected " +
                                 std::to_string(expectedTuples) + " x " + std::to_string(field.components));
    }
    vtkNew<vtkDoubleArray> array;
    array->SetName(field.name.c_str());
    array->SetNumberOfComponents(field.components);
    array->SetNumberOfTuples(static_cast<vtkIdType>(expectedTuples));
    std::copy(field.values.begin(), field.values.end(), array->GetPointer(0));
    return array;
}

} // namespace

VtkCells vtkCellsOf(const PolyMesh& mesh, const MeshTopology& topology)
{
    VtkCells cells;
    const Label cellCount = topology.cellCount;
    cells.types.reserve(static_cast<std::size_t>(cellCount));
    cells.offsets.reserve(static_cast<std::size_t>(cellCount) + 1);
    cells.faceStreamOffsets.reserve(static_cast<std::size_t>(cellCount) + 1);
    cells.connectivity.reserve(topology.cellPoints.size());
    for (Label c = 0; c < cellCount; ++c) {
        cells.types.push_back(static_cast<std::uint8_t>(appendVtkCell(mesh, topology, c, cells.connectivity, cells.faceStream)));
        cells.offsets.push_back(static_cast<Label>(cells.connectivity.size()));
        cells.faceStreamOffsets.push_back(static_cast<Label>(cells.faceStream.size()));
    }
    return cells;
}

void writeVtu(const fs::path& file, const std::vector<Vector3>& points, const VtkCells& cells,
              const std::vector<VtkField>& pointFields, const std::vector<VtkField>& cellFields)
{
    vtkNew<vtkPoints> vtkPointSet;
    vtkPointSet->SetDataTypeToDouble();
    vtkPointSet->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
    for (std::size_t i = 0; i < points.size(); ++i) {
        vtkPointSet->SetPoint(static_cast<vtkIdType>(i), points[i].x, points[i].y, points[i].z);
    }

    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(vtkPointSet);
    grid->Allocate(cells.cellCount());
    std::vector<vtkIdType> ids;
    std::vector<vtkIdType> faceIds;
    for (Label c = 0; c < cells.cellCount(); ++c) {
        ids.assign(cells.connectivity.begin() + cells.offsets[c], cells.connectivity.begin() + cells.offsets[c + 1]);
        const Label faceBegin = cells.faceStreamOffsets.size() > static_cast<std::size_t>(c + 1) ? cells.faceStreamOffsets[c] : 0;
        const Label faceEnd = cells.faceStreamOffsets.size() > static_cast<std::size_t>(c + 1) ? cells.faceStreamOffsets[c + 1] : 0;
        if (faceEnd > faceBegin) {
            faceIds.assign(cells.faceStream.begin() + faceBegin + 1, cells.faceStream.begin() + faceEnd);
            grid->InsertNextCell(cells.types[c], static_cast<vtkIdType>(ids.size()), ids.data(),
                                 static_cast<vtkIdType>(cells.faceStream[faceBegin]), faceIds.data());
        } else {
            grid->InsertNextCell(cells.types[c], static_cast<vtkIdType>(ids.size()), ids.data());
        }
    }
    for (const VtkField& field : pointFields) grid->GetPointData()->AddArray(makeArray(field, points.size(), "point"));
    for (const VtkField& field : cellFields) {
        grid->GetCellData()->AddArray(makeArray(field, static_cast<std::size_t>(cells.cellCount()), "cell"));
    }

    // VTK writes into memory, and the bytes go to the file through replaceFileAtomically:
    // a temporary file renamed over the old one, so a reader never sees half a file, a failure
    // (a full disk) leaves the old file and no temporary, and the message names the file and
    // the OS reason. VTK's own messages, if any, become one line of the error.
    VtkMessageCapture capture;
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->WriteToOutputStringOn();
    writer->SetInputData(grid);
    writer->SetDataModeToAppended();
    writer->SetCompressorTypeToZLib();
    // zlib's fastest level, as for the .gz files (CompressedFile.cpp); VTK's default is 5.
    writer->SetCompressionLevel(1);
    if (writer->Write() != 1 || capture.hasErrors()) {
        throw std::runtime_error("VTK could not write " + file.string() + ": " + capture.summary());
    }
    replaceFileAtomically(file, writer->GetOutputString());
}

PvdCollection::PvdCollection(fs::path file) : file_(std::move(file)) {}

void PvdCollection::load()
{
    entries_.clear();
    // A missing file is an empty collection; a file that cannot be read is an error (taking
    // it for empty would drop its entries at the next write()).
    std::error_code error;
    if (!fs::exists(fs::symlink_status(file_, error))) return;
    const std::string text = readWholeFile(file_);
    const std::regex dataSet(R"re(<DataSet[^>]*timestep="([^"]*)"[^>]*file="([^"]*)")re");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), dataSet); it != std::sregex_iterator(); ++it) {
        add(std::stod((*it)[1].str()), (*it)[2].str());
    }
}

void PvdCollection::add(double time, const std::string& dataset)
{
    auto sameTime = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.time == time; });
    if (sameTime != entries_.end()) {
        sameTime->dataset = dataset;
        return;
    }
    entries_.push_back({time, dataset});
    std::stable_sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
}

void PvdCollection::write() const
{
    std::ostringstream xml;
    xml << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    xml << std::setprecision(17);
    for (const Entry& e : entries_) {
        xml << "    <DataSet timestep=\"" << e.time << "\" group=\"\" part=\"0\" file=\"" << e.dataset << "\"/>\n";
    }
    xml << "  </Collection>\n</VTKFile>\n";

    replaceFileAtomically(file_, xml.str());
}

} // namespace rbm::io
