#include "Untangling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <tuple>
#include <stdexcept>

namespace rbm {

namespace {

// CSR inverse of a CSR map (rows → items): item → rows, rows ascending.
void invert(std::span<const Label> offsets, std::span<const Label> items, Label itemCount, std::vector<Label>& outOffsets,
            std::vector<Label>& outRows)
{
    outOffsets.assign(static_cast<std::size_t>(itemCount) + 1, 0);
    for (Label item : items) ++outOffsets[static_cast<std::size_t>(item) + 1];
    for (Label i = 0; i < itemCount; ++i) outOffsets[i + 1] += outOffsets[i];
    outRows.assign(items.size(), 0);
    std::vector<Label> next(outOffsets.begin(), outOffsets.end() - 1);
    const Label rows = static_cast<Label>(offsets.size()) - 1;
    for (Label row = 0; row < rows; ++row)
        for (Label k = offsets[row]; k < offsets[row + 1]; ++k) outRows[next[items[k]]++] = row;
}

// Signed volume of a simplex and its derivative with respect to each corner.
//  3D: V = (b − a)·((c − a) × (d − a)) / 6; ∂V/∂b = (c−a)×(d−a)/6, ∂V/∂c = (d−a)×(b−a)/6,
//      ∂V/∂d = (b−a)×(c−a)/6, ∂V/∂a = −(their sum) (V is invariant under translation).
//  2D: A = ((b − a) × (c − a))_z / 2, ∂A/∂b = (c_y − a_y, a_x − c_x)/2, ∂A/∂c = (a_y − b_y, b_x − a_x)/2.
double simplexVolume(int dimension, const Vector3* corner, Vector3* gradient)
{
    if (dimension == 2) {
        const Vector3 e1 = corner[1] - corner[0], e2 = corner[2] - corner[0];
        if (gradient) {
            gradient[1] = {0.5 * e2.y, -0.5 * e2.x, 0.0};
            gradient[2] = {-0.5 * e1.y, 0.5 * e1.x, 0.0};
            gradient[0] = -1.0 * (gradient[1] + gradient[2]);
        }
        return 0.5 * (e1.x * e2.y - e1.y * e2.x);
    }
    const Vector3 e1 = corner[1] - corner[0], e2 = corner[2] - corner[0], e3 = corner[3] - corner[0];
    const Vector3 c23 = cross(e2, e3);
    if (gradient) {
        gradient[1] = c23 / 6.0;
        gradient[2] = cross(e3, e1) / 6.0;
        gradient[3] = cross(e1, e2) / 6.0;
        gradient[0] = -1.0 * (gradient[1] + gradient[2] + gradient[3]);
    }
    return dot(e1, c23) / 6.0;
}

// Solves the k × k (k ≤ 3) symmetric positive definite system a y = b by Cholesky; false if
// a pivot is not positive.
bool solveSmall(int k, std::array<std::array<double, 3>, 3> a, std::array<double, 3>& b)
{
    for (int j = 0; j < k; ++j) {
        double pivot = a[j][j];
        for (int q = 0; q < j; ++q) pivot -= a[j][q] * a[j][q];
        if (!(pivot > 0.0)) return false;
        a[j][j] = std::sqrt(pivot);
        for (int i = j + 1; i < k; ++i) {
            double value = a[i][j];
            for (int q = 0; q < j; ++q) value -= a[i][q] * a[j][q];
            a[i][j] = value / a[j][j];
        }
    }
    for (int i = 0; i < k; ++i) {
        for (int q = 0; q < i; ++q) b[i] -= a[i][q] * b[q];
        b[i] /= a[i][i];
    }
    for (int i = k - 1; i >= 0; --i) {
        for (int q = i + 1; q < k; ++q) b[i] -= a[q][i] * b[q];
        b[i] /= a[i][i];
    }
    return true;
}

// Orthonormal basis of the directions a point may move in (0 to 3 vectors).
int admissibleBasis(int dimension, const UntanglePointConstraint& constraint, std::array<Vector3, 3>& basis)
{
    if (constraint.fixed) return 0;
    const bool plane = !(constraint.normal == Vector3{});
    const bool line = !(constraint.secondNormal == Vector3{});
    if (dimension == 2) {
        if (line) return 0;  // two lines in a plane meet in a point
        if (!plane) {
            basis[0] = {1.0, 0.0, 0.0};
            basis[1] = {0.0, 1.0, 0.0};
            return 2;
        }
        basis[0] = {-constraint.normal.y, constraint.normal.x, 0.0};
        basis[0] /= norm(basis[0]);
        return 1;
    }
    if (line) {
        basis[0] = cross(constraint.normal, constraint.secondNormal);
        basis[0] /= norm(basis[0]);
        return 1;
    }
    if (plane) {
        const Vector3& n = constraint.normal;
        // The coordinate axis least aligned with n gives a well-conditioned first tangent.
        Vector3 axis{1.0, 0.0, 0.0};
        if (std::abs(n.y) < std::abs(n.x) && std::abs(n.y) <= std::abs(n.z)) axis = {0.0, 1.0, 0.0};
        else if (std::abs(n.z) < std::abs(n.x) && std::abs(n.z) < std::abs(n.y)) axis = {0.0, 0.0, 1.0};
        basis[0] = cross(n, axis);
        basis[0] /= norm(basis[0]);
        basis[1] = cross(n, basis[0]);
        basis[1] /= norm(basis[1]);
        return 2;
    }
    basis[0] = {1.0, 0.0, 0.0};
    basis[1] = {0.0, 1.0, 0.0};
    basis[2] = {0.0, 0.0, 1.0};
    return 3;
}

} // namespace

SimplexDecomposition decomposeCells(const PolyMesh& mesh)
{
    SimplexDecomposition result;
    result.dimension = 3;
    const Label points = mesh.pointCount(), faces = mesh.faceCount(), cellCount = mesh.cellCount();
    // Corners: every point, then every face centroid, then every cell centroid.
    for (Label p = 0; p < points; ++p) {
        result.cornerPoints.push_back(p);
        result.cornerOffsets.push_back(static_cast<Label>(result.cornerPoints.size()));
    }
    for (Label f = 0; f < faces; ++f) {
        for (Label p : mesh.face(f)) result.cornerPoints.push_back(p);
        result.cornerOffsets.push_back(static_cast<Label>(result.cornerPoints.size()));
    }
    // Cell points: the union of its faces' points, ascending.
    std::vector<std::vector<Label>> cellPointLists(static_cast<std::size_t>(cellCount));
    for (Label f = 0; f < faces; ++f) {
        for (Label p : mesh.face(f)) {
            cellPointLists[mesh.owner[f]].push_back(p);
            if (f < mesh.internalFaceCount()) cellPointLists[mesh.neighbour[f]].push_back(p);
        }
    }
    for (auto& list : cellPointLists) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        for (Label p : list) {
            result.cellPoints.push_back(p);
            result.cornerPoints.push_back(p);
        }
        result.cellOffsets.push_back(static_cast<Label>(result.cellPoints.size()));
        result.cornerOffsets.push_back(static_cast<Label>(result.cornerPoints.size()));
    }
    // Tetrahedra (cell centre, face centre, p_k, p_k+1): the face normal points out of the
    // owner, so this order is positive for the owner and reversed for the neighbour.
    const Label cellCorner = points + faces;
    for (Label f = 0; f < faces; ++f) {
        const auto face = mesh.face(f);
        const std::size_t size = face.size();
        for (std::size_t k = 0; k < size; ++k) {
            const Label a = face[k], b = face[(k + 1) % size];
            for (const auto& [cell, first, second] :
                 {std::tuple{mesh.owner[f], a, b}, std::tuple{f < mesh.internalFaceCount() ? mesh.neighbour[f] : -1, b, a}}) {
                if (cell < 0) continue;
                for (Label corner : {cellCorner + cell, points + f, first, second}) result.simplexCorners.push_back(corner);
                result.simplexCell.push_back(cell);
            }
        }
    }
    return result;
}

