#include "rbmGlobalMesh.H"

#include "PstreamBuffers.H"
#include "globalIndex.H"
#include "processorPolyPatch.H"
#include "rbmHostPatch.H"
#include "rbmOpenFOAMVersion.H"
#include "rbmPointNumbering.H"

namespace
{

// Gathers one list per processor onto every processor.
template<class ListType>
Foam::List<ListType> allGather(const ListType& mine)
{
    Foam::List<ListType> all(Foam::Pstream::nProcs());
    all[Foam::Pstream::myProcNo()] = mine;
    Foam::Pstream::gatherList(all);
    Foam::Pstream::scatterList(all);
    return all;
}

void appendFace(Foam::DynamicList<Foam::label>& list, const Foam::face& f, const Foam::labelList& pointToGlobal)
{
    list.append(f.size());
    for (const Foam::label p : f)
    {
        list.append(pointToGlobal[p]);
    }
}

void appendHostFace(rbm::host::HostMesh& host, const Foam::labelList& encoded, Foam::label& i)
{
    const Foam::label n = encoded[i++];
    for (Foam::label k = 0; k < n; ++k)
    {
        host.faceVertices.push_back(static_cast<int>(encoded[i++]));
    }
    host.faceOffsets.push_back(static_cast<int>(host.faceVertices.size()));
}

} // End anonymous namespace


Foam::rbmGlobalMesh::rbmGlobalMesh(const polyMesh& mesh, const pointField& points0)
:
    nRealPatches_(0)
{
    const polyBoundaryMesh& patches = mesh.boundaryMesh();
    nRealPatches_ = rbmRealPatchCount(patches);

    // Points: OpenFOAM's global numbering, each shared point once.
    rbmPointNumbering numbering = rbmGlobalPointNumbering(mesh);
    pointToGlobal_.transfer(numbering.pointToGlobal);
    const List<pointField> allPoints(allGather(pointField(points0, numbering.uniquePoints)));
    globalPoints_.setSize(numbering.nGlobalPoints);
    label next = 0;
    for (const pointField& part : allPoints)
    {
        for (const point& p : part)
        {
            globalPoints_[next++] = p;
        }
    }
    if (next != globalPoints_.size())
    {
        FatalErrorInFunction
            << "rigidBodyMotionSolver: gathered " << next << " points for a global numbering of "
            << globalPoints_.size() << exit(FatalError);
    }
    forAll(points0, pointi)
    {
        if (mag(globalPoints_[pointToGlobal_[pointi]] - points0[pointi]) > SMALL*(1 + mag(points0[pointi])))
        {
            FatalErrorInFunction
                << "rigidBodyMotionSolver: local point " << pointi << " at " << points0[pointi]
                << " is global point " << pointToGlobal_[pointi] << " at "
                << globalPoints_[pointToGlobal_[pointi]] << ": the global numbering is inconsistent."
                << exit(FatalError);
        }
    }

    // Cells, and the global cell across every processor-patch face.
    const globalIndex globalCells(mesh.nCells());
    List<labelList> neighbourCells(patches.size());
    if (Pstream::parRun())
    {
        PstreamBuffers buffers(Pstream::commsTypes::nonBlocking);
        for (label patchi = nRealPatches_; patchi < patches.size(); ++patchi)
        {
            const processorPolyPatch& pp = refCast<const processorPolyPatch>(patches[patchi]);
            labelList cells(pp.faceCells());
            for (label& c : cells)
            {
                c = globalCells.toGlobal(c);
            }
            UOPstream toNeighbour(pp.neighbProcNo(), buffers);
            toNeighbour << cells;
        }
        buffers.finishedSends();
        for (label patchi = nRealPatches_; patchi < patches.size(); ++patchi)
        {
            const processorPolyPatch& pp = refCast<const processorPolyPatch>(patches[patchi]);
            UIPstream fromNeighbour(pp.neighbProcNo(), buffers);
            fromNeighbour >> neighbourCells[patchi];
        }
    }

    // This processor's faces, encoded (owner, [neighbour,] size, global points ...).
    const faceList& faces = mesh.faces();
    const labelList& owner = mesh.faceOwner();
    const labelList& neighbour = mesh.faceNeighbour();
    DynamicList<label> internal;
    for (label facei = 0; facei < mesh.nInternalFaces(); ++facei)
    {
        internal.append(globalCells.toGlobal(owner[facei]));
        internal.append(globalCells.toGlobal(neighbour[facei]));
        appendFace(internal, faces[facei], pointToGlobal_);
    }
    for (label patchi = nRealPatches_; patchi < patches.size(); ++patchi)
    {
        const processorPolyPatch& pp = refCast<const processorPolyPatch>(patches[patchi]);
        if (!pp.owner())
        {
            continue;
        }
        forAll(pp, i)
        {
            const label facei = pp.start() + i;
            internal.append(globalCells.toGlobal(owner[facei]));
            internal.append(neighbourCells[patchi][i]);
            appendFace(internal, faces[facei], pointToGlobal_);
        }
    }
    const List<labelList> allInternal(allGather(labelList(internal)));

    for (const labelList& part : allInternal)
    {
        for (label i = 0; i < part.size(); )
        {
            host_.owner.push_back(static_cast<int>(part[i++]));
            host_.neighbour.push_back(static_cast<int>(part[i++]));
            appendHostFace(host_, part, i);
        }
    }
    for (label patchi = 0; patchi < nRealPatches_; ++patchi)
    {
        const polyPatch& pp = patches[patchi];
        DynamicList<label> boundary;
        forAll(pp, i)
        {
            const label facei = pp.start() + i;
            boundary.append(globalCells.toGlobal(owner[facei]));
            appendFace(boundary, faces[facei], pointToGlobal_);
        }
        rbm::host::HostPatch hostPatch = rbmHostPatch(pp);
        hostPatch.startFace = static_cast<int>(host_.owner.size());
        for (const labelList& part : allGather(labelList(boundary)))
        {
            for (label i = 0; i < part.size(); )
            {
                host_.owner.push_back(static_cast<int>(part[i++]));
                appendHostFace(host_, part, i);
            }
        }
        hostPatch.faceCount = static_cast<int>(host_.owner.size()) - hostPatch.startFace;
        host_.patches.push_back(hostPatch);
    }

    host_.points.reserve(3*globalPoints_.size());
    for (const point& p : globalPoints_)
    {
        host_.points.push_back(p.x());
        host_.points.push_back(p.y());
        host_.points.push_back(p.z());
    }
}


