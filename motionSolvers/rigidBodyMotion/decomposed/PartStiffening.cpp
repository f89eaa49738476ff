#include "PartStiffening.hpp"

#include "PetscSupport.hpp"
#include "Stiffening.hpp"

#include <mpi.h>

#include <vector>

namespace rbm::motion {

namespace {

// Every rank's triangle coordinates, in rank order, on every rank.
std::vector<double> gatheredOnAllRanks(const std::vector<double>& mine, MPI_Comm communicator)
{
    int ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(communicator, &ranks));
    const int count = static_cast<int>(mine.size());
    std::vector<int> counts(ranks), offsets(ranks, 0);
    RBM_CHECK_PETSC(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, communicator));
    for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    std::vector<double> all(static_cast<std::size_t>(offsets.back()) + static_cast<std::size_t>(counts.back()));
    RBM_CHECK_PETSC(MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                                   MPI_DOUBLE, communicator));
    return all;
}

} // namespace

EdgeStiffening::FactorSource partStiffeningFactors(const PolyMesh& localMesh, const MeshPart& part,
                                                   const CellNeighbourGraph& graph)
{
    return [&localMesh, &part, &graph](std::span<const Label> patches, double exponent) {
        const std::vector<double> triangles = gatheredOnAllRanks(
            patchTriangleCoordinates(localMesh, localMesh.points, patches), part.communicator());
        const NearestSurface surface = triangleSurface(triangles);
        double shortest = shortestGraphEdge(graph, part.nodePoints(), 3);
        RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &shortest, 1, MPI_DOUBLE, MPI_MIN, part.communicator()));
        return stiffeningFactors(graph, part.nodePoints(), 3, surface, exponent, shortest);
    };
}

} // namespace rbm::motion
