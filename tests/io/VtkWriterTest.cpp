#include "VtkWriter.hpp"

#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using rbm::Vector3;
using rbm::io::VtkCells;
using rbm::io::VtkField;

namespace {

fs::path freshDirectory(const std::string& name)
{
    const fs::path dir = fs::temp_directory_path() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// A unit cube (hexahedron) and a tetrahedron on top of it sharing the face z = 1,
// plus the same cube as a polyhedron, so all three cell-writing paths are used.
struct TwoCellExample {
    std::vector<Vector3> points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 2}};
    VtkCells cells;
    TwoCellExample()
    {
        cells.types = {VTK_HEXAHEDRON, VTK_TETRA, VTK_POLYHEDRON};
        cells.connectivity = {0, 1, 2, 3, 4, 5, 6, 7, 4, 5, 6, 8, 0, 1, 2, 3, 4, 5, 6, 7};
        cells.offsets = {0, 8, 12, 20};
        cells.faceStream = {6, 4, 0, 3, 2, 1, 4, 4, 5, 6, 7, 4, 0, 1, 5, 4, 4, 1, 2, 6, 5, 4, 2, 3, 7, 6, 4, 3, 0, 4, 7};
        cells.faceStreamOffsets = {0, 0, 0, static_cast<rbm::Label>(cells.faceStream.size())};
    }
};

} // namespace

TEST(VtkWriter, WrittenGridReadsBackWithCellsAndFields)
{
    const fs::path dir = freshDirectory("rbmVtkWriterTest");
    TwoCellExample example;
    VtkField displacement{"displacement", 3, {}};
    for (std::size_t i = 0; i < example.points.size(); ++i) {
        displacement.values.insert(displacement.values.end(), {0.1 * static_cast<double>(i), 0.0, -1.0});
    }
    VtkField quality{"quality", 1, {1.0, 0.5, 0.25}};
    rbm::io::writeVtu(dir / "mesh_0.vtu", example.points, example.cells, {displacement}, {quality});

    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir / "mesh_0.vtu").c_str());
    reader->Update();
    vtkUnstructuredGrid* grid = reader->GetOutput();
    ASSERT_EQ(grid->GetNumberOfPoints(), 9);
    ASSERT_EQ(grid->GetNumberOfCells(), 3);
    EXPECT_EQ(grid->GetCellType(0), VTK_HEXAHEDRON);
    EXPECT_EQ(grid->GetCellType(1), VTK_TETRA);
    EXPECT_EQ(grid->GetCellType(2), VTK_POLYHEDRON);
    EXPECT_EQ(grid->GetCell(2)->GetNumberOfFaces(), 6);
    double apex[3];
    grid->GetPoint(8, apex);
    EXPECT_DOUBLE_EQ(apex[2], 2.0);
    vtkDataArray* readDisplacement = grid->GetPointData()->GetArray("displacement");
    ASSERT_NE(readDisplacement, nullptr);
    EXPECT_DOUBLE_EQ(readDisplacement->GetComponent(7, 0), 0.7);
    EXPECT_DOUBLE_EQ(readDisplacement->GetComponent(7, 2), -1.0);
    vtkDataArray* readQuality = grid->GetCellData()->GetArray("quality");
    ASSERT_NE(readQuality, nullptr);
    EXPECT_DOUBLE_EQ(readQuality->GetComponent(1, 0), 0.5);
    EXPECT_FALSE(fs::exists(dir / "mesh_0.vtu.tmp"));
    fs::remove_all(dir);
}

TEST(VtkWriter, FieldOfWrongLengthIsRejected)
{
    const fs::path dir = freshDirectory("rbmVtkWriterTestWrongLength");
    TwoCellExample example;
    VtkField quality{"quality", 1, {1.0, 0.5}};
    EXPECT_THROW(rbm::io::writeVtu(dir / "bad.vtu", example.points, example.cells, {}, {quality}), std::runtime_error);
    EXPECT_FALSE(fs::exists(dir / "bad.vtu"));
    fs::remove_all(dir);
}

TEST(PvdCollection, EntriesAreSortedReplacedAndReloaded)
{
    const fs::path dir = freshDirectory("rbmPvdTest");
    rbm::io::PvdCollection series(dir / "case.pvd");
    series.add(0.5, "VTK/case_0.5.vtu");
    series.add(0.0, "VTK/case_0.vtu");
    series.add(0.5, "VTK/case_0.5b.vtu");
    series.write();
    EXPECT_EQ(series.size(), 2u);

    std::ifstream in(dir / "case.pvd");
    std::stringstream text;
    text << in.rdbuf();
    const std::string xml = text.str();
    EXPECT_LT(xml.find("case_0.vtu"), xml.find("case_0.5b.vtu"));
    EXPECT_EQ(xml.find("case_0.5.vtu"), std::string::npos);

    rbm::io::PvdCollection reloaded(dir / "case.pvd");
    reloaded.load();
    EXPECT_EQ(reloaded.size(), 2u);
    reloaded.add(1.0, "VTK/case_1.vtu");
    EXPECT_EQ(reloaded.size(), 3u);
    fs::remove_all(dir);
}

TEST(VtkWriter, HexBoxCellsAreWrittenAsHexahedraWithPositiveVolume)
{
    const rbm::PolyMesh mesh = rbm::makeHexBox(3, 2, 2, {0, 0, 0}, {3, 2, 2});
    const rbm::MeshTopology topology = rbm::buildMeshTopology(mesh);
    const VtkCells cells = rbm::io::vtkCellsOf(mesh, topology);
    ASSERT_EQ(cells.cellCount(), 12);
    for (rbm::Label c = 0; c < cells.cellCount(); ++c) {
        EXPECT_EQ(cells.types[c], VTK_HEXAHEDRON);
        EXPECT_EQ(cells.offsets[c + 1] - cells.offsets[c], 8);
    }
    const fs::path dir = freshDirectory("rbmVtkWriterHexBox");
    rbm::io::writeVtu(dir / "box.vtu", mesh.points, cells, {}, {});
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir / "box.vtu").c_str());
    reader->Update();
    vtkUnstructuredGrid* grid = reader->GetOutput();
    ASSERT_EQ(grid->GetNumberOfCells(), 12);
    // Cell 5 is a unit cube of the 3 x 2 x 2 box.
    double bounds[6];
    grid->GetCell(5)->GetBounds(bounds);
    EXPECT_DOUBLE_EQ(bounds[1] - bounds[0], 1.0);
    EXPECT_DOUBLE_EQ(bounds[3] - bounds[2], 1.0);
    EXPECT_DOUBLE_EQ(bounds[5] - bounds[4], 1.0);
    fs::remove_all(dir);
}
