#include "PartQuality.hpp"

#include "CheckMeshQuality.hpp"
#include "PetscSupport.hpp"
#include "RankExchange.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rbm::motion {

namespace {

static_assert(sizeof(Vector3) == 3 * sizeof(double), "cell centres travel as 3 doubles each");

// The integer value of entry `keyword` of a patch (myProcNo, neighbProcNo), or −1 when absent
// or not an integer.
int integerEntry(const Patch& patch, const std::string& keyword)
{
    for (const auto& [key, value] : patch.otherEntries) {
        if (key != keyword) continue;
        int number = -1;
        const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), number);
        return error == std::errc() && end == value.data() + value.size() ? number : -1;
    }
    return -1;
}

// True on every rank when any rank passes true. Collective.
bool anyRank(MPI_Comm communicator, bool local)
{
    int mine = local ? 1 : 0, any = 0;
    RBM_CHECK_PETSC(MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, communicator));
    return any != 0;
}

// Throws on every rank when one rank found a problem: that rank's message there, a pointer to
// it elsewhere (a throw on one rank alone would leave the others in the next collective call).
void throwOnEveryRankIfAny(MPI_Comm communicator, int rank, const std::string& problem)
{
    if (!anyRank(communicator, !problem.empty())) return;
    throw std::invalid_argument("PartQuality on rank " + std::to_string(rank) + ": " +
                                (problem.empty() ? "another rank's processor mesh does not fit (see its message)" : problem));
}

// checkMesh's angle of a non-orthogonality cosine, as computeCheckMeshExtremes takes it.
double nonOrthogonalityDegrees(double cosine)
{
    return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

} // namespace

PartQuality::PartQuality(const PolyMesh& processorMesh, MPI_Comm communicator)
    : mesh_(processorMesh), communicator_(communicator), evaluator_(std::in_place, processorMesh)
{
    int ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_rank(communicator, &rank_));
    RBM_CHECK_PETSC(MPI_Comm_size(communicator, &ranks));

    std::string problem;
    if (evaluator_->isTwoD()) problem = "the processor mesh is pseudo-2D (3D parts only)";
    std::map<int, int> patchesTo;   // per neighbour rank: its patches so far
    Label processorFaces = 0;
    for (const Patch& patch : processorMesh.patches) {
        if (patch.type == "processorCyclic") {
            // Its faces' neighbour centres would need the cyclic's transform.
            problem = "processorCyclic patch " + patch.name + " (cyclic patches across ranks are not supported)";
            break;
        }
        if (patch.type != "processor") continue;
        const int myProcNo = integerEntry(patch, "myProcNo");
        const int neighbProcNo = integerEntry(patch, "neighbProcNo");
        if (myProcNo != rank_ || neighbProcNo < 0 || neighbProcNo >= ranks || neighbProcNo == rank_) {
            problem = "processor patch " + patch.name + " has myProcNo " + std::to_string(myProcNo) + " and neighbProcNo " +
                      std::to_string(neighbProcNo) + ", but this is rank " + std::to_string(rank_) + " of " +
                      std::to_string(ranks) + " (one rank per processor, rank = myProcNo)";
            break;
        }
        processorPatches_.push_back({patch.startFace, patch.faceCount, neighbProcNo, patchesTo[neighbProcNo]++,
                                     processorFaces});
        processorFaces += patch.faceCount;
    }
    throwOnEveryRankIfAny(communicator, rank_, problem);

    // Matching patches: every rank tells each neighbour its patches' face counts towards it, in
    // patch order; the neighbour's own list must be the same (then the faces correspond one to
    // one, and no exchange below waits for a message that never comes).
    std::vector<std::vector<Label>> faceCountsTo(static_cast<std::size_t>(ranks));
    for (const ProcessorPatch& patch : processorPatches_) faceCountsTo[patch.neighbourRank].push_back(patch.faceCount);
    const std::vector<std::vector<Label>> faceCountsFrom = exchangeWithAllRanks(communicator, faceCountsTo);
    for (int r = 0; r < ranks && problem.empty(); ++r)
        if (faceCountsFrom[r] != faceCountsTo[r])
            problem = "its processor patches towards rank " + std::to_string(r) + " (" +
                      std::to_string(faceCountsTo[r].size()) + ") do not match that rank's (" +
                      std::to_string(faceCountsFrom[r].size()) + ") in number or face counts";
    throwOnEveryRankIfAny(communicator, rank_, problem);
    centresAcross_.resize(static_cast<std::size_t>(processorFaces));
}

