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
#include "CyclicPairs.hpp"
#include "CyclicPatchEntries.hpp"
#include "PolyMeshReader.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>

namespace {

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

} // namespace

int main(int argc, char** argv)
{
    const bool cyclic = argc == 5 && std::strcmp(argv[1], "--cyclic") == 0;
    if (argc != 4 && !cyclic) {
        std::cerr << "usage: rbmComparePoints FILE_A FILE_B TOLERANCE\n"
                     "       rbmComparePoints --cyclic POLYMESH_DIR MOVED_POINTS TOLERANCE\n";
        return 2;
    }
    try {
        if (cyclic) return compareCyclicPairs(argv[2], argv[3], std::stod(argv[4]));
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