SimplexDecomposition decomposeCells(const PlanarMesh& mesh)
{
    SimplexDecomposition result;
    result.dimension = 2;
    const Label points = mesh.nodeCount();
    for (Label p = 0; p < points; ++p) {
        result.cornerPoints.push_back(p);
        result.cornerOffsets.push_back(static_cast<Label>(result.cornerPoints.size()));
    }
    for (Label c = 0; c < mesh.cellCount(); ++c) {
        for (Label p : mesh.cell(c)) {
            result.cornerPoints.push_back(p);
            result.cellPoints.push_back(p);
        }
        result.cornerOffsets.push_back(static_cast<Label>(result.cornerPoints.size()));
        result.cellOffsets.push_back(static_cast<Label>(result.cellPoints.size()));
    }
    // Polygons are counter-clockwise. A triangle is its own simplex; a quadrilateral gives its
    // four corner triangles (p_k−1, p_k, p_k+1), all positive exactly when it is convex, i.e.
    // when every corner Jacobian and so its F_shape (thesis eq 2.99) is positive; other
    // polygons give the triangles (cell centre, p_k, p_k+1).
    for (Label c = 0; c < mesh.cellCount(); ++c) {
        const auto cell = mesh.cell(c);
        if (cell.size() == 3 || cell.size() == 4) {
            const std::size_t size = cell.size();
            for (std::size_t k = 0; k < (size == 3 ? 1 : 4); ++k) {
                for (Label corner : {cell[(k + size - 1) % size], cell[k], cell[(k + 1) % size]})
                    result.simplexCorners.push_back(corner);
                result.simplexCell.push_back(c);
            }
            continue;
        }
        for (std::size_t k = 0; k < cell.size(); ++k) {
            for (Label corner : {points + c, cell[k], cell[(k + 1) % cell.size()]}) result.simplexCorners.push_back(corner);
            result.simplexCell.push_back(c);
        }
    }
    return result;
}

