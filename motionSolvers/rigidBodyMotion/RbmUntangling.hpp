#pragma once
// The RBM solver's side of the untangling stage (src/Untangling.hpp, issue 13.3): the
// untangler's point constraints from the problem's node classes, and where a cell that stays
// inverted lies (its boundary patches) for the message.

#include "PlanarMesh.hpp"
#include "PolyMesh.hpp"
#include "RbmProblem.hpp"
#include "Untangling.hpp"

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

} // namespace rbm::motion
