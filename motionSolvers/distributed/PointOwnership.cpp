#include "PointOwnership.hpp"

#include "RankExchange.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

namespace rbm::motion {

namespace {

struct GlobalLabelRank {
    Label globalId;
    int rank;
};

struct GlobalLabelRow {
    Label globalId;
    int owner;
    Label row;
};

// The rank that keeps the directory entry of global label g.
int directoryRank(Label g, Label globalCount, int ranks)
{
    return static_cast<int>(static_cast<std::int64_t>(g) * ranks / std::max<Label>(globalCount, 1));
}

// Round 1: every holder of a processor-boundary point tells its directory rank, which answers
// the lowest holder. Returns the directory's entries (label, holder), sorted by label then
// holder, for round 2; fills ownership.ownerRanks.
std::vector<GlobalLabelRank> findOwners(MPI_Comm communicator, const LocalCells& part, Label labelCount,
                                        PointOwnership& ownership)
{
    int ranks = 1, rank = 0;
    RBM_CHECK_PETSC(MPI_Comm_size(communicator, &ranks));
    RBM_CHECK_PETSC(MPI_Comm_rank(communicator, &rank));
    std::vector<std::vector<Label>> held(ranks);
    for (Label p = 0; p < part.pointCount(); ++p)
        if (part.onProcessorBoundary[p]) held[directoryRank(part.globalIds[p], labelCount, ranks)].push_back(part.globalIds[p]);
    const auto heldHere = exchangeWithAllRanks(communicator, held);
    std::vector<GlobalLabelRank> entries;
    for (int r = 0; r < ranks; ++r)
        for (Label g : heldHere[r]) entries.push_back({g, r});
    std::sort(entries.begin(), entries.end(), [](const GlobalLabelRank& a, const GlobalLabelRank& b) {
        return a.globalId != b.globalId ? a.globalId < b.globalId : a.rank < b.rank;
    });
    std::vector<std::vector<GlobalLabelRank>> owners(ranks);  // (g, lowest holder) to each holder
    for (std::size_t first = 0; first < entries.size();) {
        std::size_t end = first;
        while (end < entries.size() && entries[end].globalId == entries[first].globalId) ++end;
        for (std::size_t k = first; k < end; ++k)
            owners[entries[k].rank].push_back({entries[first].globalId, entries[first].rank});
        first = end;
    }
    const auto ownersHere = exchangeWithAllRanks(communicator, owners);
    ownership.ownerRanks.assign(part.pointCount(), rank);
    for (Label p = 0; p < part.pointCount(); ++p) {
        if (!part.onProcessorBoundary[p]) continue;
        // Each directory's answers are sorted by label.
        const auto& answers = ownersHere[directoryRank(part.globalIds[p], labelCount, ranks)];
        const auto found = std::lower_bound(answers.begin(), answers.end(), part.globalIds[p],
                                            [](const GlobalLabelRank& a, Label g) { return a.globalId < g; });
        if (found == answers.end() || found->globalId != part.globalIds[p])
            throw std::logic_error("point ownership: no answer for global point " + std::to_string(part.globalIds[p]));
        ownership.ownerRanks[p] = found->rank;
    }
    return entries;
}

// Rows of the owned points: local order, after the lower ranks' owned points.
void numberOwnedPoints(MPI_Comm communicator, int rank, PointOwnership& ownership)
{
    const auto pointCount = static_cast<Label>(ownership.ownerRanks.size());
    for (Label p = 0; p < pointCount; ++p) ownership.ownedCount += ownership.ownerRanks[p] == rank ? 1 : 0;
    RBM_CHECK_PETSC(MPI_Exscan(&ownership.ownedCount, &ownership.firstOwnedRow, 1, MPI_INT, MPI_SUM, communicator));
    if (rank == 0) ownership.firstOwnedRow = 0;  // MPI_Exscan leaves rank 0's result undefined
    RBM_CHECK_PETSC(
        MPI_Allreduce(&ownership.ownedCount, &ownership.globalPointCount, 1, MPI_INT, MPI_SUM, communicator));
    ownership.rows.assign(pointCount, -1);
    Label nextRow = ownership.firstOwnedRow;
    for (Label p = 0; p < pointCount; ++p)
        if (ownership.ownerRanks[p] == rank) ownership.rows[p] = nextRow++;
}

const GlobalLabelRow& rowOfLabel(const std::vector<GlobalLabelRow>& sorted, Label g)
{
    const auto found = std::lower_bound(sorted.begin(), sorted.end(), g,
                                        [](const GlobalLabelRow& a, Label label) { return a.globalId < label; });
    if (found == sorted.end() || found->globalId != g)
        throw std::logic_error("point ownership: no row for global point " + std::to_string(g));
    return *found;
}

std::vector<GlobalLabelRow> sortedByLabel(const std::vector<std::vector<GlobalLabelRow>>& lists)
{
    std::vector<GlobalLabelRow> all;
    for (const auto& list : lists) all.insert(all.end(), list.begin(), list.end());
    std::sort(all.begin(), all.end(), [](const GlobalLabelRow& a, const GlobalLabelRow& b) { return a.globalId < b.globalId; });
    return all;
}

// Round 2: owners post the rows of their shared points to the directory, which passes them
// on to the other holders (`entries`: findOwners' result).
void shareRows(MPI_Comm communicator, const LocalCells& part, Label labelCount,
               const std::vector<GlobalLabelRank>& entries, PointOwnership& ownership)
{
    int ranks = 1, rank = 0;
    RBM_CHECK_PETSC(MPI_Comm_size(communicator, &ranks));
    RBM_CHECK_PETSC(MPI_Comm_rank(communicator, &rank));
    std::vector<std::vector<GlobalLabelRow>> posted(ranks);
    for (Label p = 0; p < part.pointCount(); ++p)
        if (part.onProcessorBoundary[p] && ownership.ownerRanks[p] == rank)
            posted[directoryRank(part.globalIds[p], labelCount, ranks)].push_back(
                {part.globalIds[p], rank, ownership.rows[p]});
    const std::vector<GlobalLabelRow> rowsKeptHere = sortedByLabel(exchangeWithAllRanks(communicator, posted));
    std::vector<std::vector<GlobalLabelRow>> forwarded(ranks);
    for (const GlobalLabelRank& entry : entries) {
        const GlobalLabelRow& row = rowOfLabel(rowsKeptHere, entry.globalId);
        if (entry.rank != row.owner) forwarded[entry.rank].push_back(row);
    }
    const std::vector<GlobalLabelRow> sharedRows = sortedByLabel(exchangeWithAllRanks(communicator, forwarded));
    for (Label p = 0; p < part.pointCount(); ++p)
        if (ownership.ownerRanks[p] != rank) ownership.rows[p] = rowOfLabel(sharedRows, part.globalIds[p]).row;
}

} // namespace

PointOwnership findPointOwnership(MPI_Comm communicator, const LocalCells& part)
{
    int rank = 0;
    RBM_CHECK_PETSC(MPI_Comm_rank(communicator, &rank));
    if (part.globalIds.size() != part.points.size() || part.onProcessorBoundary.size() != part.points.size())
        throw std::invalid_argument("point ownership: globalIds and onProcessorBoundary need one entry per point");
    Label largest = -1;
    for (Label g : part.globalIds) {
        if (g < 0) throw std::invalid_argument("negative global point label " + std::to_string(g));
        largest = std::max(largest, g);
    }
    const Label localCount = largest + 1;
    Label labelCount = 0;
    RBM_CHECK_PETSC(MPI_Allreduce(&localCount, &labelCount, 1, MPI_INT, MPI_MAX, communicator));
    PointOwnership ownership;
    const std::vector<GlobalLabelRank> entries = findOwners(communicator, part, labelCount, ownership);
    numberOwnedPoints(communicator, rank, ownership);
    shareRows(communicator, part, labelCount, entries, ownership);
    return ownership;
}

} // namespace rbm::motion
