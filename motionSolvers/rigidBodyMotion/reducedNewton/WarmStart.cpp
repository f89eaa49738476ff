#include "WarmStart.hpp"

#include "GramSchmidt.hpp"
#include "OrderedSums.hpp"
#include "TurnedStart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rbm::motion {

namespace {

// -rbm_reduced_correction_memory N, -rbm_reduced_harmonic_basis false and
// -rbm_reduced_turned_start false override the options.
// A part (RbmProblem::isPart) has no harmonic basis (it looks at the whole prescribed boundary);
// its turned start fits the boundary's motion from sums over the ranks (TurnedStart.cpp).
WarmStartOptions withPetscOptions(WarmStartOptions options, const RbmProblem& problem)
{
    if (problem.isPart()) options.harmonicBasis = false;
    PetscInt memory = options.correctionMemory;
    RBM_CHECK_PETSC(PetscOptionsGetInt(nullptr, "rbm_reduced_", "-correction_memory", &memory, nullptr));
    options.correctionMemory = std::max<int>(0, static_cast<int>(memory));
    PetscBool harmonicBasis = options.harmonicBasis ? PETSC_TRUE : PETSC_FALSE;
    RBM_CHECK_PETSC(PetscOptionsGetBool(nullptr, "rbm_reduced_", "-harmonic_basis", &harmonicBasis, nullptr));
    options.harmonicBasis = harmonicBasis == PETSC_TRUE;
    PetscBool turnedStart = options.turnedStart ? PETSC_TRUE : PETSC_FALSE;
    RBM_CHECK_PETSC(PetscOptionsGetBool(nullptr, "rbm_reduced_", "-turned_start", &turnedStart, nullptr));
    options.turnedStart = turnedStart == PETSC_TRUE;
    return options;
}

// A kept result's displacement of `node`; an empty result is the reference mesh (no
// displacement), kept without its zeros (WarmStart::record).
Vector3 keptDisplacement(const std::vector<Vector3>& result, int node)
{
    return result.empty() ? Vector3{} : result[node];
}

} // namespace

WarmStart::WarmStart(const RbmProblem& problem, ReducedEnergy& energy, LaplacianPreconditioner& preconditioner,
                     const RelativeDisplacement& relativeDisplacement, const WarmStartOptions& options)
    : problem_(problem), energy_(energy), preconditioner_(preconditioner), relativeDisplacement_(relativeDisplacement),
      options_(withPetscOptions(options, problem)), harmonicBasis_(problem, preconditioner, options_.harmonicBasis)
{
}

std::vector<double> WarmStart::boundaryRightHandSide(std::span<const Vector3> values,
                                                     std::span<const double> slidingOffset)
{
    const int m = problem_.unknownNodeCount();
    const int dim = problem_.dimension();
    const std::size_t size = static_cast<std::size_t>(m) * dim;
    const std::vector<int>& nodes = problem_.unknownNodes();
    const CellNeighbourGraph& graph = problem_.graph();
    const BlockPattern& pattern = problem_.blockPattern();
    auto flat = [dim](Vector3 v) {
        if (dim == 2) v.z = 0.0;
        return v;
    };
    // b_k = Σ_{j prescribed} w ū_j − (K c)_k: the right-hand side of the harmonic interpolation.
    // Only unknown nodes next to a prescribed one have a boundary term, and K c only with
    // sliding nodes (c = 0 otherwise): a warm start evaluates this twice.
    if (boundaryNeighbours_.empty()) {
        for (int a = 0; a < m; ++a) {
            const int i = nodes[a];
            for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
                if (!problem_.isUnknown(graph.neighbours[e])) {
                    boundaryNeighbours_.push_back(a);
                    break;
                }
        }
        boundaryNeighbours_.push_back(-1);  // the list is made (a solve may have none)
    }
    std::vector<double> b(size, 0.0);
    for (const int a : boundaryNeighbours_) {
        if (a < 0) break;
        const int i = nodes[a];
        Vector3 sum{};
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
            if (!problem_.isUnknown(graph.neighbours[e]))
                sum += problem_.edgeWeights()[e] * flat(values[graph.neighbours[e]]);
        for (int q = 0; q < dim; ++q) b[static_cast<std::size_t>(a) * dim + q] = sum[q];
    }
    if (problem_.hasSlidingNodes()) {
        const std::vector<double>& laplacian = preconditioner_.laplacian();
        for (int a = 0; a < m; ++a)
            for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
                for (int q = 0; q < dim; ++q)
                    b[static_cast<std::size_t>(a) * dim + q] -=
                        laplacian[position] * slidingOffset[static_cast<std::size_t>(pattern.columns[position]) * dim + q];
    }
    return b;
}