namespace {

Vector3 cornerPosition(const SimplexDecomposition& cells, std::span<const Vector3> positions, Label corner)
{
    const Label begin = cells.cornerOffsets[corner], end = cells.cornerOffsets[corner + 1];
    if (end - begin == 1) return positions[cells.cornerPoints[begin]];
    Vector3 sum{};
    for (Label k = begin; k < end; ++k) sum += positions[cells.cornerPoints[k]];
    return sum / static_cast<double>(end - begin);
}

} // namespace

std::vector<double> simplexVolumes(const SimplexDecomposition& cells, std::span<const Vector3> positions)
{
    const int corners = cells.dimension + 1;
    std::vector<double> volumes(static_cast<std::size_t>(cells.simplexCount()));
    std::array<Vector3, 4> corner;
    for (Label s = 0; s < cells.simplexCount(); ++s) {
        for (int j = 0; j < corners; ++j)
            corner[j] = cornerPosition(cells, positions, cells.simplexCorners[static_cast<std::size_t>(s) * corners + j]);
        volumes[s] = simplexVolume(cells.dimension, corner.data(), nullptr);
    }
    return volumes;
}

std::string UntangleResult::describe(std::span<const Vector3> positions, const SimplexDecomposition& cells) const
{
    if (remainingCells.empty()) return "";
    std::string text = std::to_string(remainingCells.size()) + " cell(s) stay inverted";
    if (!stuckCells.empty())
        text += ", " + std::to_string(stuckCells.size()) +
                " of them with every point fixed by the boundary conditions (no valid position exists)";
    text += ":";
    const std::size_t shown = std::min<std::size_t>(remainingCells.size(), 5);
    for (std::size_t k = 0; k < shown; ++k) {
        const Label c = remainingCells[k];
        Vector3 centre{};
        for (Label q = cells.cellOffsets[c]; q < cells.cellOffsets[c + 1]; ++q) centre += positions[cells.cellPoints[q]];
        centre /= static_cast<double>(cells.cellOffsets[c + 1] - cells.cellOffsets[c]);
        char buffer[160];
        std::snprintf(buffer, sizeof buffer, " cell %d at (%.6g %.6g %.6g)%s", static_cast<int>(c), centre.x, centre.y,
                      centre.z, std::binary_search(stuckCells.begin(), stuckCells.end(), c) ? " (all points fixed)" : "");
        text += buffer;
        if (k + 1 < shown) text += ",";
    }
    if (shown < remainingCells.size()) text += ", ...";
    return text;
}

