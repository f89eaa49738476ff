#pragma once
// The benchmark's cases: their meshes (generated, or the committed airfoil) and their motions.

#include "BenchmarkMeshes.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <string>
#include <vector>

namespace rbm::benchmark {

struct CaseInfo {
    std::string name;
    std::string description;
    bool generated = true;
    bool holeMesh = false;
    HoleMeshCellKind kind = HoleMeshCellKind::quadrilaterals;
};

const std::vector<CaseInfo>& allCases();

const CaseInfo& caseInfo(const std::string& name);

Label twistCellsPerSide(double size);

PolyMesh generateMesh(const CaseInfo& info, double size);

// What a patch does in a case's motion.
enum class PatchRole { moving, fixed, free, ignored };

struct CaseMotion {
    std::string movingPatch;
    Vector3 centre;
    Vector3 axis{0.0, 0.0, 1.0};
    double angle = 0.0;  // radians, counter-clockwise about axis
};

CaseMotion caseMotion(const std::string& name);

PatchRole patchRole(const std::string& caseName, const Patch& patch);

} // namespace rbm::benchmark