void WarmStart::extrapolateAlongHistory(std::span<const Vector3> prescribedDisplacement,
                                        std::vector<Vector3>& base) const
{
    const int n = problem_.nodeCount();
    const int dim = problem_.dimension();
    auto flat = [dim](Vector3 v) {
        if (dim == 2) v.z = 0.0;
        return v;
    };
    const std::vector<Vector3>& last = solutionHistory_[0];
    const std::vector<Vector3>& previous = solutionHistory_[1];
    double numerator = 0.0, denominator = 0.0;
    for (int node = 0; node < problem_.ownedNodeCount(); ++node) {  // a part: its owned nodes, summed over the ranks
        if (problem_.isUnknown(node)) continue;
        const Vector3 step = flat(last[node] - keptDisplacement(previous, node));
        numerator += dot(flat(prescribedDisplacement[node]) - flat(last[node]), step);
        denominator += normSquared(step);
    }
    numerator = problem_.sumOverRanks(numerator);
    denominator = problem_.sumOverRanks(denominator);
    const double secant = denominator > 0.0 ? numerator / denominator : 0.0;
    std::vector<double> coefficients{std::clamp(secant, -2.0, 2.0)};
    // |α| beyond 2: the boundary moves back past the last step (a turning point of the
    // motion between the steps), where the secant extrapolates the wrong way. Then the
    // candidate that fits the prescribed boundary best: the secant, the line through
    // the last result and each older one, or the fit over all (bestPredictorOnBoundary);
    // in a periodic motion the step after each reversal then starts at the result of the
    // step mirroring it (the same boundary).
    // (Not on a part: the fit sums over the prescribed nodes without reductions.)
    if (std::abs(secant) > 2.0 && solutionHistory_.size() >= 3 && !problem_.isPart())
        coefficients = bestPredictorOnBoundary(prescribedDisplacement, std::move(coefficients));
    for (std::size_t j = 0; j < coefficients.size(); ++j) {
        if (coefficients[j] == 0.0) continue;
        const std::vector<Vector3>& older = solutionHistory_[j + 1];
        for (int node = 0; node < n; ++node) base[node] += coefficients[j] * (last[node] - keptDisplacement(older, node));
    }
}

void WarmStart::keepTurnedStartIfLower(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess,
                                       ReducedIterate& point)
{
    std::vector<Vector3>& u = point.displacement;
    // Where the boundary is one rigid body moving in a fixed frame, also the harmonic
    // interpolation of its TURN: s = K⁻¹ b(1 on the body, 0 on the fixed nodes), and every
    // node moved by the body's motion scaled by s — turned by s θ about the body's centre
    // and shifted by s t — instead of interpolating the displacement vectors, which
    // shortens the cells between (a turned neighbourhood's chord, not its arc). The start
    // of lower energy is kept (with its fitted rotations): near a large turn the turned one
    // starts far closer to the minimum and saves a Newton step.
    // A warm start without the history for the secant (the first after a restart; a
    // series' second step continues a chain from the reference mesh, see record()): the
    // same from the guess, the body's motion since the guess turned in.
    trial_ = u;
    const std::span<const Vector3> base =
        initialGuess ? std::span<const Vector3>(initialGuess->displacement) : std::span<const Vector3>{};
    if (turnedHarmonicStart(problem_, preconditioner_, prescribedDisplacement, trial_, base)) {
        // The turned field does not know the cyclic pairs: their B nodes follow their A nodes.
        problem_.enforceCoupledPairs(trial_);
        const double turnedEnergy = energy_.fitAndEnergy(trial_, trialRotations_);
        if (turnedEnergy < point.energy) {
            u.swap(trial_);
            point.rotations.swap(trialRotations_);
            point.energy = turnedEnergy;
        }
    }
}

