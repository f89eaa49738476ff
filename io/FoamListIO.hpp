#pragma once
// Fast reading and writing of the big lists in OpenFOAM mesh files (points, faces, owner,
// neighbour): millions of entries, so no tokenizer and no per-entry allocation. Numbers are
// parsed in place with std::from_chars and written with std::to_chars.
//
// List forms read (OpenFOAM v1912 UList/List I/O):
//   ascii:   N ( a b c ... )      N { a }  (uniform)      ( a b c ... )  (count not given)
//   binary:  N ( <N * sizeof(T) raw little-endian bytes> )   and a bare `0` for an empty list
// The sizes of binary labels and scalars come from the header's arch ("label=32|64",
// "scalar=32|64"). Vectors are `( x y z )` in ascii and 3 consecutive scalars in binary.
// A faceList is a list of label lists (`4(0 1 2 3)`), in binary each face a binary label
// list; a faceCompactList is two lists: N+1 offsets, then all point labels.
//
// Every error is an rbm::InputError naming the file, the line (counted only when an error is
// raised) and what was expected.

#include "FoamDictionary.hpp"
#include "InputError.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::io {

class TextFileWriter;   // TextFileWriter.hpp

// A cursor over the body of one file (the text after its FoamFile header).
class FoamListReader {
public:
    // `text`: the whole file content (line numbers are counted from its start); reading
    // begins at `offset`. `header` gives ascii/binary and the binary label and scalar sizes.
    FoamListReader(std::string_view text, std::size_t offset, std::string fileName, const FoamFileHeader& header);

    // `what` names one element in messages ("point", "owner label", ...). `maxCount` bounds
    // the count of a uniform list `N{value}`, whose text does not bound it; counts of other
    // lists are bounded by the bytes left in the file before anything is allocated.
    std::vector<Label> readLabelList(std::string_view what, std::size_t maxCount);
    std::vector<double> readScalarList(std::string_view what, std::size_t maxCount);
    std::vector<Vector3> readVectorList(std::string_view what, std::size_t maxCount);
    // 0/1 (also true/false, yes/no, on/off in ascii); one byte each in binary.
    std::vector<bool> readBoolList(std::string_view what, std::size_t maxCount);

    // A faceList: faces are appended to `faceOffsets` (which must hold at least its leading 0)
    // and `facePoints`, PolyMesh's compact form. Faces with fewer than 3 points are an error.
    void readFaceList(std::vector<Label>& faceOffsets, std::vector<Label>& facePoints);
    // A faceCompactList (offsets list, then point-label list), checked for consistency:
    // offsets start at 0, grow by at least 3 per face, and end at the number of labels.
    void readFaceCompactList(std::vector<Label>& faceOffsets, std::vector<Label>& facePoints);

    // Only whitespace and comments may remain (the trailing `// ****` line is a comment).
    void expectEnd();

    bool binary() const { return binary_; }
    std::size_t position() const { return position_; }
    const std::string& fileName() const { return fileName_; }
    // 1-based line of a byte offset in the text.
    int lineAt(std::size_t offset) const;
    [[noreturn]] void failAt(std::size_t offset, const std::string& message) const;

private:
    enum class ListStart { Counted, Uniform, Uncounted, EmptyBinary };
    struct ListHead {
        ListStart kind;
        std::size_t count;
    };

    // Skips whitespace and comments; inline fast path for the common "nothing to skip".
    void skipSpace()
    {
        if (position_ < text_.size()) {
            const auto c = static_cast<unsigned char>(text_[position_]);
            if (c > ' ' && c != '/') return;
        }
        skipSpaceAndComments();
    }
    void skipSpaceAndComments();
    bool atEnd() const { return position_ >= text_.size(); }
    void expectChar(char c, std::string_view context);
    ListHead readListHead(std::string_view what, std::size_t elementBytes, std::size_t minimumAsciiBytes,
                          std::size_t maxCount);
    void expectListEnd(std::string_view what, std::size_t count, std::size_t read);
    [[noreturn]] void failShortList(std::string_view what, std::size_t count, std::size_t read) const;
    std::int64_t readInteger(std::string_view what);
    Label readAsciiLabel(std::string_view what);
    double readAsciiScalar(std::string_view what);
    Vector3 readAsciiVector(std::string_view what);
    bool readAsciiBool(std::string_view what);
    const char* takeBinary(std::size_t bytes, std::string_view what, std::size_t count);
    Label binaryLabel(const char* bytes, std::string_view what) const;
    double binaryScalar(const char* bytes) const;
    void checkFace(std::size_t face, Label pointCount, std::size_t offset) const;
    // The text at an offset, quoted for messages ("end of file" at the end).
    std::string describeAt(std::size_t offset) const;

    std::string_view text_;
    std::size_t position_;
    std::string fileName_;
    bool binary_;
    int labelBytes_;
    int scalarBytes_;
};

// ---- Writing -------------------------------------------------------------------------------

// How OpenFOAM files are written (controlDict writeFormat, writePrecision, writeCompression).
struct FoamWriteOptions {
    bool binary = false;
    int precision = 6;          // significant digits of ascii scalars (OpenFOAM's writePrecision)
    bool compressed = false;    // gzip, file name gets ".gz"
    // Points are written with at least this many digits, as OpenFOAM's mesh generators and
    // manipulators do (IOstream::defaultPrecision(max(10u, ...))): with 6 digits the thin cells
    // of a boundary layer collapse. Set 0 to honour `precision` literally.
    int minimumPointPrecision = 10;
};

// Banner comment, FoamFile dictionary and the `// * * *` rule, as OpenFOAM v1912 writes
// them. `arch "LSB;label=32;scalar=64"` is always written; `note` only when not empty.
std::string foamFileHeaderText(bool binary, std::string_view className, std::string_view location,
                               std::string_view object, std::string_view note = {});
// The closing `// ****` line, preceded by the blank lines OpenFOAM puts there.
std::string foamFileFooterText();

// Appends a scalar in OpenFOAM's ascii form: `precision` significant digits, shortest of fixed
// and exponent notation (C++ streams' default float format, printf %g).
void appendScalar(std::string& out, double value, int precision);
void appendLabel(std::string& out, std::int64_t value);

// Appends a whole list the way OpenFOAM writes it: "\nN\n(\n" one entry a line ")\n" in ascii,
// "\nN\n(" raw bytes ")" in binary (labels 32-bit, scalars 64-bit).
void appendLabelList(std::string& out, std::span<const Label> values, bool binary);
void appendVectorList(std::string& out, std::span<const Vector3> values, bool binary, int precision);
// The same text streamed through `out` (TextFileWriter.hpp), a piece at a time: for lists of
// a whole mesh's points, whose text would otherwise be held whole (tens of MB).
void appendVectorList(TextFileWriter& out, std::span<const Vector3> values, bool binary, int precision);
void appendScalarList(std::string& out, std::span<const double> values, bool binary, int precision);
void appendBoolList(std::string& out, const std::vector<bool>& values, bool binary);
// ascii faceList: one `n(p0 p1 ...)` a line.
void appendFaceList(std::string& out, std::span<const Label> faceOffsets, std::span<const Label> facePoints);
// faceCompactList: the offsets list, then the point-label list.
void appendFaceCompactList(std::string& out, std::span<const Label> faceOffsets, std::span<const Label> facePoints,
                           bool binary);

} // namespace rbm::io
