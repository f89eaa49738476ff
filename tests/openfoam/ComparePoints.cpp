// rbmComparePoints: the largest distance between the points of two OpenFOAM points files
// (polyMesh/points, ascii or binary, gzip or not), for the OpenFOAM plugin's tests
// (OpenFOAMPluginTest.cmake), which compare the plugin's meshes with rbmMoveMesh's.
//   rbmComparePoints FILE_A FILE_B TOLERANCE
// Prints "max |difference| X over N points" and exits 0 when X <= TOLERANCE, 1 when it is
// larger, 2 when a file cannot be read or the point counts differ.
#include "PolyMeshReader.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv)
{
    if (argc != 4) {
        std::cerr << "usage: rbmComparePoints FILE_A FILE_B TOLERANCE\n";
        return 2;
    }
    try {
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