WarmStart::Predicted WarmStart::predictFromGuess(std::span<const Vector3> prescribedDisplacement,
                                                 const RbmState& initialGuess, std::span<const double> offset)
{
    const int m = problem_.unknownNodeCount();
    const int dim = problem_.dimension();
    const std::size_t size = static_cast<std::size_t>(m) * dim;
    const std::vector<int>& nodes = problem_.unknownNodes();
    auto flat = [dim](Vector3 v) {
        if (dim == 2) v.z = 0.0;
        return v;
    };
    Predicted result;
    result.start.assign(size, 0.0);
    std::vector<double> correction(size);
    // When the guess is this solver's own last result and the one before is known, a secant
    // step along the boundary's path first: G = u_n + α (u_n − u_{n−1}), α fitting the
    // prescribed change best (along a smooth motion the start is then off by the second
    // difference of the motion instead of the first). Then the boundary mismatch moved in
    // harmonically: start = G + K⁻¹ (b(new) − b(G)).
    problem_.checkNodeArray(initialGuess.displacement, "initial guess displacement");
    std::vector<Vector3> base(initialGuess.displacement.begin(), initialGuess.displacement.end());
    result.chained = solutionHistory_.size() >= 2 && solutionHistory_[0] == base;
    if (problem_.isPart()) result.chained = problem_.sumOverRanks(result.chained ? 0.0 : 1.0) == 0.0;  // all ranks alike
    if (result.chained) extrapolateAlongHistory(prescribedDisplacement, base);
    // On the prescribed nodes: the predictor's miss, the sizes of the new boundary, the
    // predictor's and the guess's (the two tests to rounding below).
    double missSquared = 0.0, restSquared = 0.0, baseSquared = 0.0, lastSquared = 0.0;
    for (int node = 0; node < problem_.ownedNodeCount(); ++node) {  // a part: summed over the ranks below
        if (problem_.isUnknown(node)) continue;
        missSquared += normSquared(flat(prescribedDisplacement[node]) - flat(base[node]));
        restSquared += normSquared(flat(prescribedDisplacement[node]));
        baseSquared += normSquared(flat(base[node]));
        lastSquared += normSquared(flat(initialGuess.displacement[node]));
    }
    missSquared = problem_.sumOverRanks(missSquared);
    restSquared = problem_.sumOverRanks(restSquared);
    baseSquared = problem_.sumOverRanks(baseSquared);
    lastSquared = problem_.sumOverRanks(lastSquared);
    // The predictor meets the prescribed boundary to rounding (a turning point of the motion
    // back to a boundary met before, whose kept result it reproduces; a boundary back at
    // rest): the start is usually the minimum already (the driver's displacement test comes first).
    result.boundaryReproduced =
        std::isfinite(restSquared + baseSquared) &&
        std::sqrt(missSquared) <= HarmonicChangeBasis::roundingChangeShare * std::sqrt(restSquared + baseSquared);
    std::vector<double> baseOffset(size);
    problem_.slidingOffset(base, baseOffset, dim);
    // K⁻¹ of the change is linear in the boundary's change (without sliding nodes): taken
    // from the extensions of the changes met before where the new one is their combination
    // (HarmonicChangeBasis), solved otherwise.
    std::vector<double> boundaryChange;
    if (!harmonicBasis_.correctionFromBasis(prescribedDisplacement, base, boundaryChange, correction)) {
        std::vector<double> change = boundaryRightHandSide(prescribedDisplacement, offset);
        const std::vector<double> previous = boundaryRightHandSide(base, baseOffset);
        for (std::size_t k = 0; k < size; ++k) change[k] -= previous[k];
        if (!preconditioner_.apply(change, correction)) result.failure = "DIVERGED_LINEAR_SOLVE (harmonic predictor)";
        else harmonicBasis_.remember(std::move(boundaryChange), correction);
    }
    for (int a = 0; a < m; ++a) {
        const Vector3 guess = flat(base[nodes[a]]);
        for (int q = 0; q < dim; ++q) {
            const std::size_t k = static_cast<std::size_t>(a) * dim + q;
            result.start[k] = guess[q] + correction[k] + (offset[k] - baseOffset[k]);
        }
    }
    // A boundary back at rest to rounding (a pitching motion about its rest position, every
    // half period): the reference mesh, no displacement, is its exact minimum, and the
    // start. The predictor's start is kept: the chain's correction is still its miss (the
    // subspace step of the next steps learns from it).
    if (result.failure.empty() && std::isfinite(lastSquared) &&
        std::sqrt(restSquared) <= HarmonicChangeBasis::roundingChangeShare * std::sqrt(lastSquared)) {
        result.predictorStart = result.start;
        result.start.assign(offset.begin(), offset.end());  // the sliding nodes' normal part (zero at rest, to rounding)
        result.boundaryReproduced = true;
    }
    return result;
}

