// rbmComparePoints: the largest distance between the points of two OpenFOAM points files
// (polyMesh/points, ascii or binary, gzip or not), for the OpenFOAM plugin's tests
// (OpenFOAMPluginTest.cmake), which compare the plugin's meshes with rbmMoveMesh's.
//   rbmComparePoints FILE_A FILE_B TOLERANCE
// Prints "max |difference| X over N points" and exits 0 when X <= TOLERANCE, 1 when it is
// larger, 2 when a file cannot be read or the point counts differ.
//   rbmComparePoints --cyclic POLYMESH_DIR MOVED_POINTS TOLERANCE
// The cyclic pairs of the mesh in POLYMESH_DIR (its points the reference, paired by
// src/CyclicPairs.hpp) after the motion to MOVED_POINTS: prints "cyclic pairs: max |u_B - R u_A|
// X, max |u_A| Y over N pairs" and exits 0 when X <= TOLERANCE and the mesh has pairs.
//   rbmComparePoints --decomposed POLYMESH_DIR REFERENCE_POINTS CASE_DIR TIME TOLERANCE
// Every processor folder's points at TIME (CASE_DIR/processorN/TIME/polyMesh/points, placed in
// the whole mesh by its pointProcAddressing) against REFERENCE_POINTS, the whole mesh's points
// of a serial run, relative to the shortest edge at each point of the mesh in POLYMESH_DIR (the
// scale the solver's displacementTolerance is relative to): prints "max |difference| /
// shortest edge X over N processor points" and exits 0 when X <= TOLERANCE and every point of
// the mesh is in some processor folder.
#include "CyclicPairs.hpp"
#include "CyclicPatchEntries.hpp"
#include "DecomposedCase.hpp"
#include "PolyMeshReader.hpp"
#include "ShortestEdges.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

int compareCyclicPairs(const std::string& polyMeshDir, const std::string& movedPoints, double tolerance)
{
    const rbm::PolyMesh mesh = rbm::io::readPolyMesh(polyMeshDir);
    const auto moved = rbm::io::readPolyMeshPoints(movedPoints);
    if (moved.size() != mesh.points.size()) {
        std::cerr << "rbmComparePoints: " << moved.size() << " points in " << movedPoints << ", "
                  << mesh.points.size() << " in the mesh\n";
        return 2;
    }
    const std::string boundary = polyMeshDir + "/boundary";
    const auto pairings = rbm::pairCyclicPatches(mesh, mesh.points, rbm::io::readCyclicPatchSpecs(mesh, boundary), boundary);
    double mismatch = 0.0, largest = 0.0;
    std::size_t count = 0;
    for (const rbm::CyclicPatchPairing& pairing : pairings)
        for (const auto& [a, b] : pairing.points) {
            const rbm::Vector3 ua = moved[a] - mesh.points[a], ub = moved[b] - mesh.points[b];
            mismatch = std::max(mismatch, rbm::norm(ub - pairing.rotation * ua));
            largest = std::max(largest, rbm::norm(ua));
            ++count;
        }
    char text[96];
    std::snprintf(text, sizeof text, "max |u_B - R u_A| %.3e, max |u_A| %.3e", mismatch, largest);
    std::cout << "cyclic pairs: " << text << " over " << count << " pairs\n";
    return count > 0 && mismatch <= tolerance ? 0 : 1;
}

int compareDecomposed(const std::string& polyMeshDir, const std::string& referencePoints, const fs::path& caseDir,
                      const std::string& time, double tolerance)
{
    const rbm::PolyMesh mesh = rbm::io::readPolyMesh(polyMeshDir);
    const std::vector<double> shortest = rbm::test::shortestEdgeAtEachPoint(mesh);
    const auto reference = rbm::io::readPolyMeshPoints(referencePoints);
    if (reference.size() != mesh.points.size()) {
        std::cerr << "rbmComparePoints: " << reference.size() << " points in " << referencePoints << ", "
                  << mesh.points.size() << " in the mesh\n";
        return 2;
    }
    std::vector<char> seen(mesh.points.size(), 0);
    double largest = 0.0;
    std::size_t compared = 0;
    const int processors = rbm::io::countProcessorFolders(caseDir);
    for (int p = 0; p < processors; ++p) {
        const fs::path processor = caseDir / ("processor" + std::to_string(p));
        const auto moved = rbm::io::readPolyMeshPoints(processor / time / "polyMesh" / "points");
        const std::vector<rbm::Label> global = rbm::io::readLabelListFile(
            processor / "constant" / "polyMesh" / "pointProcAddressing", "pointProcAddressing", moved.size());
        if (global.size() != moved.size()) {
            std::cerr << "rbmComparePoints: " << processor.string() << " has " << moved.size() << " points and "
                      << global.size() << " pointProcAddressing labels\n";
            return 2;
        }
        for (std::size_t k = 0; k < moved.size(); ++k) {
            const auto g = static_cast<std::size_t>(global[k]);
            largest = std::max(largest, rbm::norm(moved[k] - reference[g]) / shortest[g]);
            seen[g] = 1;
            ++compared;
        }
    }
    const auto missing = std::count(seen.begin(), seen.end(), 0);
    char text[64];
    std::snprintf(text, sizeof text, "%.3e", largest);
    std::cout << "max |difference| / shortest edge " << text << " over " << compared << " points of " << processors
              << " processors";
    if (missing > 0) std::cout << "; " << missing << " points of the mesh in no processor folder";
    std::cout << "\n";
    return largest <= tolerance && missing == 0 ? 0 : 1;
}

} // namespace

int main(int argc, char** argv)
{
    const bool cyclic = argc == 5 && std::strcmp(argv[1], "--cyclic") == 0;
    const bool decomposed = argc == 7 && std::strcmp(argv[1], "--decomposed") == 0;
    if (argc != 4 && !cyclic && !decomposed) {
        std::cerr << "usage: rbmComparePoints FILE_A FILE_B TOLERANCE\n"
                     "       rbmComparePoints --cyclic POLYMESH_DIR MOVED_POINTS TOLERANCE\n"
                     "       rbmComparePoints --decomposed POLYMESH_DIR REFERENCE_POINTS CASE_DIR TIME TOLERANCE\n";
        return 2;
    }
    try {
        if (cyclic) return compareCyclicPairs(argv[2], argv[3], std::stod(argv[4]));
        if (decomposed) return compareDecomposed(argv[2], argv[3], argv[4], argv[5], std::stod(argv[6]));
        const auto a = rbm::io::readPolyMeshPoints(argv[1]);
        const auto b = rbm::io::readPolyMeshPoints(argv[2]);
        const double tolerance = std::stod(argv[3]);
        if (a.size() != b.size()) {
            std::cerr << "rbmComparePoints: " << a.size() << " points in " << argv[1] << ", " << b.size() << " in "
                      << argv[2] << "\n";
            return 2;
        }
        double largest = 0.0;
        for (std::size_t p = 0; p < a.size(); ++p) largest = std::max(largest, rbm::norm(a[p] - b[p]));
        char text[64];
        std::snprintf(text, sizeof text, "%.3e", largest);
        std::cout << "max |difference| " << text << " over " << a.size() << " points\n";
        return largest <= tolerance ? 0 : 1;
    } catch (const std::exception& error) {
        std::cerr << "rbmComparePoints: " << error.what() << "\n";
        return 2;
    }
}
