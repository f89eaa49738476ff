#include "BenchmarkCases.hpp"

#include "MeshGenerators.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rbm::benchmark {

namespace {
constexpr double degree = std::numbers::pi / 180.0;
} // namespace

const std::vector<CaseInfo>& allCases()
{
    static const std::vector<CaseInfo> cases{
        {"quad2D", "2D quadrilaterals (one layer of hexahedra), square hole turned 4 deg", true, true,
         HoleMeshCellKind::quadrilaterals},
        {"tri2D", "2D triangles (one layer of prisms), square hole turned 4 deg", true, true, HoleMeshCellKind::triangles},
        {"hex3D", "3D hexahedra, cube hole turned 4 deg about z", true, true, HoleMeshCellKind::hexahedra},
        {"tet3D", "3D tetrahedra (6 per cube), cube hole turned 4 deg about z", true, true, HoleMeshCellKind::tetrahedra},
        {"twist3D", "3D hexahedral unit cube, top turned 30 deg about the vertical axis, bottom fixed, sides free", true,
         false, HoleMeshCellKind::hexahedra},
        {"airfoil", "NACA4415 boundary-layer mesh (benchmarks/airfoilMesh), turned 4 deg about the trailing edge", false,
         false, HoleMeshCellKind::quadrilaterals},
    };
    return cases;
}

const CaseInfo& caseInfo(const std::string& name)
{
    for (const CaseInfo& info : allCases())
        if (info.name == name) return info;
    std::string valid;
    for (const CaseInfo& info : allCases()) valid += " " + info.name;
    throw std::invalid_argument("unknown case " + name + ". Valid cases are:" + valid);
}

Label twistCellsPerSide(double size)
{
    return std::max<Label>(2, static_cast<Label>(std::lround(std::cbrt(size))));
}

PolyMesh generateMesh(const CaseInfo& info, double size)
{
    if (info.holeMesh) return makeBoxWithHole(boxWithHoleCellsPerSide(size, info.kind), info.kind);
    if (info.name == "twist3D") {
        const Label n = twistCellsPerSide(size);
        return makeHexBox(n, n, n, {-0.5, -0.5, 0.0}, {0.5, 0.5, 1.0},
                          {BoxPatch{"sides"}, BoxPatch{"sides"}, BoxPatch{"sides"}, BoxPatch{"sides"}, BoxPatch{"bottom"},
                           BoxPatch{"top", "wall"}});
    }
    throw std::logic_error("generateMesh: case " + info.name + " is not generated");
}

CaseMotion caseMotion(const std::string& name)
{
    if (name == "airfoil") return {"airfoil", {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 4.0 * degree};
    if (name == "twist3D") return {"top", {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 30.0 * degree};
    return {"inner", {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 4.0 * degree};
}

PatchRole patchRole(const std::string& caseName, const Patch& patch)
{
    if (patch.type == "empty" || patch.type == "wedge") return PatchRole::ignored;
    if (patch.name == caseMotion(caseName).movingPatch) return PatchRole::moving;
    if (caseName == "twist3D" && patch.name == "sides") return PatchRole::free;
    return PatchRole::fixed;
}

} // namespace rbm::benchmark
