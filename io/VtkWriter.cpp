#include "VtkWriter.hpp"

#include "CellShape.hpp"
#include "vtk/VtuBytes.hpp"
#include "WholeFile.hpp"


#include <dlfcn.h>

#include <algorithm>
#include <iomanip>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace rbm::io {

namespace fs = std::filesystem;

VtkCells vtkCellsOf(const PolyMesh& mesh, const MeshTopology& topology)
{
    VtkCells cells;
    const Label cellCount = topology.cellCount;
    cells.types.reserve(static_cast<std::size_t>(cellCount));
    cells.offsets.reserve(static_cast<std::size_t>(cellCount) + 1);
    cells.faceStreamOffsets.reserve(static_cast<std::size_t>(cellCount) + 1);
    cells.connectivity.reserve(topology.cellPoints.size());
    for (Label c = 0; c < cellCount; ++c) {
        cells.types.push_back(static_cast<std::uint8_t>(appendVtkCell(mesh, topology, c, cells.connectivity, cells.faceStream)));
        cells.offsets.push_back(static_cast<Label>(cells.connectivity.size()));
        cells.faceStreamOffsets.push_back(static_cast<Label>(cells.faceStream.size()));
    }
    return cells;
}

namespace {

// The VTK module, opened at the first .vtu (VtuBytes.hpp). RBM_VTK_MODULE is its path in the
// build tree; beside it, <program folder>/../lib/librbm_vtk.so is tried.
using VtuBytesFunction = bool (*)(VtuRequest*);

VtuBytesFunction loadVtkModule()
{
    static const VtuBytesFunction function = []() -> VtuBytesFunction {
        std::vector<std::string> candidates;
#ifdef RBM_VTK_MODULE
        candidates.emplace_back(RBM_VTK_MODULE);
#endif
        std::error_code error;
        const fs::path self = fs::read_symlink("/proc/self/exe", error);
        if (!error) candidates.push_back((self.parent_path() / ".." / "lib" / "librbm_vtk.so").string());
        std::string reasons;
        for (const std::string& candidate : candidates) {
            if (void* module = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL)) {
                if (void* symbol = dlsym(module, "rbmVtuBytes")) return reinterpret_cast<VtuBytesFunction>(symbol);
            }
            const char* reason = dlerror();
            reasons += (reasons.empty() ? "" : "; ") + std::string(reason ? reason : candidate + ": no rbmVtuBytes");
        }
        throw std::runtime_error("cannot load rbm's VTK writer librbm_vtk.so (" +
                                 (reasons.empty() ? std::string("no candidate") : reasons) + ")");
    }();
    return function;
}

} // namespace

void writeVtu(const fs::path& file, const std::vector<Vector3>& points, const VtkCells& cells,
              const std::vector<VtkField>& pointFields, const std::vector<VtkField>& cellFields)
{
    // VTK writes into memory, and the bytes go to the file through replaceFileAtomically:
    // a temporary file renamed over the old one, so a reader never sees half a file, a failure
    // (a full disk) leaves the old file and no temporary, and the message names the file and
    // the OS reason.
    VtuRequest request;
    request.points = &points;
    request.cells = &cells;
    request.pointFields = &pointFields;
    request.cellFields = &cellFields;
    if (!loadVtkModule()(&request)) throw std::runtime_error("VTK could not write " + file.string() + ": " + request.error);
    replaceFileAtomically(file, request.bytes);
}

PvdCollection::PvdCollection(fs::path file) : file_(std::move(file)) {}

void PvdCollection::load()
{
    entries_.clear();
    // A missing file is an empty collection; a file that cannot be read is an error (taking
    // it for empty would drop its entries at the next write()).
    std::error_code error;
    if (!fs::exists(fs::symlink_status(file_, error))) return;
    const std::string text = readWholeFile(file_);
    const std::regex dataSet(R"re(<DataSet[^>]*timestep="([^"]*)"[^>]*file="([^"]*)")re");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), dataSet); it != std::sregex_iterator(); ++it) {
        add(std::stod((*it)[1].str()), (*it)[2].str());
    }
}

void PvdCollection::add(double time, const std::string& dataset)
{
    auto sameTime = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.time == time; });
    if (sameTime != entries_.end()) {
        sameTime->dataset = dataset;
        return;
    }
    entries_.push_back({time, dataset});
    std::stable_sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
}

void PvdCollection::write() const
{
    std::ostringstream xml;
    xml << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    xml << std::setprecision(17);
    for (const Entry& e : entries_) {
        xml << "    <DataSet timestep=\"" << e.time << "\" group=\"\" part=\"0\" file=\"" << e.dataset << "\"/>\n";
    }
    xml << "  </Collection>\n</VTKFile>\n";

    replaceFileAtomically(file_, xml.str());
}

} // namespace rbm::io
