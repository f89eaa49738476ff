#pragma once
// Untangling: moves the points of a mesh region whose cells are inverted until every cell is
// valid again, keeping boundary constraints (fixed points stay bit-for-bit, sliding points on
// their plane or line). Pure geometry, no PETSc: the RBM solver calls it after a solve that
// left inverted cells (issue 13.3), but any mesh motion could.
//
// Cells are split into simplices the way validity is judged: 2D, a triangle itself, the four
// corner triangles of a quadrilateral (positive exactly when it is convex: F_shape > 0), and the
// triangles (cell centroid, p_k, p_k+1) of other polygons; 3D, the tetrahedra (cell centroid, face centroid, p_k,
// p_k+1) of every face edge, with centroids the plain means of the points. All simplices
// positive implies a positive polygon area (2D) and positive face pyramids about the cell
// centre (3D, up to the difference between OpenFOAM's area-weighted centres and point means),
// which is how ThesisQuality and the solver count inverted cells; the caller's own test
// decides when the stage is done.
//
// Objective (Knupp, "Hexahedral and tetrahedral mesh untangling", Eng. Comput. 17 (2001)
// 261–268): Σ_s (|α_s − V_s| − (α_s − V_s)) is zero exactly when every simplex volume V_s
// reaches its target α_s > 0. It is minimised here in its squared form
// Σ_s max(0, α_s − V_s)² / α_s² (the same minimisers, continuously differentiable), point by
// point (Knupp's local optimisation: a Gauss–Newton step in the point's admissible
// directions with backtracking), in a fixed order, so the result does not depend on threads.
// α_s = targetFraction × the simplex's volume in the reference mesh: the untangled cells keep a
// fraction of their shape. A simplex that is not positive in the reference mesh (a concave
// corner the user's mesh already had) is left out.
//
// Region: the inverted cells grown by `layers` layers of point-neighbour cells; its points
// move, and every simplex touching them is in the objective (a valid cell next to the region
// is not given up for an inverted one without paying for it); success is judged on the whole
// mesh by the caller's test. When a round of sweeps does not untangle, the region is grown
// (layers doubled) up to maxRounds.

#include "PlanarMesh.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace rbm {

// How a point may move: fixed, free, or on a plane (one unit normal) or a line (two
// orthonormal unit normals); normals unused are zero vectors.
struct UntanglePointConstraint {
    bool fixed = false;
    Vector3 normal{};
    Vector3 secondNormal{};
};

// Cells as simplices whose corners are means of point sets (see the header comment).
struct SimplexDecomposition {
    int dimension = 3;                // 2: triangles in x, y; 3: tetrahedra
    std::vector<Label> cornerOffsets{0};  // corner c is the mean of cornerPoints[cornerOffsets[c] ..)
    std::vector<Label> cornerPoints;
    std::vector<Label> simplexCorners;    // dimension + 1 corners per simplex, positively oriented when valid
    std::vector<Label> simplexCell;       // the cell of every simplex
    std::vector<Label> cellOffsets{0};    // points of every cell (CSR), for the region's growth
    std::vector<Label> cellPoints;

    Label simplexCount() const { return static_cast<Label>(simplexCell.size()); }
    Label cellCount() const { return static_cast<Label>(cellOffsets.size()) - 1; }
};

SimplexDecomposition decomposeCells(const PolyMesh& mesh);
SimplexDecomposition decomposeCells(const PlanarMesh& mesh);

// Signed volumes (2D: areas) of every simplex at the given point positions.
std::vector<double> simplexVolumes(const SimplexDecomposition& cells, std::span<const Vector3> positions);

struct UntangleOptions {
    int layers = 2;                 // region: the inverted cells and this many layers around them
    int maxRounds = 5;              // rounds of sweeps, the layers doubled after each
    int maxSweepsPerRound = 200;
    double targetFraction = 0.1;    // α_s = this × the reference simplex volume
};

struct UntangleResult {
    Label initialInverted = 0;          // cells the caller's test found inverted at the start
    std::vector<Label> remainingCells;  // still inverted at the end (empty: untangled)
    std::vector<Label> stuckCells;      // of those, cells whose points are all fixed
    Label movedPoints = 0;              // points whose position changed
    int sweeps = 0;
    int rounds = 0;
    bool untangled() const { return remainingCells.empty(); }
    // "" when untangled, else which cells stay inverted and where (first few, with centroids).
    std::string describe(std::span<const Vector3> positions, const SimplexDecomposition& cells) const;
};

// The caller's inverted-cell test: the labels of the cells that are inverted at `positions`.
using InvertedCellTest = std::function<std::vector<Label>(std::span<const Vector3> positions)>;

// Untangles `positions` in place. referencePositions: the valid mesh the targets α come
// from (same size). constraints: one per point. Returns at once, positions untouched, when
// the test finds no inverted cell. Throws std::invalid_argument for sizes that do not match.
UntangleResult untangle(const SimplexDecomposition& cells, std::span<const Vector3> referencePositions,
                        std::span<const UntanglePointConstraint> constraints, std::vector<Vector3>& positions,
                        const InvertedCellTest& isInverted, const UntangleOptions& options = {});

} // namespace rbm