WarmStart::Predicted WarmStart::harmonicStart(std::span<const Vector3> prescribedDisplacement,
                                              std::span<const double> offset)
{
    // Cold start: the harmonic interpolation of the boundary, c n + P K⁻¹ P b.
    Predicted result;
    const std::size_t size = offset.size();
    std::vector<double> correction(size);
    if (!preconditioner_.apply(boundaryRightHandSide(prescribedDisplacement, offset), correction))
        result.failure = "DIVERGED_LINEAR_SOLVE (harmonic start)";
    result.start.resize(size);
    for (std::size_t k = 0; k < size; ++k) result.start[k] = offset[k] + correction[k];
    return result;
}

WarmStart::Start WarmStart::start(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess,
                                  const CompactUnknowns& unknowns)
{
    const int n = problem_.nodeCount();
    const int dim = problem_.dimension();
    const std::vector<double> offset = unknowns.slidingOffset();  // this start's only
    Start result;
    std::vector<Vector3>& u = result.point.displacement;
    u.assign(static_cast<std::size_t>(n), Vector3{});
    for (int node = 0; node < n; ++node) {
        if (problem_.isUnknown(node)) continue;
        u[node] = prescribedDisplacement[node];
        if (dim == 2) u[node].z = 0.0;
    }
    const Predicted predicted = initialGuess ? predictFromGuess(prescribedDisplacement, *initialGuess, offset)
                                             : harmonicStart(prescribedDisplacement, offset);
    unknowns.set(u, predicted.start);
    std::vector<Matrix3>& rotations = result.point.rotations;
    result.point.energy = energy_.fitAndEnergy(u, rotations);
    if ((!initialGuess || !predicted.chained) && predicted.failure.empty() && options_.turnedStart)
        keepTurnedStartIfLower(prescribedDisplacement, initialGuess, result.point);
    // The start actually taken (after the turned one's choice), or the predictor's where the
    // reference mesh was taken instead: the step's Newton correction is the result minus it
    // (the subspace step of later steps).
    result.predicted = unknowns.compact(u);
    if (!predicted.predictorStart.empty()) {
        trial_ = u;
        unknowns.set(trial_, predicted.predictorStart);
        result.predicted = unknowns.compact(trial_);
    }
    result.point.gradient.assign(offset.size(), 0.0);
    energy_.gradient(u, rotations, result.point.gradient);
    result.point.gradientNorm = problem_.compactNorm(result.point.gradient);
    releaseTrial();
    result.chained = predicted.chained;
    result.boundaryReproduced = predicted.boundaryReproduced;
    result.failure = predicted.failure;
    // The subspace step: along a chain, in the span of the chain's own corrections (the
    // secant predictor's misses); a warm start outside a chain (the second after a restart,
    // whose first kept no history), in that of the last solve's (the miss of its turned start).
    result.subspaceStepDue = initialGuess && !recentCorrections_.empty() && predicted.chained == correctionsFromChain_;
    return result;
}

