#include "CyclicPatchEntries.hpp"

#include "FoamDictionary.hpp"
#include "InputError.hpp"

namespace rbm::io {

namespace {

CyclicTransformKind transformKind(const std::string& word, const Patch& patch, const std::string& file)
{
    if (word == "translational" || word == "coincidentFullMatch" || word == "none")
        return CyclicTransformKind::translational;
    if (word == "rotational") return CyclicTransformKind::rotational;
    if (word == "unknown" || word == "unspecified" || word == "noOrdering") return CyclicTransformKind::unspecified;
    throw InputError(file, 0,
                     "cyclic patch '" + patch.name + "': unknown transform " + word +
                         ". Valid transforms are: translational rotational coincidentFullMatch none unknown "
                         "unspecified noOrdering");
}

CyclicPatchSpec readSpec(const PolyMesh& mesh, Label patchIndex, const std::string& file)
{
    const Patch& patch = mesh.patches[patchIndex];
    // The entries as one dictionary text, parsed by the same reader as every other file.
    std::string text;
    for (const auto& [keyword, value] : patch.otherEntries) text += keyword + " " + value + ";\n";
    CyclicPatchSpec spec;
    spec.patch = patchIndex;
    try {
        const Dictionary entries = Dictionary::parseText(text, file);
        if (!entries.contains("neighbourPatch"))
            throw InputError(file, 0, "cyclic patch '" + patch.name + "' has no neighbourPatch entry");
        spec.neighbourPatch = entries.get<std::string>("neighbourPatch");
        const char* transformKeyword = entries.contains("transformType") ? "transformType" : "transform";
        if (entries.contains(transformKeyword))
            spec.transform = transformKind(entries.get<std::string>(transformKeyword), patch, file);
        if (spec.transform != CyclicTransformKind::rotational) return spec;
        for (const char* keyword : {"rotationAxis", "rotationCentre"})
            if (!entries.contains(keyword))
                throw InputError(file, 0,
                                 "cyclic patch '" + patch.name + "' has transform rotational but no " + keyword +
                                     " entry");
        spec.rotationAxis = entries.get<Vector3>("rotationAxis");
        spec.rotationCentre = entries.get<Vector3>("rotationCentre");
    } catch (const InputError& error) {
        if (error.line() == 0) throw;  // this function's own
        // The parser's message (a word where a vector was expected, ...): its line is the line
        // within this patch's entries, not the file's, so the patch is named instead.
        throw InputError(file, 0, "cyclic patch '" + patch.name + "': " + error.message());
    }
    return spec;
}

} // namespace

std::vector<CyclicPatchSpec> readCyclicPatchSpecs(const PolyMesh& mesh, const std::string& file)
{
    std::vector<CyclicPatchSpec> specs;
    for (Label p = 0; p < static_cast<Label>(mesh.patches.size()); ++p)
        if (mesh.patches[p].type == "cyclic") specs.push_back(readSpec(mesh, p, file));
    return specs;
}

} // namespace rbm::io
