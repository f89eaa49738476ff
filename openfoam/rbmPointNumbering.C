#include "rbmPointNumbering.H"

#include "globalIndex.H"
#include "globalMeshData.H"

Foam::rbmPointNumbering Foam::rbmGlobalPointNumbering(const polyMesh& mesh)
{
    rbmPointNumbering numbering;
    const autoPtr<globalIndex> globalPoints =
        mesh.globalData().mergePoints(numbering.pointToGlobal, numbering.uniquePoints);
    numbering.nGlobalPoints = globalPoints().size();
    return numbering;
}