namespace {

// The prescribed change b − u_0 and the differences u_0 − u_j (j ≥ 1) on the prescribed nodes,
// flattened (2D: in-plane components only).
struct BoundaryDifferences {
    std::vector<double> target;
    std::vector<std::vector<double>> columns;
};

BoundaryDifferences boundaryDifferences(const RbmProblem& problem, std::span<const Vector3> prescribed,
                                        const std::vector<std::vector<Vector3>>& history)
{
    const int dim = problem.dimension();
    BoundaryDifferences d;
    d.columns.resize(history.size() - 1);
    for (int node = 0; node < problem.nodeCount(); ++node) {
        if (problem.isUnknown(node)) continue;
        for (int q = 0; q < dim; ++q) {
            d.target.push_back(prescribed[node][q] - history[0][node][q]);
            for (std::size_t j = 1; j < history.size(); ++j)
                d.columns[j - 1].push_back(history[0][node][q] - keptDisplacement(history[j], node)[q]);
        }
    }
    return d;
}

} // namespace

std::vector<double> WarmStart::bestPredictorOnBoundary(std::span<const Vector3> prescribedDisplacement,
                                                       std::vector<double> secant) const
{
    // Candidates c (G = u_0 + Σ_j c_j (u_0 − u_j)): the clamped secant; each older result j alone,
    // c_j fitted; all together by least squares (orthonormalise: a nearly dependent column is
    // left out, as a result repeated at a reversal gives a zero difference). Every c_j clamped
    // to ±2. The smallest misfit |b − G| on the prescribed nodes wins; within 1e-9 of it, the candidate
    // that extrapolates least (the smallest largest |c_j|): where the boundary moves along one
    // fixed field, every candidate fits it exactly and the nearest result is the right start.
    const BoundaryDifferences d = boundaryDifferences(problem_, prescribedDisplacement, solutionHistory_);
    const std::size_t columns = d.columns.size();
    std::vector<std::vector<double>> candidates;
    secant.resize(columns, 0.0);
    candidates.push_back(std::move(secant));
    for (std::size_t j = 1; j < columns; ++j) {
        const double squared = problem_.compactDot(d.columns[j], d.columns[j]);
        if (!(squared > 0.0)) continue;
        std::vector<double> alone(columns, 0.0);
        alone[j] = std::clamp(problem_.compactDot(d.target, d.columns[j]) / squared, -2.0, 2.0);
        candidates.push_back(std::move(alone));
    }
    const auto [basis, r, kept] = orthonormalise(d.columns);
    std::vector<double> all(columns, 0.0);
    for (std::size_t i = basis.size(); i-- > 0;) {  // R c = Qᵀ target, R upper triangular
        double value = problem_.compactDot(basis[i], d.target);
        for (std::size_t l = i + 1; l < basis.size(); ++l) value -= r[l][i] * all[kept[l]];
        all[kept[i]] = value / r[i][i];
    }
    for (double& c : all) c = std::clamp(c, -2.0, 2.0);
    candidates.push_back(std::move(all));

    auto misfit = [&](const std::vector<double>& c) {
        std::vector<double> left = d.target;
        for (std::size_t j = 0; j < columns; ++j)
            if (c[j] != 0.0)
                for (std::size_t k = 0; k < left.size(); ++k) left[k] -= c[j] * d.columns[j][k];
        return problem_.compactNorm(left);
    };
    auto reach = [](const std::vector<double>& c) {
        double largest = 0.0;
        for (double value : c) largest = std::max(largest, std::abs(value));
        return largest;
    };
    std::vector<double> misfits;
    double best = std::numeric_limits<double>::infinity();
    for (const std::vector<double>& c : candidates) {
        misfits.push_back(misfit(c));
        best = std::min(best, misfits.back());
    }
    const double scale = problem_.compactNorm(d.target);
    std::size_t chosen = 0;
    bool found = false;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        if (misfits[k] > best + 1e-9 * scale) continue;
        if (!found || reach(candidates[k]) < reach(candidates[chosen])) chosen = k;
        found = true;
    }
    return candidates[chosen];
}

