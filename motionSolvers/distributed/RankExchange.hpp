#pragma once
// Personalised all-to-all of plain values: every rank sends its own list to every other rank
// (MPI_Alltoall of the counts, then MPI_Alltoallv of the values). The building block of the
// rendezvous steps that set up a distributed mesh (PointOwnership, MeshPart): each setup
// step is one or two such exchanges, so no step needs to know in advance who talks to whom.
//
// T must be trivially copyable; it travels as bytes (both ends run the same program).

#include "PetscSupport.hpp"

#include <mpi.h>

#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace rbm::motion {

// Collective on `communicator`: outgoing[r] goes to rank r; the result's [r] is what rank r
// sent here. outgoing must have one list per rank.
template <typename T>
std::vector<std::vector<T>> exchangeWithAllRanks(MPI_Comm communicator, const std::vector<std::vector<T>>& outgoing)
{
    static_assert(std::is_trivially_copyable_v<T>);
    int ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(communicator, &ranks));
    if (static_cast<int>(outgoing.size()) != ranks)
        throw std::invalid_argument("exchangeWithAllRanks: one list per rank expected");
    std::vector<int> sendBytes(ranks), receiveBytes(ranks), sendOffsets(ranks + 1, 0), receiveOffsets(ranks + 1, 0);
    for (int r = 0; r < ranks; ++r) sendBytes[r] = static_cast<int>(outgoing[r].size() * sizeof(T));
    RBM_CHECK_PETSC(MPI_Alltoall(sendBytes.data(), 1, MPI_INT, receiveBytes.data(), 1, MPI_INT, communicator));
    for (int r = 0; r < ranks; ++r) {
        sendOffsets[r + 1] = sendOffsets[r] + sendBytes[r];
        receiveOffsets[r + 1] = receiveOffsets[r] + receiveBytes[r];
    }
    std::vector<char> sendBuffer(static_cast<std::size_t>(sendOffsets[ranks]));
    for (int r = 0; r < ranks; ++r)
        if (sendBytes[r] > 0) std::memcpy(sendBuffer.data() + sendOffsets[r], outgoing[r].data(), sendBytes[r]);
    std::vector<char> receiveBuffer(static_cast<std::size_t>(receiveOffsets[ranks]));
    RBM_CHECK_PETSC(MPI_Alltoallv(sendBuffer.data(), sendBytes.data(), sendOffsets.data(), MPI_BYTE,
                                  receiveBuffer.data(), receiveBytes.data(), receiveOffsets.data(), MPI_BYTE,
                                  communicator));
    std::vector<std::vector<T>> incoming(ranks);
    for (int r = 0; r < ranks; ++r) {
        incoming[r].resize(receiveBytes[r] / sizeof(T));
        if (receiveBytes[r] > 0) std::memcpy(incoming[r].data(), receiveBuffer.data() + receiveOffsets[r], receiveBytes[r]);
    }
    return incoming;
}

} // namespace rbm::motion