Foam::label Foam::rbmGlobalMesh::patchStart(label patchi) const
{
    return host_.patches[patchi].startFace;
}


Foam::label Foam::rbmGlobalMesh::patchEnd(label patchi) const
{
    return host_.patches[patchi].startFace + host_.patches[patchi].faceCount;
}


Foam::label Foam::rbmGlobalMesh::patchPointCount(label patchi) const
{
    labelHashSet seen;
    for (label f = patchStart(patchi); f < patchEnd(patchi); ++f)
    {
        for (int k = host_.faceOffsets[f]; k < host_.faceOffsets[f + 1]; ++k)
        {
            seen.insert(host_.faceVertices[k]);
        }
    }
    return seen.size();
}


std::vector<double> Foam::rbmGlobalMesh::pointNormals(label patchi) const
{
    // Patch points in order of first appearance; the sum of the unit normals around each.
    Map<label> local;
    DynamicList<vector> sums;
    for (label f = patchStart(patchi); f < patchEnd(patchi); ++f)
    {
        face faceOfPoints(host_.faceOffsets[f + 1] - host_.faceOffsets[f]);
        forAll(faceOfPoints, k)
        {
            faceOfPoints[k] = host_.faceVertices[host_.faceOffsets[f] + k];
        }
        const vector n = rbmOpenFOAM::unitNormal(faceOfPoints, globalPoints_);
        for (const label p : faceOfPoints)
        {
            auto iter = local.find(p);
            if (iter == local.end())
            {
                local.insert(p, sums.size());
                sums.append(n);
            }
            else
            {
                sums[*iter] += n;
            }
        }
    }
    std::vector<double> normals;
    normals.reserve(3*sums.size());
    for (vector n : sums)
    {
        n = normalised(n);
        normals.push_back(n.x());
        normals.push_back(n.y());
        normals.push_back(n.z());
    }
    return normals;
}


Foam::vector Foam::rbmGlobalMesh::planeNormal(label patchi) const
{
    vector sum(Zero);
    for (label f = patchStart(patchi); f < patchEnd(patchi); ++f)
    {
        face faceOfPoints(host_.faceOffsets[f + 1] - host_.faceOffsets[f]);
        forAll(faceOfPoints, k)
        {
            faceOfPoints[k] = host_.faceVertices[host_.faceOffsets[f] + k];
        }
        sum += rbmOpenFOAM::unitNormal(faceOfPoints, globalPoints_);
    }
    return normalised(sum);
}


void Foam::rbmGlobalMesh::gather
(
    const vectorField& local,
    const boolList& flagged,
    std::vector<double>& global
) const
{
    global.assign(3*globalPoints_.size(), 0.0);
    if (!Pstream::parRun())
    {
        forAll(local, pointi)
        {
            if (flagged[pointi])
            {
                const label g = pointToGlobal_[pointi];
                global[3*g] = local[pointi].x();
                global[3*g + 1] = local[pointi].y();
                global[3*g + 2] = local[pointi].z();
            }
        }
        return;
    }
    DynamicList<label> ids;
    DynamicList<vector> values;
    forAll(local, pointi)
    {
        if (flagged[pointi])
        {
            ids.append(pointToGlobal_[pointi]);
            values.append(local[pointi]);
        }
    }
    const List<labelList> allIds(allGather(labelList(ids)));
    const List<vectorField> allValues(allGather(vectorField(values)));
    forAll(allIds, proci)
    {
        forAll(allIds[proci], i)
        {
            const label g = allIds[proci][i];
            global[3*g] = allValues[proci][i].x();
            global[3*g + 1] = allValues[proci][i].y();
            global[3*g + 2] = allValues[proci][i].z();
        }
    }
}


void Foam::rbmGlobalMesh::scatter(const std::vector<double>& global, vectorField& local) const
{
    forAll(local, pointi)
    {
        const label g = pointToGlobal_[pointi];
        local[pointi] = vector(global[3*g], global[3*g + 1], global[3*g + 2]);
    }
}