namespace {
// A subspace step, or a correction kept for it, matters when it moves some node by more than
// this many displacement tolerances of its shortest edge (below, the displacement test and
// Newton finish more cheaply; at a reversal of the motion the predictor is the solution).
constexpr double significantCorrection = 10.0;
} // namespace

int WarmStart::subspaceStep(ReducedIterate& point, const CompactUnknowns& unknowns, bool monitor)
{
    std::vector<Vector3>& u = point.displacement;
    std::vector<Matrix3>& rotations = point.rotations;
    double& energy = point.energy;
    std::vector<double>& g = point.gradient;
    // An orthonormal basis of the corrections; nearly dependent ones are left out.
    const std::vector<std::vector<double>> basis = orthonormalise(recentCorrections_).basis;
    const int k = static_cast<int>(basis.size());
    if (k == 0) return 0;
    // A = Wᵀ S W and b = −Wᵀ ∇Ẽ; A by Cholesky (k ≤ a few), given up unless positive definite.
    energy_.prepareHessian(u, rotations);
    std::vector<double> product(g.size());
    std::vector<double> a(static_cast<std::size_t>(k) * k), b(static_cast<std::size_t>(k));
    for (int j = 0; j < k; ++j) {
        energy_.applyHessian(basis[j], product);
        for (int i = 0; i < k; ++i) a[static_cast<std::size_t>(i) * k + j] = problem_.compactDot(basis[i], product);
        b[j] = -problem_.compactDot(basis[j], g);
    }
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < i; ++j) a[static_cast<std::size_t>(i) * k + j] = a[static_cast<std::size_t>(j) * k + i] =
                                        0.5 * (a[static_cast<std::size_t>(i) * k + j] + a[static_cast<std::size_t>(j) * k + i]);
    for (int j = 0; j < k; ++j) {
        double pivot = a[static_cast<std::size_t>(j) * k + j];
        for (int l = 0; l < j; ++l) pivot -= a[static_cast<std::size_t>(j) * k + l] * a[static_cast<std::size_t>(j) * k + l];
        if (!(pivot > 0.0)) return 0;  // negative curvature in W: leave it to Newton's safeguards
        const double root = std::sqrt(pivot);
        a[static_cast<std::size_t>(j) * k + j] = root;
        for (int i = j + 1; i < k; ++i) {
            double value = a[static_cast<std::size_t>(i) * k + j];
            for (int l = 0; l < j; ++l) value -= a[static_cast<std::size_t>(i) * k + l] * a[static_cast<std::size_t>(j) * k + l];
            a[static_cast<std::size_t>(i) * k + j] = value / root;
        }
    }
    std::vector<double> c = b;  // L Lᵀ c = b
    for (int i = 0; i < k; ++i) {
        for (int l = 0; l < i; ++l) c[i] -= a[static_cast<std::size_t>(i) * k + l] * c[l];
        c[i] /= a[static_cast<std::size_t>(i) * k + i];
    }
    for (int i = k - 1; i >= 0; --i) {
        for (int l = i + 1; l < k; ++l) c[i] -= a[static_cast<std::size_t>(l) * k + i] * c[l];
        c[i] /= a[static_cast<std::size_t>(i) * k + i];
    }
    std::vector<double> step(g.size(), 0.0);
    for (int j = 0; j < k; ++j)
        for (std::size_t q = 0; q < step.size(); ++q) step[q] += c[j] * basis[j][q];
    const double slope = problem_.compactDot(g, step);  // −bᵀA⁻¹b < 0
    // A decrease the energy's rounding cannot show (a start at the minimum already: a warm start
    // from the solution, or one solved to round-off): not taken.
    if (!(-0.5 * slope > 1e-13 * std::abs(energy))) {
        if (monitor) std::printf("  reduced Newton, subspace of %d correction(s): decrease at rounding level, not taken\n", k);
        return 0;
    }
    if (options_.displacementTolerance > 0.0 &&
        relativeDisplacement_.largest(step) <= significantCorrection * options_.displacementTolerance) {
        if (monitor) std::printf("  reduced Newton, subspace of %d correction(s): step within 10 tolerances, not taken\n", k);
        return 0;
    }
    unknowns.moveAlong(u, step, 1.0, trial_);
    const double trialEnergy = energy_.fitAndEnergy(trial_, trialRotations_);
    const bool accepted = slope < 0.0 && std::isfinite(trialEnergy) && trialEnergy <= energy + 1e-4 * slope;
    if (accepted) {
        u.swap(trial_);
        rotations.swap(trialRotations_);
    }
    releaseTrial();
    if (monitor)
        std::printf("  reduced Newton, subspace of %d correction(s): energy %.12e -> %.12e%s\n", k, energy, trialEnergy,
                    accepted ? "" : ", not taken");
    if (!accepted) return 0;
    energy = trialEnergy;
    energy_.gradient(u, rotations, g);
    point.gradientNorm = problem_.compactNorm(g);
    return k;
}