namespace {

// One untangling: the maps between points, corners, simplices and cells, the targets, the
// current corner positions, and the points moved so far.
struct Untangler {
    const SimplexDecomposition& cells;
    std::span<const UntanglePointConstraint> constraints;
    std::vector<Vector3>& positions;
    const UntangleOptions& options;
    int dimension;
    int cornersPerSimplex;
    Label pointCount;
    Label cornerCount;
    Label simplexCount;
    Label cellCount;
    // Maps: point → corners, corner → simplices, point → cells.
    std::vector<Label> pointCornerOffsets, pointCorners, cornerSimplexOffsets, cornerSimplices, pointCellOffsets,
        pointCells;
    std::vector<double> target;
    std::vector<Vector3> corners;
    std::vector<char> marked;
    std::vector<Label> localSimplices;
    std::vector<char> moved;

    // The maps, the targets from the reference positions and the corners of `positions`.
    Untangler(const SimplexDecomposition& cells, std::span<const Vector3> referencePositions,
              std::span<const UntanglePointConstraint> constraints, std::vector<Vector3>& positions,
              const UntangleOptions& options)
        : cells(cells), constraints(constraints), positions(positions), options(options), dimension(cells.dimension),
          cornersPerSimplex(dimension + 1), pointCount(static_cast<Label>(positions.size())),
          cornerCount(static_cast<Label>(cells.cornerOffsets.size()) - 1), simplexCount(cells.simplexCount()),
          cellCount(cells.cellCount())
    {
        invert(cells.cornerOffsets, cells.cornerPoints, pointCount, pointCornerOffsets, pointCorners);
        {
            std::vector<Label> simplexOffsets(static_cast<std::size_t>(simplexCount) + 1);
            for (Label s = 0; s <= simplexCount; ++s) simplexOffsets[s] = s * cornersPerSimplex;
            invert(simplexOffsets, cells.simplexCorners, cornerCount, cornerSimplexOffsets, cornerSimplices);
        }
        invert(cells.cellOffsets, cells.cellPoints, pointCount, pointCellOffsets, pointCells);

        // Targets α_s from the reference mesh. A simplex that is not positive there (a concave
        // quadrilateral corner, a warped face's tetrahedron in the user's own mesh) is not asked
        // to become positive: target 0 leaves it out of the objective.
        target = simplexVolumes(cells, referencePositions);
        for (double& value : target) value = value > 0.0 ? options.targetFraction * value : 0.0;

        corners.resize(static_cast<std::size_t>(cornerCount));
        for (Label c = 0; c < cornerCount; ++c) corners[c] = cornerPosition(cells, positions, c);
        marked.assign(static_cast<std::size_t>(simplexCount), 0);
        moved.assign(static_cast<std::size_t>(pointCount), 0);
    }

    // Whether simplex s is in the objective (positive target).
    bool counts(Label s) const { return target[s] > 0.0; }

