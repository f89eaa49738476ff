// Tests of the mesh geometry (src/MeshGeometry): face areas and centres, cell volumes and centres.

#include "CheckMeshQuality.hpp"
#include "MeshGenerators.hpp"
#include "MeshGeometry.hpp"
#include "PlanarMesh.hpp"
#include "PolyMeshReader.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "QualityReport.hpp"
#include "TestCases.hpp"
#include "ThesisQuality.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <map>
#include <numbers>
#include <tuple>
#include <vector>

using namespace rbm::test::qualityCases;

namespace {

TEST(MeshGeometry, UnitCubeHasVolumeOneAndCentreAtItsMiddle)
{
    const PolyMesh mesh = buildMesh(unitCubePoints(), {hexFaces()});
    const auto g = rbm::computeMeshGeometry(mesh);
    ASSERT_EQ(g.cellVolumes.size(), 1u);
    EXPECT_NEAR(g.cellVolumes[0], 1.0, 1e-15);
    EXPECT_NEAR(g.cellCentres[0].x, 0.5, 1e-15);
    EXPECT_NEAR(g.cellCentres[0].y, 0.5, 1e-15);
    EXPECT_NEAR(g.cellCentres[0].z, 0.5, 1e-15);
    for (Label f = 0; f < mesh.faceCount(); ++f) {
        // Unit outward area vectors; centres on the face planes at the face middles.
        EXPECT_NEAR(rbm::norm(g.faceAreas[f]), 1.0, 1e-15);
        const Vector3 outward = g.faceCentres[f] - g.cellCentres[0];
        EXPECT_NEAR(rbm::dot(outward, g.faceAreas[f]), 0.5, 1e-15) << "face " << f;
        EXPECT_NEAR(rbm::norm(outward), 0.5, 1e-15) << "face " << f;
    }
}

TEST(MeshGeometry, CubeFarFromTheOriginKeepsItsVolume)
{
    const PolyMesh mesh = buildMesh(unitCubePoints({1e5, -2e5, 3e5}), {hexFaces()});
    const auto g = rbm::computeMeshGeometry(mesh);
    EXPECT_NEAR(g.cellVolumes[0], 1.0, 1e-9);
    EXPECT_NEAR(g.cellCentres[0].x, 1e5 + 0.5, 1e-9);
}

TEST(MeshGeometry, TetrahedronVolumeIsOneSixthOfTheTripleProduct)
{
    const std::vector<Vector3> points = {{0.1, 0.2, 0.3}, {2.1, 0.4, 0.2}, {0.5, 1.7, 0.1}, {0.3, 0.6, 1.4}};
    // (p1-p0) x (p2-p0) points towards p3: outward faces.
    const PolyMesh mesh = buildMesh(points, {{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}});
    const auto g = rbm::computeMeshGeometry(mesh);
    const double expected =
        rbm::dot(rbm::cross(points[1] - points[0], points[2] - points[0]), points[3] - points[0]) / 6.0;
    ASSERT_GT(expected, 0.0);
    EXPECT_NEAR(g.cellVolumes[0], expected, 1e-15);
    const Vector3 centroid = 0.25 * (points[0] + points[1] + points[2] + points[3]);
    EXPECT_NEAR(rbm::norm(g.cellCentres[0] - centroid), 0.0, 1e-15);
}

TEST(MeshGeometry, PrismVolumeIsBaseAreaTimesHeight)
{
    const double h = 0.7;
    const std::vector<Vector3> points = {{0, 0, 0}, {3, 0, 0}, {0, 2, 0}, {0, 0, h}, {3, 0, h}, {0, 2, h}};
    const PolyMesh mesh = buildMesh(points, {{{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}});
    const auto g = rbm::computeMeshGeometry(mesh);
    EXPECT_NEAR(g.cellVolumes[0], 3.0 * h, 1e-14);   // base area 3
    EXPECT_NEAR(g.cellCentres[0].x, 1.0, 1e-14);
    EXPECT_NEAR(g.cellCentres[0].y, 2.0 / 3.0, 1e-14);
    EXPECT_NEAR(g.cellCentres[0].z, h / 2, 1e-14);
}

TEST(MeshGeometry, PolygonalFaceCentreIsItsAreaCentroidNotItsPointAverage)
{
    // A pentagon: unit square with an extra point on one edge. Point average is off the
    // centroid; OpenFOAM's triangle decomposition gives the true centroid.
    PolyMesh mesh;
    mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 0.25, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<Label> face = {0, 1, 2, 3, 4};
    mesh.addFace(face);
    mesh.owner = {0};
    std::vector<Vector3> centres, areas;
    rbm::computeFaceCentresAndAreas(mesh, mesh.points, centres, areas);
    EXPECT_NEAR(centres[0].x, 0.5, 1e-15);
    EXPECT_NEAR(centres[0].y, 0.5, 1e-15);
    EXPECT_NEAR(areas[0].z, 1.0, 1e-15);
}

TEST(MeshGeometry, MirroredCellHasNegativeVolume)
{
    auto points = unitCubePoints();
    for (auto& p : points) p.x = -p.x;
    const PolyMesh mesh = buildMesh(points, {hexFaces()});
    const auto g = rbm::computeMeshGeometry(mesh);
    EXPECT_NEAR(g.cellVolumes[0], -1.0, 1e-15);
}

TEST(MeshGeometry, MovedPointsReplaceTheMeshPoints)
{
    const PolyMesh mesh = buildMesh(unitCubePoints(), {hexFaces()});
    auto moved = mesh.points;
    for (auto& p : moved) p *= 2.0;
    rbm::MeshGeometry g;
    rbm::updateMeshGeometry(mesh, moved, g);
    EXPECT_NEAR(g.cellVolumes[0], 8.0, 1e-14);
    std::vector<Vector3> wrongCount(3);
    EXPECT_THROW(rbm::updateMeshGeometry(mesh, wrongCount, g), std::invalid_argument);
}

} // namespace
