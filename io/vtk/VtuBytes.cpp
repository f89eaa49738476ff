// librbm_vtk.so: the .vtu bytes of a grid through VTK's XML writer (VtuBytes.hpp).

#include "VtuBytes.hpp"

#include "VtkMessageCapture.hpp"

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
#include <exception>
#include <stdexcept>

namespace rbm::io {

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

void buildVtuBytes(VtuRequest& request)
{
    const std::vector<Vector3>& points = *request.points;
    const VtkCells& cells = *request.cells;
    const std::vector<VtkField>& pointFields = *request.pointFields;
    const std::vector<VtkField>& cellFields = *request.cellFields;
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

    // VTK writes into memory; writeVtu puts the bytes in the file (atomically). VTK's own
    // messages, if any, become one line of the error.
    VtkMessageCapture capture;
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->WriteToOutputStringOn();
    writer->SetInputData(grid);
    writer->SetDataModeToAppended();
    writer->SetCompressorTypeToZLib();
    // zlib's fastest level, as for the .gz files (CompressedFile.cpp); VTK's default is 5.
    writer->SetCompressionLevel(1);
    if (writer->Write() != 1 || capture.hasErrors()) throw std::runtime_error(capture.summary());
    request.bytes = writer->GetOutputString();
}

} // namespace

} // namespace rbm::io

extern "C" bool rbmVtuBytes(rbm::io::VtuRequest* request)
{
    try {
        rbm::io::buildVtuBytes(*request);
        return true;
    } catch (const std::exception& error) {
        request->error = error.what();
    } catch (...) {
        request->error = "unknown error";
    }
    return false;
}