    // Recomputes the corners that contain `point` after it moved.
    void refreshCorners(Label point)
    {
        for (Label k = pointCornerOffsets[point]; k < pointCornerOffsets[point + 1]; ++k)
            corners[pointCorners[k]] = cornerPosition(cells, positions, pointCorners[k]);
    }

    // Penalty of a simplex: (max(0, α − V)/α)².
    double penalty(Label s, Vector3* gradient, double* volume) const
    {
        std::array<Vector3, 4> corner;
        for (int j = 0; j < cornersPerSimplex; ++j)
            corner[j] = corners[cells.simplexCorners[static_cast<std::size_t>(s) * cornersPerSimplex + j]];
        const double v = simplexVolume(dimension, corner.data(), gradient);
        if (volume) *volume = v;
        if (!counts(s)) return 0.0;
        const double shortfall = std::max(0.0, target[s] - v) / target[s];
        return shortfall * shortfall;
    }

    // Region: the inverted cells (the caller's test and any non-positive simplex), grown.
    std::vector<char> region(const std::vector<Label>& inverted, int layers) const
    {
        std::vector<char> cellInRegion(static_cast<std::size_t>(cellCount));
        std::fill(cellInRegion.begin(), cellInRegion.end(), 0);
        for (Label c : inverted) cellInRegion[c] = 1;
        {
            const std::vector<double> volumes = simplexVolumes(cells, positions);
            for (Label s = 0; s < simplexCount; ++s)
                if (counts(s) && !(volumes[s] > 0.0)) cellInRegion[cells.simplexCell[s]] = 1;
        }
        for (int layer = 0; layer < layers; ++layer) {
            std::vector<char> grown(cellInRegion);
            for (Label c = 0; c < cellCount; ++c) {
                if (!cellInRegion[c]) continue;
                for (Label q = cells.cellOffsets[c]; q < cells.cellOffsets[c + 1]; ++q) {
                    const Label p = cells.cellPoints[q];
                    for (Label k = pointCellOffsets[p]; k < pointCellOffsets[p + 1]; ++k) grown[pointCells[k]] = 1;
                }
            }
            cellInRegion.swap(grown);
        }
        return cellInRegion;
    }

    // The points of the region's cells that may move in some direction, ascending.
    std::vector<Label> movablePoints(const std::vector<char>& cellInRegion) const
    {
        std::vector<Label> movable;
        std::vector<char> isMovable(static_cast<std::size_t>(pointCount), 0);
        for (Label c = 0; c < cellCount; ++c)
            if (cellInRegion[c])
                for (Label q = cells.cellOffsets[c]; q < cells.cellOffsets[c + 1]; ++q) isMovable[cells.cellPoints[q]] = 1;
        std::array<Vector3, 3> basis;
        for (Label p = 0; p < pointCount; ++p)
            if (isMovable[p] && admissibleBasis(dimension, constraints[p], basis) > 0) movable.push_back(p);
        return movable;
    }

    // The simplices touching p, into localSimplices.
    void collectLocalSimplices(Label p)
    {
        localSimplices.clear();
        for (Label k = pointCornerOffsets[p]; k < pointCornerOffsets[p + 1]; ++k) {
            const Label corner = pointCorners[k];
            for (Label q = cornerSimplexOffsets[corner]; q < cornerSimplexOffsets[corner + 1]; ++q) {
                const Label s = cornerSimplices[q];
                if (!marked[s]) {
                    marked[s] = 1;
                    localSimplices.push_back(s);
                }
            }
        }
        for (Label s : localSimplices) marked[s] = 0;
    }