void WarmStart::releaseTrial()
{
    std::vector<Vector3>().swap(trial_);
    std::vector<Matrix3>().swap(trialRotations_);
}

void WarmStart::record(const Start& start, const std::vector<Vector3>& u, bool converged, bool warm,
                       const CompactUnknowns& unknowns)
{
    const std::size_t size = start.predicted.size();
    const bool chained = start.chained;
    const bool correctionsFit = chained == correctionsFromChain_;
    const std::vector<double>& predicted = start.predicted;
    // History of the predictor: only along a chain of warm starts from own results.
    if (!warm) solutionHistory_.clear();
    // The corrections of converged steps, newest first (a reversal's zero one adds nothing); a
    // solve that does not continue a chain, or the first of a chain, starts the list afresh.
    if (!chained || !correctionsFit) recentCorrections_.clear();
    correctionsFromChain_ = chained;
    if (!converged || options_.correctionMemory <= 0) {
        recentCorrections_.clear();
    } else {
        std::vector<double> newCorrection = unknowns.compact(u);
        for (std::size_t k = 0; k < size; ++k) newCorrection[k] -= predicted[k];
        // Only corrections of the predictor's error, not of a few tolerances (a reversal of
        // the motion, whose predictor was the solution already): noise would take a place.
        const bool significant =
            options_.displacementTolerance > 0.0
                ? relativeDisplacement_.largest(newCorrection) > significantCorrection * options_.displacementTolerance
                : problem_.compactNorm(newCorrection) > 0.0;
        if (significant) {
            recentCorrections_.insert(recentCorrections_.begin(), std::move(newCorrection));
            if (recentCorrections_.size() > static_cast<std::size_t>(options_.correctionMemory))
                recentCorrections_.resize(static_cast<std::size_t>(options_.correctionMemory));
        }
    }
    solutionHistory_.insert(solutionHistory_.begin(), u);
    // After a cold solve, the reference mesh is the result before it: no displacement is the
    // exact minimum (Ẽ = 0) for a boundary that does not move. So the next warm start from this
    // result continues a chain of two results, and takes the secant predictor at once
    // (u₁ + α u₁, its boundary mismatch moved in harmonically) instead of the turned start from
    // the guess; its Newton correction then is a chain's, and the third step takes the subspace
    // step along it: the series' third and fourth steps start much closer to their minima.
    // (Kept as an empty result: its zeros would be 24 bytes a node through the next solves.)
    if (!warm && converged) solutionHistory_.emplace_back();
    if (solutionHistory_.size() > keptResults) solutionHistory_.resize(keptResults);
}

} // namespace rbm::motion
