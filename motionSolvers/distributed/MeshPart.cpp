#include "MeshPart.hpp"

#include "RankExchange.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace rbm::motion {

namespace {

// A point of a halo cell as it travels: enough to make it a ghost node.
struct HaloPoint {
    Label globalId;
    int owner;
    Label row;
    double x, y, z;
};

} // namespace

MeshPart::MeshPart(MPI_Comm communicator, const LocalCells& part) : communicator_(communicator)
{
    RBM_CHECK_PETSC(MPI_Comm_rank(communicator, &rank_));
    const PointOwnership ownership = findPointOwnership(communicator, part);
    ownedNodeCount_ = ownership.ownedCount;
    globalNodeCount_ = ownership.globalPointCount;
    firstOwnedRow_ = ownership.firstOwnedRow;
    numberLocalNodes(part, ownership);
    addHaloCells(part, ownership);
    cellCount_ = static_cast<Label>(cellOffsets_.size()) - 1;
}

void MeshPart::releaseCells()
{
    std::vector<Label>{0}.swap(cellOffsets_);
    std::vector<Label>().swap(cellNodes_);
}

// Owned points first, then the rank's other points, each group in local point order; the
// rank's own cells in those labels.
void MeshPart::numberLocalNodes(const LocalCells& part, const PointOwnership& ownership)
{
    const Label pointCount = part.pointCount();
    pointNodes_.assign(pointCount, -1);
    Label next = 0;
    for (int pass = 0; pass < 2; ++pass)
        for (Label p = 0; p < pointCount; ++p) {
            if ((ownership.ownerRanks[p] == rank_) != (pass == 0)) continue;
            pointNodes_[p] = next++;
            nodePoints_.push_back(part.points[p]);
            nodeGlobalIds_.push_back(part.globalIds[p]);
            nodeRows_.push_back(ownership.rows[p]);
            nodeOwnerRanks_.push_back(ownership.ownerRanks[p]);
        }
    ownCellCount_ = part.cellCount();
    cellOffsets_ = part.cellOffsets;
    cellNodes_.resize(part.cellPoints.size());
    std::transform(part.cellPoints.begin(), part.cellPoints.end(), cellNodes_.begin(),
                   [&](Label p) { return pointNodes_[p]; });
}

// Every own cell goes to the owner of each of its points that another rank owns (once per
// rank); the cells received become the halo, their unknown points new ghost nodes.
void MeshPart::addHaloCells(const LocalCells& part, const PointOwnership& ownership)
{
    int ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(communicator_, &ranks));
    std::vector<std::vector<Label>> cellSizes(ranks);
    std::vector<std::vector<HaloPoint>> cellPoints(ranks);
    std::vector<int> destinations;
    for (Label c = 0; c < part.cellCount(); ++c) {
        destinations.clear();
        for (Label k = part.cellOffsets[c]; k < part.cellOffsets[c + 1]; ++k) {
            const int owner = ownership.ownerRanks[part.cellPoints[k]];
            if (owner != rank_ && std::find(destinations.begin(), destinations.end(), owner) == destinations.end())
                destinations.push_back(owner);
        }
        for (int d : destinations) {
            cellSizes[d].push_back(part.cellOffsets[c + 1] - part.cellOffsets[c]);
            for (Label k = part.cellOffsets[c]; k < part.cellOffsets[c + 1]; ++k) {
                const Label p = part.cellPoints[k];
                const Vector3& x = part.points[p];
                cellPoints[d].push_back({part.globalIds[p], ownership.ownerRanks[p], ownership.rows[p], x.x, x.y, x.z});
            }
        }
    }
    const auto sizesHere = exchangeWithAllRanks(communicator_, cellSizes);
    const auto pointsHere = exchangeWithAllRanks(communicator_, cellPoints);

    // Halo points that the rank holds are shared, so on its processor boundary: only those
    // need looking up by global label.
    std::unordered_map<Label, Label> nodeOfGlobalId;
    for (Label p = 0; p < part.pointCount(); ++p)
        if (part.onProcessorBoundary[p]) nodeOfGlobalId.emplace(part.globalIds[p], pointNodes_[p]);
    for (int r = 0; r < ranks; ++r) {
        std::size_t k = 0;
        for (Label size : sizesHere[r]) {
            for (Label j = 0; j < size; ++j, ++k) {
                const HaloPoint& point = pointsHere[r].at(k);
                const auto [where, added] = nodeOfGlobalId.emplace(point.globalId, nodeCount());
                if (added) {
                    nodePoints_.push_back({point.x, point.y, point.z});
                    nodeGlobalIds_.push_back(point.globalId);
                    nodeRows_.push_back(point.row);
                    nodeOwnerRanks_.push_back(point.owner);
                }
                cellNodes_.push_back(where->second);
            }
            cellOffsets_.push_back(static_cast<Label>(cellNodes_.size()));
        }
        if (k != pointsHere[r].size())
            throw std::logic_error("mesh part: halo cells from rank " + std::to_string(r) + " do not match their sizes");
    }
}

} // namespace rbm::motion
