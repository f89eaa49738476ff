// exchangeWithAllRanks (RankExchange.hpp) under mpiexec with 1–4 ranks: every rank sends every
// rank a list it can predict (its values and lengths a formula of both ranks), so each rank
// checks what it received without a reference exchange; in one round, and in rounds of a few
// bytes that split the values themselves (the path lists of more than 2 GiB take).

#include "PetscTestEnvironment.hpp"

#include "RankExchange.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstddef>
#include <vector>

namespace {

struct Pair {
    double value;
    int sender;
};

int rankOf(MPI_Comm communicator)
{
    int rank = 0;
    MPI_Comm_rank(communicator, &rank);
    return rank;
}

int sizeOf(MPI_Comm communicator)
{
    int size = 1;
    MPI_Comm_size(communicator, &size);
    return size;
}

// What rank `from` sends rank `to`: (from + 2 to) % 5 + from values (some lists empty).
std::vector<Pair> listFor(int from, int to)
{
    std::vector<Pair> list;
    const int length = (from + 2 * to) % 5 + from;
    for (int i = 0; i < length; ++i) list.push_back({1000.0 * from + 10.0 * to + i + 0.25, from});
    return list;
}

void exchangeAndCheck(std::size_t roundBytes)
{
    const int rank = rankOf(MPI_COMM_WORLD);
    const int ranks = sizeOf(MPI_COMM_WORLD);
    std::vector<std::vector<Pair>> outgoing(ranks);
    for (int to = 0; to < ranks; ++to) outgoing[to] = listFor(rank, to);
    const auto incoming = rbm::motion::exchangeWithAllRanks(MPI_COMM_WORLD, outgoing, roundBytes);
    ASSERT_EQ(static_cast<int>(incoming.size()), ranks);
    for (int from = 0; from < ranks; ++from) {
        const std::vector<Pair> expected = listFor(from, rank);
        ASSERT_EQ(incoming[from].size(), expected.size()) << "from rank " << from << ", rounds of " << roundBytes;
        for (std::size_t i = 0; i < expected.size(); ++i) {
            EXPECT_EQ(incoming[from][i].value, expected[i].value);
            EXPECT_EQ(incoming[from][i].sender, from);
        }
    }
}

TEST(RankExchange, ListsArriveWholeInOneRound) { exchangeAndCheck(0); }

TEST(RankExchange, ListsArriveWholeInRoundsThatSplitTheirValues)
{
    // 3 and 7 bytes a round: a 16-byte Pair crosses rounds; the longest list, 8 Pairs, takes
    // 43 and 19 rounds, and every rank takes part in all of them.
    exchangeAndCheck(3);
    exchangeAndCheck(7);
}

TEST(RankExchange, AListPerRankIsRequired)
{
    std::vector<std::vector<int>> tooMany(sizeOf(MPI_COMM_WORLD) + 1);
    EXPECT_THROW(rbm::motion::exchangeWithAllRanks(MPI_COMM_WORLD, tooMany), std::invalid_argument);
}

} // namespace
