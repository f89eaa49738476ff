#include "rbmHostPatch.H"

#include "IStringStream.H"
#include "OStringStream.H"
#include "processorPolyPatch.H"

#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{

// The entries of a plain cyclic patch rbm reads (io/CyclicPatchEntries.hpp), from what the patch
// writes: neighbourPatch and the transform (`transform` in v1912, `transformType` in OpenFOAM
// 13) with, for a rotation, its axis and centre.
std::vector<std::pair<std::string, std::string>> cyclicEntries(const Foam::polyPatch& patch)
{
    Foam::OStringStream os;
    patch.write(os);
    Foam::IStringStream is(os.str());
    const Foam::dictionary dict(is);
    std::vector<std::pair<std::string, std::string>> entries;
    for (const char* keyword : {"neighbourPatch", "transform", "transformType"})
    {
        if (dict.found(keyword))
        {
            entries.emplace_back(keyword, Foam::word(dict.lookup(keyword)));
        }
    }
    for (const char* keyword : {"rotationAxis", "rotationCentre"})
    {
        if (dict.found(keyword))
        {
            const Foam::vector v(dict.lookup(keyword));
            std::ostringstream text;
            text << std::setprecision(17) << '(' << v.x() << ' ' << v.y() << ' ' << v.z() << ')';
            entries.emplace_back(keyword, text.str());
        }
    }
    return entries;
}

} // End anonymous namespace


Foam::label Foam::rbmRealPatchCount(const polyBoundaryMesh& patches)
{
    label nRealPatches = 0;
    forAll(patches, patchi)
    {
        if (isA<processorPolyPatch>(patches[patchi]))
        {
            if (!isType<processorPolyPatch>(patches[patchi]))
            {
                FatalErrorInFunction
                    << "rigidBodyMotionSolver: patch " << patches[patchi].name() << " is a "
                    << patches[patchi].type() << " patch; only plain processor patches are supported"
                    << " (a processorCyclic is a cyclic interface split between processors: keep each"
                    << " cyclic pair on one processor with preservePatches in decomposeParDict)."
                    << exit(FatalError);
            }
        }
        else
        {
            if (nRealPatches != patchi)
            {
                FatalErrorInFunction
                    << "rigidBodyMotionSolver: patch " << patches[patchi].name()
                    << " comes after a processor patch; expected processor patches last."
                    << exit(FatalError);
            }
            ++nRealPatches;
        }
    }
    return nRealPatches;
}


rbm::host::HostPatch Foam::rbmHostPatch(const polyPatch& patch)
{
    rbm::host::HostPatch hostPatch;
    hostPatch.name = patch.name();
    hostPatch.type = patch.type();
    if (hostPatch.type == "cyclic")
    {
        hostPatch.entries = cyclicEntries(patch);
    }
    else if (isA<processorPolyPatch>(patch))
    {
        const processorPolyPatch& pp = refCast<const processorPolyPatch>(patch);
        hostPatch.entries.emplace_back("myProcNo", std::to_string(pp.myProcNo()));
        hostPatch.entries.emplace_back("neighbProcNo", std::to_string(pp.neighbProcNo()));
    }
    for (const word& group : patch.inGroups())
    {
        hostPatch.groups.push_back(group);
    }
    return hostPatch;
}