StepQuality PartQuality::evaluateStep(std::span<const Vector3> points)
{
    // The cell figures and the internal faces' non-orthogonality as a serial mesh's; the
    // skewness without the processor faces' mirror-cell figure.
    if (!evaluator_) evaluator_.emplace(mesh_);
    StepQuality quality = evaluator_->evaluateStep(points);
    quality.maxSkewness = ownFacesMaxSkewness();
    const MeshGeometry& geometry = evaluator_->geometry();
    exchangeCellCentres(geometry);
    addProcessorFaces(points, geometry, quality);

    StepQuality whole;
    RBM_CHECK_PETSC(
        MPI_Allreduce(&quality.worstCellQuality, &whole.worstCellQuality, 1, MPI_DOUBLE, MPI_MIN, communicator_));
    const double largest[2] = {quality.maxNonOrthogonality, quality.maxSkewness};
    double wholeLargest[2] = {0.0, 0.0};
    RBM_CHECK_PETSC(MPI_Allreduce(largest, wholeLargest, 2, MPI_DOUBLE, MPI_MAX, communicator_));
    whole.maxNonOrthogonality = wholeLargest[0];
    whole.maxSkewness = wholeLargest[1];
    static_assert(sizeof(Label) == sizeof(std::int32_t));
    RBM_CHECK_PETSC(
        MPI_Allreduce(&quality.invertedCellCount, &whole.invertedCellCount, 1, MPI_INT32_T, MPI_SUM, communicator_));
    return whole;
}

double PartQuality::ownFacesMaxSkewness() const
{
    const std::vector<double>& faceSkew = evaluator_->stepFaceMeasures().faceSkew;
    double largest = 0.0;   // computeCheckMeshExtremes' start: skewness is at least 0
    const auto largestOf = [&](Label begin, Label end) {
        for (Label f = begin; f < end; ++f) largest = std::max(largest, faceSkew[f]);
    };
    largestOf(0, mesh_.internalFaceCount());
    for (const Patch& patch : mesh_.patches)
        if (patch.type != "processor") largestOf(patch.startFace, patch.startFace + patch.faceCount);
    return largest;
}

void PartQuality::exchangeCellCentres(const MeshGeometry& geometry)
{
    std::vector<MPI_Request> requests;
    requests.reserve(processorPatches_.size());
    for (const ProcessorPatch& patch : processorPatches_) {
        Vector3* centres = centresAcross_.data() + patch.firstCentre;
        const int count = 3 * patch.faceCount;
        MPI_Request request = MPI_REQUEST_NULL;
        if (patch.neighbourRank > rank_) {
            RBM_CHECK_PETSC(MPI_Irecv(centres, count, MPI_DOUBLE, patch.neighbourRank, patch.tag, communicator_, &request));
        } else {
            for (Label k = 0; k < patch.faceCount; ++k) centres[k] = geometry.cellCentres[mesh_.owner[patch.startFace + k]];
            RBM_CHECK_PETSC(MPI_Isend(centres, count, MPI_DOUBLE, patch.neighbourRank, patch.tag, communicator_, &request));
        }
        requests.push_back(request);
    }
    RBM_CHECK_PETSC(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE));
}

void PartQuality::addProcessorFaces(std::span<const Vector3> points, const MeshGeometry& geometry,
                                    StepQuality& quality) const
{
    // The serial formulas of an internal face with this rank's cell as its owner: the face's
    // area vector points out of that cell, and d runs from its centre to the neighbour's.
    double smallestCosine = 1.0;
    bool measured = false;
    for (const ProcessorPatch& patch : processorPatches_) {
        if (patch.neighbourRank < rank_) continue;   // measured by the neighbour
        for (Label k = 0; k < patch.faceCount; ++k) {
            const Label f = patch.startFace + k;
            const Vector3& ownCentre = geometry.cellCentres[mesh_.owner[f]];
            const Vector3& neighbourCentre = centresAcross_[patch.firstCentre + k];
            const Vector3& area = geometry.faceAreas[f];
            smallestCosine = std::min(smallestCosine, faceNonOrthogonalityCosine(ownCentre, neighbourCentre, area));
            quality.maxSkewness = std::max(quality.maxSkewness, faceSkewness(mesh_.face(f), points, geometry.faceCentres[f],
                                                                             area, ownCentre, neighbourCentre));
            measured = true;
        }
    }
    if (measured)
        quality.maxNonOrthogonality = std::max(quality.maxNonOrthogonality, nonOrthogonalityDegrees(smallestCosine));
}

void PartQuality::releaseWorkspaces() { evaluator_.reset(); }

} // namespace rbm::motion
