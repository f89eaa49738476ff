#pragma once
// Personalised all-to-all of plain values: every rank sends its own list to every other rank
// (MPI_Alltoall of the counts, then MPI_Alltoallv of the values). The building block of the
// rendezvous steps that set up a distributed mesh (PointOwnership, MeshPart) and of the
// quality exchange (PartQuality): each step is one or two such exchanges, so no step needs to
// know in advance who talks to whom.
//
// MPI's counts and displacements are ints: one MPI_Alltoallv moves less than 2 GiB in all to
// or from a rank, which a part of a 10⁸-cell mesh can exceed. The lists therefore travel in
// rounds of at most `roundBytes` per pair of ranks (by default 2³¹−1 over the rank count, so
// every round's displacements fit), as many rounds as the largest list needs, agreed over the
// ranks; a small exchange is one round, as before.
//
// T must be trivially copyable; it travels as bytes (both ends run the same program).

#include "PetscSupport.hpp"

#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace rbm::motion {

// Collective on `communicator`: outgoing[r] goes to rank r; the result's [r] is what rank r
// sent here. outgoing must have one list per rank. roundBytes > 0 caps a round's bytes per
// pair of ranks (tests use a few bytes); 0: the largest that keeps MPI's ints in range.
template <typename T>
std::vector<std::vector<T>> exchangeWithAllRanks(MPI_Comm communicator, const std::vector<std::vector<T>>& outgoing,
                                                 std::size_t roundBytes = 0)
{
    static_assert(std::is_trivially_copyable_v<T>);
    int ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(communicator, &ranks));
    if (static_cast<int>(outgoing.size()) != ranks)
        throw std::invalid_argument("exchangeWithAllRanks: one list per rank expected");
    const std::size_t limit = static_cast<std::size_t>(INT_MAX) / static_cast<std::size_t>(ranks);
    const std::size_t chunk = roundBytes > 0 ? std::min(roundBytes, limit) : limit;

    std::vector<std::uint64_t> sendTotal(ranks), receiveTotal(ranks);
    for (int r = 0; r < ranks; ++r) sendTotal[r] = outgoing[r].size() * sizeof(T);
    RBM_CHECK_PETSC(MPI_Alltoall(sendTotal.data(), 1, MPI_UINT64_T, receiveTotal.data(), 1, MPI_UINT64_T, communicator));
    std::uint64_t largest = 0;
    for (int r = 0; r < ranks; ++r) largest = std::max({largest, sendTotal[r], receiveTotal[r]});
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_UINT64_T, MPI_MAX, communicator));
    const std::uint64_t rounds = std::max<std::uint64_t>(1, (largest + chunk - 1) / chunk);

    std::vector<std::vector<T>> incoming(ranks);
    for (int r = 0; r < ranks; ++r) incoming[r].resize(receiveTotal[r] / sizeof(T));
    std::vector<int> sendBytes(ranks), receiveBytes(ranks), sendOffsets(ranks + 1), receiveOffsets(ranks + 1);
    std::vector<char> sendBuffer, receiveBuffer;
    // The bytes [begin, begin + chunk) of a list of `total` bytes: how many there are.
    auto roundPart = [chunk](std::uint64_t total, std::uint64_t begin) {
        return static_cast<int>(begin >= total ? 0 : std::min<std::uint64_t>(chunk, total - begin));
    };
    for (std::uint64_t round = 0; round < rounds; ++round) {
        const std::uint64_t begin = round * chunk;
        sendOffsets[0] = receiveOffsets[0] = 0;
        for (int r = 0; r < ranks; ++r) {
            sendBytes[r] = roundPart(sendTotal[r], begin);
            receiveBytes[r] = roundPart(receiveTotal[r], begin);
            sendOffsets[r + 1] = sendOffsets[r] + sendBytes[r];
            receiveOffsets[r + 1] = receiveOffsets[r] + receiveBytes[r];
        }
        sendBuffer.resize(static_cast<std::size_t>(sendOffsets[ranks]));
        receiveBuffer.resize(static_cast<std::size_t>(receiveOffsets[ranks]));
        for (int r = 0; r < ranks; ++r)
            if (sendBytes[r] > 0)
                std::memcpy(sendBuffer.data() + sendOffsets[r],
                            reinterpret_cast<const char*>(outgoing[r].data()) + begin, static_cast<std::size_t>(sendBytes[r]));
        RBM_CHECK_PETSC(MPI_Alltoallv(sendBuffer.data(), sendBytes.data(), sendOffsets.data(), MPI_BYTE,
                                      receiveBuffer.data(), receiveBytes.data(), receiveOffsets.data(), MPI_BYTE,
                                      communicator));
        for (int r = 0; r < ranks; ++r)
            if (receiveBytes[r] > 0)
                std::memcpy(reinterpret_cast<char*>(incoming[r].data()) + begin, receiveBuffer.data() + receiveOffsets[r],
                            static_cast<std::size_t>(receiveBytes[r]));
    }
    return incoming;
}

} // namespace rbm::motion
