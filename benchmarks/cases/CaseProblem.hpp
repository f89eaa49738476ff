#pragma once
// The RBM problem of a case, built the way the OpenFOAM-facing solver builds it.

#include "BenchmarkCases.hpp"
#include "CellNeighbourGraph.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RbmProblem.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rbm::benchmark {

struct CaseProblem {
    int dimension = 3;
    std::unique_ptr<PseudoTwoDMesh> twoD;
    std::shared_ptr<const CellNeighbourGraph> graph;
    std::vector<Vector3> reference;
    std::vector<motion::NodeConstraint> constraints;
    std::vector<Vector3> prescribed;
};

void buildGraph(const PolyMesh& mesh, CaseProblem& problem);

void buildConstraints(const PolyMesh& mesh, const std::string& caseName, CaseProblem& problem);

// The mesh's points after the motion: 2D node displacements lifted to both planes.
std::vector<Vector3> movedPoints(const PolyMesh& mesh, const CaseProblem& problem, const std::vector<Vector3>& displacement);

} // namespace rbm::benchmark
