#pragma once
// The shortest face edge at every point of a mesh: the length scale the solver's
// displacement tolerance is relative to, so tests compare two solutions point by point in it.

#include "PolyMesh.hpp"

#include <algorithm>
#include <limits>
#include <vector>

namespace rbm::test {

inline std::vector<double> shortestEdgeAtEachPoint(const PolyMesh& mesh)
{
    std::vector<double> shortestEdge(mesh.pointCount(), std::numeric_limits<double>::infinity());
    for (Label f = 0; f < mesh.faceCount(); ++f) {
        const auto face = mesh.face(f);
        for (std::size_t k = 0; k < face.size(); ++k) {
            const Label a = face[k];
            const Label b = face[(k + 1) % face.size()];
            const double length = norm(mesh.points[a] - mesh.points[b]);
            shortestEdge[a] = std::min(shortestEdge[a], length);
            shortestEdge[b] = std::min(shortestEdge[b], length);
        }
    }
    return shortestEdge;
}

} // namespace rbm::test
