#pragma once
// The RBM solver's side of the untangling stage (src/Untangling.hpp): the untangler's point
// constraints from the problem's node classes, where a cell that stays inverted lies (its
// boundary patches) for the message, and the stage itself (RbmUntangler).

#include "InvertedCellCounter.hpp"
#include "PlanarMesh.hpp"
#include "PolyMesh.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RbmProblem.hpp"
#include "Untangling.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rbm::motion {

// Prescribed (and held) nodes are fixed; sliding nodes keep their plane, line nodes their
// line (the problem's orthonormal normals); free nodes are free.
std::vector<UntanglePointConstraint> untangleConstraints(const RbmProblem& problem);

// "patch a, b" for a cell with boundary faces (2D: edges) on patches a and b, "" for an
// interior cell.
std::string cellPatchNames(const PolyMesh& mesh, Label cell);
std::string cellPatchNames(const PlanarMesh& mesh, Label cell);

// The untangling stage of a solve (`untangle on`): when a displacement leaves inverted cells,
// moves the free and sliding nodes around them until none is; prescribed nodes keep their
// displacement bit for bit. The mesh's decomposition into simplices is built at the first use.
class RbmUntangler {
public:
    // `twoD` non-null: the planar mesh is untangled (nodes: planar nodes).
    RbmUntangler(const PolyMesh& mesh, const PseudoTwoDMesh* twoD) : mesh_(mesh), twoD_(twoD) {}

    struct Outcome {
        Label untangledCellCount = 0;
        std::string reason;   // "; untangled 3 inverted cells", or "; untangling: " and where cells stay inverted
    };
    // `displacement`: per node, relative to `referencePoints`; `counter` checks candidates.
    // Call only when `displacement` inverts cells.
    Outcome untangle(const RbmProblem& problem, const std::vector<Vector3>& referencePoints,
                     std::vector<Vector3>& displacement, InvertedCellCounter& counter);

private:
    const PolyMesh& mesh_;
    const PseudoTwoDMesh* twoD_;
    std::unique_ptr<SimplexDecomposition> simplices_;
};

} // namespace rbm::motion