    // The local objective at p (returned), its gradient and Gauss–Newton matrix with respect to p.
    double localModel(Label p, Vector3& gradient, std::array<std::array<double, 3>, 3>& hessian) const
    {
        // Local objective, its gradient g and Gauss–Newton matrix H with respect to p:
        // ∂V_s/∂p = Σ_j [p ∈ corner j] ∂V_s/∂corner_j / |corner j|.
        double objective = 0.0;
        for (Label s : localSimplices) {
            std::array<Vector3, 4> cornerGradient;
            double volume = 0.0;
            const double value = penalty(s, cornerGradient.data(), &volume);
            objective += value;
            if (value == 0.0) continue;
            Vector3 dVdp{};
            for (int j = 0; j < cornersPerSimplex; ++j) {
                const Label corner = cells.simplexCorners[static_cast<std::size_t>(s) * cornersPerSimplex + j];
                const Label begin = cells.cornerOffsets[corner], end = cells.cornerOffsets[corner + 1];
                for (Label q = begin; q < end; ++q)
                    if (cells.cornerPoints[q] == p) dVdp += cornerGradient[j] / static_cast<double>(end - begin);
            }
            // f = r², r = (α − V)/α: ∇f = −2 r ∇V/α, Gauss–Newton 2 ∇V ∇Vᵀ/α².
            const double r = (target[s] - volume) / target[s];
            gradient += (-2.0 * r / target[s]) * dVdp;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) hessian[a][b] += 2.0 * dVdp[a] * dVdp[b] / (target[s] * target[s]);
        }
        return objective;
    }

    // The damped Gauss–Newton step of p in its admissible directions and g·step; false if none.
    bool newtonStep(Label p, const Vector3& gradient, const std::array<std::array<double, 3>, 3>& hessian, Vector3& step,
                    double& slope) const
    {
        std::array<Vector3, 3> basis;
        const int k = admissibleBasis(dimension, constraints[p], basis);
        std::array<std::array<double, 3>, 3> reduced{};
        std::array<double, 3> rhs{};
        double trace = 0.0;
        for (int a = 0; a < k; ++a) {
            rhs[a] = -dot(basis[a], gradient);
            for (int b = 0; b < k; ++b) {
                double value = 0.0;
                for (int x = 0; x < 3; ++x)
                    for (int y = 0; y < 3; ++y) value += basis[a][x] * hessian[x][y] * basis[b][y];
                reduced[a][b] = value;
            }
            trace += reduced[a][a];
        }
        // Levenberg–Marquardt damping keeps the step defined where H is singular.
        for (int a = 0; a < k; ++a) reduced[a][a] += 1e-6 * trace / k + 1e-300;
        if (!solveSmall(k, reduced, rhs)) return false;
        step = Vector3{};
        for (int a = 0; a < k; ++a) step += rhs[a] * basis[a];
        slope = 0.0;
        for (int a = 0; a < k; ++a) slope -= rhs[a] * dot(basis[a], gradient);  // g·step < 0
        return true;
    }

    // Backtracking (Armijo) along step from p's position; the local objective where p ends.
    double lineSearch(Label p, double objective, const Vector3& step, double slope)
    {
        const Vector3 start = positions[p];
        double length = 1.0;
        bool accepted = false;
        double trial = objective;
        for (int attempt = 0; attempt < 40; ++attempt, length *= 0.5) {
            positions[p] = start + length * step;
            refreshCorners(p);
            trial = 0.0;
            for (Label s : localSimplices) trial += penalty(s, nullptr, nullptr);
            if (trial <= objective + 1e-4 * length * slope && trial < objective) {
                accepted = true;
                break;
            }
        }
        if (!accepted) {
            positions[p] = start;
            refreshCorners(p);
            trial = objective;
        } else {
            moved[p] = 1;
        }
        return trial;
    }

    // One Gauss–Newton move of p; its local objective after, or nothing when p has nothing to do.
    std::optional<double> relaxPoint(Label p)
    {
        collectLocalSimplices(p);
        Vector3 gradient{};
        std::array<std::array<double, 3>, 3> hessian{};
        const double objective = localModel(p, gradient, hessian);
        if (objective == 0.0) return std::nullopt;
        Vector3 step{};
        double slope = 0.0;
        if (!newtonStep(p, gradient, hessian, step, slope)) return std::nullopt;
        return lineSearch(p, objective, step, slope);
    }

