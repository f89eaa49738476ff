#include "DecomposedCase.hpp"

#include "InputError.hpp"
#include "PolyMeshReader.hpp"

#include <set>
#include <string>
#include <system_error>

namespace fs = std::filesystem;

namespace rbm::io {

namespace {

// N of a folder named processorN (N decimal, no sign), else −1.
int processorNumber(const std::string& name)
{
    const std::string prefix = "processor";
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
    int number = 0;
    for (std::size_t k = prefix.size(); k < name.size(); ++k) {
        if (name[k] < '0' || name[k] > '9' || number > 1000000) return -1;
        number = 10 * number + (name[k] - '0');
    }
    return number;
}

// The value of entry `keyword` of a patch ("" when absent).
std::string entryOf(const Patch& patch, const std::string& keyword)
{
    for (const auto& [key, value] : patch.otherEntries)
        if (key == keyword) return value;
    return {};
}

} // namespace

int countProcessorFolders(const fs::path& caseDir)
{
    std::set<int> numbers;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(caseDir, error)) {
        const int number = processorNumber(entry.path().filename().string());
        if (number >= 0 && entry.is_directory(error)) numbers.insert(number);
    }
    if (numbers.empty()) return 0;
    const int count = static_cast<int>(numbers.size());
    if (*numbers.rbegin() != count - 1)
        throw InputError(caseDir.string(), 0, "processor folders are not numbered 0 to " + std::to_string(count - 1) +
                                                  " without a gap (found " + std::to_string(count) +
                                                  ", the largest processor" + std::to_string(*numbers.rbegin()) + ")");
    return count;
}

ProcessorMesh readProcessorMesh(const fs::path& caseDir, int processor)
{
    const fs::path polyMeshDir = caseDir / ("processor" + std::to_string(processor)) / "constant" / "polyMesh";
    ProcessorMesh part;
    part.mesh = readPolyMesh(polyMeshDir);
    const fs::path addressing = polyMeshDir / "pointProcAddressing";
    part.pointProcAddressing = readLabelListFile(addressing, "point label", part.mesh.points.size());
    if (part.pointProcAddressing.size() != part.mesh.points.size())
        throw InputError(addressing.string(), 0,
                         "has " + std::to_string(part.pointProcAddressing.size()) + " labels but the mesh has " +
                             std::to_string(part.mesh.points.size()) + " points (expected one label per point)");
    for (std::size_t p = 0; p < part.pointProcAddressing.size(); ++p)
        if (part.pointProcAddressing[p] < 0)
            throw InputError(addressing.string(), 0, "label " + std::to_string(part.pointProcAddressing[p]) + " of point " +
                                                         std::to_string(p) + " is negative");
    for (const Patch& patch : part.mesh.patches)
        if (patch.type == "processor" && entryOf(patch, "myProcNo") != std::to_string(processor))
            throw InputError((polyMeshDir / "boundary").string(), 0,
                             "processor patch " + patch.name + " has myProcNo '" + entryOf(patch, "myProcNo") +
                                 "' but lies in processor" + std::to_string(processor));
    return part;
}

} // namespace rbm::io
