#include "CaseProblem.hpp"

#include "Rotation.hpp"

#include <algorithm>
#include <cstdint>

namespace rbm::benchmark {

void buildGraph(const PolyMesh& mesh, CaseProblem& problem)
{
    if (detectPseudoTwoD(mesh) != PseudoTwoDKind::None) {
        problem.twoD = std::make_unique<PseudoTwoDMesh>(extractPseudoTwoD(mesh));
        problem.dimension = 2;
        problem.reference = problem.twoD->planar.points;
        problem.graph = std::make_shared<const CellNeighbourGraph>(buildCellNeighbourGraph(problem.twoD->planar));
    } else {
        problem.dimension = 3;
        problem.reference = mesh.points;
        problem.graph = std::make_shared<const CellNeighbourGraph>(buildCellNeighbourGraph(mesh));
    }
}

void buildConstraints(const PolyMesh& mesh, const std::string& caseName, CaseProblem& problem)
{
    const std::size_t n = problem.reference.size();
    problem.constraints.assign(n, motion::NodeConstraint{});
    problem.prescribed.assign(n, Vector3{});
    const CaseMotion motion = caseMotion(caseName);
    Vector3 centre = motion.centre;
    Vector3 axis = motion.axis;
    if (problem.twoD) {
        centre = problem.twoD->frame.toLocal(centre);
        centre.z = 0.0;
        axis = problem.twoD->frame.toLocal(axis);  // (0, 0, ±1) for a rotation in the plane
        axis.x = axis.y = 0.0;
    }
    const rbm::Matrix3 rotation = rotationMatrix(axis, motion.angle);
    std::vector<std::uint8_t> role(n, 0);  // 0 free, 1 fixed, 2 moving
    auto mark = [&](Label node, PatchRole patchRole) {
        if (node < 0) return;
        const std::uint8_t value = patchRole == PatchRole::moving ? 2 : 1;
        role[node] = std::max(role[node], value);
    };
    for (Label p = 0; p < static_cast<Label>(mesh.patches.size()); ++p) {
        const Patch& patch = mesh.patches[p];
        const PatchRole patchRole = benchmark::patchRole(caseName, patch);
        if (patchRole == PatchRole::ignored || patchRole == PatchRole::free) continue;
        for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f)
            for (Label point : mesh.face(f)) mark(problem.twoD ? problem.twoD->nodeOfPoint[point] : point, patchRole);
    }
    for (std::size_t node = 0; node < n; ++node) {
        if (role[node] == 0) continue;
        problem.constraints[node].kind = motion::NodeKind::prescribed;
        if (role[node] == 2) {
            Vector3 x = problem.reference[node];
            if (problem.twoD) x.z = 0.0;
            Vector3 u = centre + rotation * (x - centre) - x;
            if (problem.twoD) u.z = 0.0;
            problem.prescribed[node] = u;
        }
    }
    // Nodes no cell uses cannot move (as in RigidBodyMotionSolver).
    for (std::size_t node = 0; node < n; ++node)
        if (problem.graph->offsets[node + 1] == problem.graph->offsets[node])
            problem.constraints[node].kind = motion::NodeKind::prescribed;
}

std::vector<Vector3> movedPoints(const PolyMesh& mesh, const CaseProblem& problem, const std::vector<Vector3>& displacement)
{
    if (problem.twoD) {
        std::vector<Vector3> positions(problem.reference);
        for (std::size_t node = 0; node < positions.size(); ++node) {
            positions[node].x += displacement[node].x;
            positions[node].y += displacement[node].y;
        }
        return problem.twoD->liftPositions(mesh.points, positions);
    }
    std::vector<Vector3> points(mesh.points);
    for (std::size_t p = 0; p < points.size(); ++p) points[p] += displacement[p];
    return points;
}

} // namespace rbm::benchmark
