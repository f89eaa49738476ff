#pragma once
// ParaView output through the VTK library: one .vtu (XML unstructured grid) per written
// time, and a .pvd collection that lists them with their times so ParaView plays the series.
// VTK 9.1 has no .pvd writer; that small XML file is written here.

#include "MeshTopology.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::io {

// Cells in VTK's terms. Cell c has VTK type types[c] (VTK_TETRA, VTK_HEXAHEDRON, VTK_POLYGON,
// VTK_POLYHEDRON, ...) and points connectivity[offsets[c] .. offsets[c+1]) in VTK's order.
// Polyhedra additionally carry their faces as a VTK face stream
// (nFaces, n0, p.., n1, p.., ...) in faceStream[faceStreamOffsets[c] .. faceStreamOffsets[c+1]);
// other cells have an empty range there.
struct VtkCells {
    std::vector<std::uint8_t> types;
    std::vector<Label> offsets{0};
    std::vector<Label> connectivity;
    std::vector<Label> faceStreamOffsets{0};
    std::vector<Label> faceStream;

    Label cellCount() const { return static_cast<Label>(types.size()); }
};

// The cells of a polyhedral mesh in VTK's terms: tetrahedra, pyramids, prisms and hexahedra
// as VTK's standard cells, everything else as VTK_POLYHEDRON with its outward faces.
VtkCells vtkCellsOf(const PolyMesh& mesh, const MeshTopology& topology);

// A named field with `components` values per point or per cell (1 = scalar, 3 = vector).
struct VtkField {
    std::string name;
    int components = 1;
    std::vector<double> values;
};

// Writes an XML .vtu file (binary appended, zlib-compressed) atomically: VTK writes into
// memory, the file is replaced through a temporary file and a rename (WholeFile.hpp), so an
// existing file stays whole and no temporary is left when writing fails. Throws
// std::runtime_error naming the file and the reason (the OS's, or VTK's messages on one line:
// VTK prints nothing itself). Field lengths must match the point / cell counts.
void writeVtu(const std::filesystem::path& file, const std::vector<Vector3>& points, const VtkCells& cells,
              const std::vector<VtkField>& pointFields, const std::vector<VtkField>& cellFields);

// The .pvd collection of a time series. Entries are kept sorted by time; writing replaces
// the file atomically (temporary file + rename), so ParaView never sees half a file and a
// failed write (a full disk) leaves the previous file.
class PvdCollection {
public:
    explicit PvdCollection(std::filesystem::path file);

    // Reads the entries of an existing .pvd so a restarted run appends to it; a missing
    // file gives an empty collection, one that cannot be read an rbm::InputError.
    void load();
    // Adds (or replaces) the dataset of a time; `dataset` is relative to the .pvd's folder.
    void add(double time, const std::string& dataset);
    // Replaces the file atomically; throws std::runtime_error naming it and the OS reason
    // (the old file is then left as it was).
    void write() const;
    std::size_t size() const { return entries_.size(); }

private:
    struct Entry {
        double time;
        std::string dataset;
    };
    std::filesystem::path file_;
    std::vector<Entry> entries_;
};

} // namespace rbm::io