    // Whether every counted simplex touching a movable point is positive.
    bool allPositive(const std::vector<Label>& movable) const
    {
        bool positive = true;
        for (Label p : movable) {
            if (!positive) break;
            for (Label k = pointCornerOffsets[p]; k < pointCornerOffsets[p + 1] && positive; ++k) {
                const Label corner = pointCorners[k];
                for (Label q = cornerSimplexOffsets[corner]; q < cornerSimplexOffsets[corner + 1]; ++q) {
                    double volume = 0.0;
                    penalty(cornerSimplices[q], nullptr, &volume);
                    if (counts(cornerSimplices[q]) && !(volume > 0.0)) {
                        positive = false;
                        break;
                    }
                }
            }
        }
        return positive;
    }

    // One round: sweeps over the region of `inverted` grown by `layers`, until the caller's
    // test passes or the sweeps stagnate; `inverted` is updated as the test is rerun.
    void round(std::vector<Label>& inverted, int layers, const InvertedCellTest& isInverted, UntangleResult& result)
    {
        const std::vector<Label> movable = movablePoints(region(inverted, layers));
        double best = std::numeric_limits<double>::infinity();
        int sinceImprovement = 0;
        for (int sweep = 0; sweep < options.maxSweepsPerRound; ++sweep) {
            ++result.sweeps;
            double total = 0.0;
            for (Label p : movable) {
                if (const std::optional<double> trial = relaxPoint(p)) total += *trial;
            }
            if (allPositive(movable) || total == 0.0) {
                inverted = isInverted(positions);
                if (inverted.empty()) break;
            }
            // Stagnation (less than 0.1 % in 10 sweeps): this region cannot do better, grow it.
            if (total < (1.0 - 1e-3) * best) {
                best = total;
                sinceImprovement = 0;
            } else if (++sinceImprovement >= 10) {
                break;
            }
        }
    }

    // The cells still inverted (ascending), those of them with every point fixed, and the moved points.
    void finish(const std::vector<Label>& inverted, UntangleResult& result) const
    {
        result.remainingCells = inverted;
        std::sort(result.remainingCells.begin(), result.remainingCells.end());
        for (Label c : result.remainingCells) {
            bool allFixed = true;
            for (Label q = cells.cellOffsets[c]; q < cells.cellOffsets[c + 1] && allFixed; ++q) {
                std::array<Vector3, 3> basis;
                allFixed = admissibleBasis(dimension, constraints[cells.cellPoints[q]], basis) == 0;
            }
            if (allFixed) result.stuckCells.push_back(c);
        }
        for (Label p = 0; p < pointCount; ++p) result.movedPoints += moved[p];
    }
};

} // namespace

UntangleResult untangle(const SimplexDecomposition& cells, std::span<const Vector3> referencePositions,
                        std::span<const UntanglePointConstraint> constraints, std::vector<Vector3>& positions,
                        const InvertedCellTest& isInverted, const UntangleOptions& options)
{
    const Label pointCount = static_cast<Label>(positions.size());
    if (static_cast<Label>(referencePositions.size()) != pointCount || static_cast<Label>(constraints.size()) != pointCount)
        throw std::invalid_argument("untangle: positions, reference positions and constraints differ in size");
    UntangleResult result;
    std::vector<Label> inverted = isInverted(positions);
    result.initialInverted = static_cast<Label>(inverted.size());
    if (inverted.empty()) return result;

    Untangler untangler(cells, referencePositions, constraints, positions, options);
    int layers = std::max(1, options.layers);
    for (int round = 0; round < options.maxRounds && !inverted.empty(); ++round) {
        ++result.rounds;
        untangler.round(inverted, layers, isInverted, result);
        inverted = isInverted(positions);
        layers *= 2;
    }
    untangler.finish(inverted, result);
    return result;
}

} // namespace rbm
