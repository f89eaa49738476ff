#include "PlanarMesh.hpp"

namespace rbm {

double PlanarMesh::signedArea(Label c) const { return signedArea(c, points); }

double PlanarMesh::signedArea(Label c, std::span<const Vector3> positions) const
{
    const auto polygon = cell(c);
    double twiceArea = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vector3& a = positions[polygon[i]];
        const Vector3& b = positions[polygon[(i + 1) % polygon.size()]];
        twiceArea += a.x * b.y - a.y * b.x;
    }
    return 0.5 * twiceArea;
}

Label PlanarMesh::patchOfEdge(Label e) const
{
    for (std::size_t p = 0; p < patches.size(); ++p) {
        if (e >= patches[p].startEdge && e < patches[p].startEdge + patches[p].edgeCount) return static_cast<Label>(p);
    }
    return -1;
}

} // namespace rbm
