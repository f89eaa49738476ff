#include "FoamListIO.hpp"

#include "TextFileWriter.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace rbm::io {

namespace {

constexpr std::int64_t largestLabel = std::numeric_limits<Label>::max();
constexpr std::int64_t smallestLabel = std::numeric_limits<Label>::min();

inline bool isSpace(char c)
{
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

// Characters that may follow a number: anything else (".", letters) means the token is not
// the number we expected, e.g. "1.5" where a label is due.
inline bool endsNumber(char c)
{
    return isSpace(c) || c == '(' || c == ')' || c == '{' || c == '}' || c == ';' || c == '/';
}

std::string plural(std::string_view what)
{
    return std::string(what) + "s";
}

} // namespace

FoamListReader::FoamListReader(std::string_view text, std::size_t offset, std::string fileName,
                               const FoamFileHeader& header)
    : text_(text), position_(offset), fileName_(std::move(fileName)), binary_(header.isBinary()),
      labelBytes_(header.labelBytes), scalarBytes_(header.scalarBytes)
{
    if (binary_ && labelBytes_ != 4 && labelBytes_ != 8)
        failAt(position_, "unsupported label size of " + std::to_string(8 * labelBytes_) +
                              " bits in the header's arch (expected label=32 or label=64)");
    if (binary_ && scalarBytes_ != 4 && scalarBytes_ != 8)
        failAt(position_, "unsupported scalar size of " + std::to_string(8 * scalarBytes_) +
                              " bits in the header's arch (expected scalar=32 or scalar=64)");
}

int FoamListReader::lineAt(std::size_t offset) const
{
    offset = std::min(offset, text_.size());
    return 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

void FoamListReader::failAt(std::size_t offset, const std::string& message) const
{
    throw InputError(fileName_, lineAt(offset), message);
}

std::string FoamListReader::describeAt(std::size_t offset) const
{
    if (offset >= text_.size()) return "end of file";
    std::size_t end = offset;
    while (end < text_.size() && end - offset < 24 && !isSpace(text_[end])) ++end;
    if (end == offset) end = offset + 1;
    const std::string_view word = text_.substr(offset, end - offset);
    for (char c : word) {
        if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) return "binary data";
    }
    return "'" + std::string(word) + "'";
}

void FoamListReader::skipSpaceAndComments()
{
    const std::size_t size = text_.size();
    while (position_ < size) {
        const char c = text_[position_];
        if (isSpace(c)) {
            ++position_;
        } else if (c == '/' && position_ + 1 < size && text_[position_ + 1] == '/') {
            const std::size_t newline = text_.find('\n', position_);
            position_ = newline == std::string_view::npos ? size : newline + 1;
        } else if (c == '/' && position_ + 1 < size && text_[position_ + 1] == '*') {
            const std::size_t close = text_.find("*/", position_ + 2);
            if (close == std::string_view::npos) failAt(position_, "comment opened with '/*' is never closed");
            position_ = close + 2;
        } else {
            return;
        }
    }
}

void FoamListReader::expectChar(char c, std::string_view context)
{
    skipSpace();
    if (atEnd() || text_[position_] != c)
        failAt(position_, "expected '" + std::string(1, c) + "' " + std::string(context) + " but found " +
                              describeAt(position_));
    ++position_;
}

std::int64_t FoamListReader::readInteger(std::string_view what)
{
    skipSpace();
    const char* begin = text_.data() + position_;
    const char* end = text_.data() + text_.size();
    std::int64_t value = 0;
    const auto [stop, error] = std::from_chars(begin, end, value);
    if (error == std::errc::result_out_of_range)
        failAt(position_, "expected " + std::string(what) + " but found " + describeAt(position_) + ", which is too large");
    if (error != std::errc() || (stop != end && !endsNumber(*stop)))
        failAt(position_, "expected " + std::string(what) + " (an integer) but found " + describeAt(position_));
    position_ += static_cast<std::size_t>(stop - begin);
    return value;
}

Label FoamListReader::readAsciiLabel(std::string_view what)
{
    skipSpace();
    // Fast path for what mesh files hold: up to 9 decimal digits (always fits 32 bits).
    const char* begin = text_.data() + position_;
    const char* end = text_.data() + text_.size();
    const char* digit = begin;
    std::uint32_t fast = 0;
    while (digit != end && static_cast<unsigned>(*digit - '0') < 10u && digit - begin < 9) {
        fast = 10 * fast + static_cast<unsigned>(*digit - '0');
        ++digit;
    }
    if (digit != begin && (digit == end || endsNumber(*digit))) {
        position_ += static_cast<std::size_t>(digit - begin);
        return static_cast<Label>(fast);
    }
    const std::size_t start = position_;
    const std::int64_t value = readInteger(what);
    if (value > largestLabel || value < smallestLabel)
        failAt(start, std::string(what) + " " + std::to_string(value) + " does not fit in a 32-bit label (rbm uses 32-bit labels)");
    return static_cast<Label>(value);
}

double FoamListReader::readAsciiScalar(std::string_view what)
{
    skipSpace();
    const std::size_t start = position_;
    const char* begin = text_.data() + position_;
    const char* end = text_.data() + text_.size();
    // from_chars rejects a leading '+', which C++ streams (and so OpenFOAM) accept.
    if (begin != end && *begin == '+') ++begin;
    double value = 0.0;
    auto [stop, error] = std::from_chars(begin, end, value);
    if (error == std::errc::result_out_of_range) {
        // Underflow (1e-400) reads as 0 or a subnormal, as with C++ streams; overflow is an error.
        char buffer[64] = {};
        std::memcpy(buffer, begin, std::min<std::size_t>(sizeof buffer - 1, static_cast<std::size_t>(stop - begin)));
        value = std::strtod(buffer, nullptr);
        if (!std::isfinite(value))
            failAt(start, "expected a finite " + std::string(what) + " but found " + describeAt(start) + " (out of range)");
        error = std::errc();
    }
    if (error != std::errc() || (stop != end && !endsNumber(*stop)))
        failAt(start, "expected " + std::string(what) + " (a number) but found " + describeAt(start));
    if (!std::isfinite(value))
        failAt(start, "expected a finite " + std::string(what) + " but found " + describeAt(start));
    position_ = static_cast<std::size_t>(stop - text_.data());
    return value;
}

Vector3 FoamListReader::readAsciiVector(std::string_view what)
{
    skipSpace();
    if (atEnd() || text_[position_] != '(')
        failAt(position_, "expected '(' opening a " + std::string(what) + " (x y z) but found " + describeAt(position_));
    ++position_;
    Vector3 v;
    v.x = readAsciiScalar("coordinate");
    v.y = readAsciiScalar("coordinate");
    v.z = readAsciiScalar("coordinate");
    skipSpace();
    if (atEnd() || text_[position_] != ')')
        failAt(position_, "expected ')' closing a " + std::string(what) + " of 3 components but found " + describeAt(position_));
    ++position_;
    return v;
}

bool FoamListReader::readAsciiBool(std::string_view what)
{
    skipSpace();
    const std::size_t start = position_;
    std::size_t end = start;
    while (end < text_.size() && !endsNumber(text_[end])) ++end;
    const std::string_view word = text_.substr(start, end - start);
    position_ = end;
    if (word == "1" || word == "true" || word == "yes" || word == "on" || word == "y" || word == "t") return true;
    if (word == "0" || word == "false" || word == "no" || word == "off" || word == "n" || word == "f") return false;
    failAt(start, "expected " + std::string(what) + " (0 or 1) but found " + describeAt(start));
}

FoamListReader::ListHead FoamListReader::readListHead(std::string_view what, std::size_t elementBytes,
                                                      std::size_t minimumAsciiBytes, std::size_t maxCount)
{
    skipSpace();
    const std::size_t start = position_;
    if (atEnd()) failAt(start, "expected a list of " + plural(what) + " (a count followed by '(') but found end of file");
    const char c = text_[position_];
    if (c == '(') {
        if (binary_ && elementBytes > 0)
            failAt(start, "expected the size of a binary list of " + plural(what) + " before '('");
        ++position_;
        return {ListStart::Uncounted, 0};
    }
    if (!(c >= '0' && c <= '9'))
        failAt(start, "expected a list of " + plural(what) + " (a count followed by '(') but found " + describeAt(start));

    const std::int64_t signedCount = readInteger("a list size");
    if (signedCount > largestLabel)
        failAt(start, "list of " + std::to_string(signedCount) + " " + plural(what) +
                          " is larger than 32-bit labels can address (rbm uses 32-bit labels)");
    const auto count = static_cast<std::size_t>(signedCount);
    skipSpace();
    const std::size_t remaining = text_.size() - std::min(text_.size(), position_);
    // Messages are built only on failure: this runs once per face of a faceList.
    const auto countText = [&] { return std::to_string(count) + " " + plural(what); };

    if (binary_ && elementBytes > 0) {
        if (count == 0) {
            // OpenFOAM writes an empty binary list as a bare "0"; accept "0()" too.
            if (!atEnd() && text_[position_] == '(') {
                ++position_;
                expectChar(')', "closing an empty list of " + plural(what));
            }
            return {ListStart::EmptyBinary, 0};
        }
        if (atEnd() || text_[position_] != '(')
            failAt(position_, "expected '(' opening the binary list of " + countText() + " but found " + describeAt(position_));
        ++position_;
        // count <= 2^31 and elementBytes <= 24: no overflow.
        if (count * elementBytes + 1 > remaining - 1)
            failAt(start, "binary list of " + countText() + " needs " + std::to_string(count * elementBytes) +
                              " bytes but the file has only " + std::to_string(remaining - 1) +
                              " left (file truncated, or a label/scalar size in the header's arch that does not match the data)");
        return {ListStart::Counted, count};
    }

    if (!atEnd() && text_[position_] == '{') {
        if (count > maxCount)
            failAt(start, "uniform list of " + countText() + " is implausibly long (at most " + std::to_string(maxCount) +
                              " expected here)");
        ++position_;
        return {ListStart::Uniform, count};
    }
    if (atEnd() || text_[position_] != '(')
        failAt(position_, "expected '(' or '{' after the list size " + std::to_string(count) + " but found " +
                              describeAt(position_));
    ++position_;
    // Never allocate for a count the remaining text cannot hold (a corrupt count such as 2^31).
    if (count > 0 && count * minimumAsciiBytes > remaining)
        failAt(start, "list claims " + countText() + " but the file has only " + std::to_string(remaining) +
                          " bytes left (at least " + std::to_string(minimumAsciiBytes) + " per entry needed)");
    return {ListStart::Counted, count};
}

void FoamListReader::failShortList(std::string_view what, std::size_t count, std::size_t read) const
{
    if (atEnd())
        failAt(position_, "list of " + std::to_string(count) + " " + plural(what) + " is truncated: the file ends after " +
                              std::to_string(read) + " entries");
    failAt(position_, "list of " + std::to_string(count) + " " + plural(what) + " ends after " + std::to_string(read) +
                          " entries (found ')')");
}

void FoamListReader::expectListEnd(std::string_view what, std::size_t count, std::size_t read)
{
    skipSpace();
    if (atEnd())
        failAt(position_, "list of " + std::to_string(count) + " " + plural(what) + " is truncated: expected ')' after " +
                              std::to_string(read) + " entries but found end of file");
    if (text_[position_] != ')')
        failAt(position_, "list of " + std::to_string(count) + " " + plural(what) + " has more entries than its size (expected ')' but found " +
                              describeAt(position_) + ")");
    ++position_;
}

const char* FoamListReader::takeBinary(std::size_t bytes, std::string_view what, std::size_t count)
{
    const char* data = text_.data() + position_;
    position_ += bytes;
    if (atEnd() || text_[position_] != ')')
        failAt(position_, "expected ')' after the " + std::to_string(bytes) + " bytes of a binary list of " +
                              std::to_string(count) + " " + plural(what) + " but found " + describeAt(position_) +
                              " (a label/scalar size in the header's arch that does not match the data?)");
    ++position_;
    return data;
}

Label FoamListReader::binaryLabel(const char* bytes, std::string_view what) const
{
    if (labelBytes_ == 4) {
        std::int32_t value;
        std::memcpy(&value, bytes, 4);
        return value;
    }
    std::int64_t value;
    std::memcpy(&value, bytes, 8);
    if (value > largestLabel || value < smallestLabel)
        failAt(static_cast<std::size_t>(bytes - text_.data()),
               std::string(what) + " " + std::to_string(value) + " does not fit in a 32-bit label (rbm uses 32-bit labels)");
    return static_cast<Label>(value);
}

double FoamListReader::binaryScalar(const char* bytes) const
{
    if (scalarBytes_ == 8) {
        double value;
        std::memcpy(&value, bytes, 8);
        return value;
    }
    float value;
    std::memcpy(&value, bytes, 4);
    return value;
}

std::vector<Label> FoamListReader::readLabelList(std::string_view what, std::size_t maxCount)
{
    const ListHead head = readListHead(what, static_cast<std::size_t>(labelBytes_), 2, maxCount);
    std::vector<Label> values;
    switch (head.kind) {
    case ListStart::EmptyBinary:
        return values;
    case ListStart::Uniform: {
        const Label value = readAsciiLabel(what);
        expectChar('}', "closing a uniform list");
        values.assign(head.count, value);
        return values;
    }
    case ListStart::Uncounted:
        while (true) {
            skipSpace();
            if (atEnd()) failAt(position_, "list of " + plural(what) + " is truncated: expected ')' but found end of file");
            if (text_[position_] == ')') break;
            values.push_back(readAsciiLabel(what));
        }
        ++position_;
        return values;
    case ListStart::Counted:
        break;
    }
    values.resize(head.count);
    if (binary_) {
        const char* data = takeBinary(head.count * static_cast<std::size_t>(labelBytes_), what, head.count);
        if (labelBytes_ == 4) {
            std::memcpy(values.data(), data, head.count * 4);
        } else {
            for (std::size_t i = 0; i < head.count; ++i) values[i] = binaryLabel(data + 8 * i, what);
        }
        return values;
    }
    for (std::size_t i = 0; i < head.count; ++i) {
        skipSpace();
        if (atEnd() || text_[position_] == ')') failShortList(what, head.count, i);
        values[i] = readAsciiLabel(what);
    }
    expectListEnd(what, head.count, head.count);
    return values;
}

std::vector<double> FoamListReader::readScalarList(std::string_view what, std::size_t maxCount)
{
    const ListHead head = readListHead(what, static_cast<std::size_t>(scalarBytes_), 2, maxCount);
    std::vector<double> values;
    switch (head.kind) {
    case ListStart::EmptyBinary:
        return values;
    case ListStart::Uniform: {
        const double value = readAsciiScalar(what);
        expectChar('}', "closing a uniform list");
        values.assign(head.count, value);
        return values;
    }
    case ListStart::Uncounted:
        while (true) {
            skipSpace();
            if (atEnd()) failAt(position_, "list of " + plural(what) + " is truncated: expected ')' but found end of file");
            if (text_[position_] == ')') break;
            values.push_back(readAsciiScalar(what));
        }
        ++position_;
        return values;
    case ListStart::Counted:
        break;
    }
    values.resize(head.count);
    if (binary_) {
        const std::size_t listStart = position_;
        const char* data = takeBinary(head.count * static_cast<std::size_t>(scalarBytes_), what, head.count);
        for (std::size_t i = 0; i < head.count; ++i) {
            values[i] = binaryScalar(data + static_cast<std::size_t>(scalarBytes_) * i);
            if (!std::isfinite(values[i]))
                failAt(listStart, std::string(what) + " " + std::to_string(i) + " of the binary list is not finite (NaN or infinity)");
        }
        return values;
    }
    for (std::size_t i = 0; i < head.count; ++i) {
        skipSpace();
        if (atEnd() || text_[position_] == ')') failShortList(what, head.count, i);
        values[i] = readAsciiScalar(what);
    }
    expectListEnd(what, head.count, head.count);
    return values;
}

std::vector<Vector3> FoamListReader::readVectorList(std::string_view what, std::size_t maxCount)
{
    // "(0 0 0)" plus a separator: at least 8 bytes an entry.
    const ListHead head = readListHead(what, 3 * static_cast<std::size_t>(scalarBytes_), 8, maxCount);
    std::vector<Vector3> values;
    switch (head.kind) {
    case ListStart::EmptyBinary:
        return values;
    case ListStart::Uniform: {
        const Vector3 value = readAsciiVector(what);
        expectChar('}', "closing a uniform list");
        values.assign(head.count, value);
        return values;
    }
    case ListStart::Uncounted:
        while (true) {
            skipSpace();
            if (atEnd()) failAt(position_, "list of " + plural(what) + " is truncated: expected ')' but found end of file");
            if (text_[position_] == ')') break;
            values.push_back(readAsciiVector(what));
        }
        ++position_;
        return values;
    case ListStart::Counted:
        break;
    }
    values.resize(head.count);
    if (binary_) {
        const std::size_t listStart = position_;
        const std::size_t scalarBytes = static_cast<std::size_t>(scalarBytes_);
        const char* data = takeBinary(head.count * 3 * scalarBytes, what, head.count);
        if (scalarBytes == 8 && sizeof(Vector3) == 24) {
            std::memcpy(static_cast<void*>(values.data()), data, head.count * 24);
        } else {
            for (std::size_t i = 0; i < head.count; ++i) {
                values[i] = {binaryScalar(data + (3 * i) * scalarBytes), binaryScalar(data + (3 * i + 1) * scalarBytes),
                             binaryScalar(data + (3 * i + 2) * scalarBytes)};
            }
        }
        for (std::size_t i = 0; i < head.count; ++i) {
            if (!std::isfinite(values[i].x) || !std::isfinite(values[i].y) || !std::isfinite(values[i].z))
                failAt(listStart, std::string(what) + " " + std::to_string(i) +
                                      " of the binary list has a coordinate that is not finite (NaN or infinity)");
        }
        return values;
    }
    for (std::size_t i = 0; i < head.count; ++i) {
        skipSpace();
        if (atEnd() || text_[position_] == ')') failShortList(what, head.count, i);
        values[i] = readAsciiVector(what);
    }
    expectListEnd(what, head.count, head.count);
    return values;
}

std::vector<bool> FoamListReader::readBoolList(std::string_view what, std::size_t maxCount)
{
    const ListHead head = readListHead(what, 1, 2, maxCount);
    std::vector<bool> values;
    switch (head.kind) {
    case ListStart::EmptyBinary:
        return values;
    case ListStart::Uniform: {
        const bool value = readAsciiBool(what);
        expectChar('}', "closing a uniform list");
        values.assign(head.count, value);
        return values;
    }
    case ListStart::Uncounted:
        while (true) {
            skipSpace();
            if (atEnd()) failAt(position_, "list of " + plural(what) + " is truncated: expected ')' but found end of file");
            if (text_[position_] == ')') break;
            values.push_back(readAsciiBool(what));
        }
        ++position_;
        return values;
    case ListStart::Counted:
        break;
    }
    values.resize(head.count);
    if (binary_) {
        const std::size_t listStart = position_;
        const char* data = takeBinary(head.count, what, head.count);
        for (std::size_t i = 0; i < head.count; ++i) {
            if (data[i] != 0 && data[i] != 1)
                failAt(listStart, std::string(what) + " " + std::to_string(i) + " of the binary list is neither 0 nor 1");
            values[i] = data[i] == 1;
        }
        return values;
    }
    for (std::size_t i = 0; i < head.count; ++i) {
        skipSpace();
        if (atEnd() || text_[position_] == ')') failShortList(what, head.count, i);
        values[i] = readAsciiBool(what);
    }
    expectListEnd(what, head.count, head.count);
    return values;
}

void FoamListReader::checkFace(std::size_t face, Label pointCount, std::size_t offset) const
{
    if (pointCount < 3)
        failAt(offset, "face " + std::to_string(face) + " has " + std::to_string(pointCount) +
                           " points; a face needs at least 3");
}

void FoamListReader::readFaceList(std::vector<Label>& faceOffsets, std::vector<Label>& facePoints)
{
    if (faceOffsets.empty()) faceOffsets.push_back(static_cast<Label>(facePoints.size()));
    // Smallest face: "3(0 1 2)" plus a separator in ascii, "3(" + 3 labels + ")" in binary.
    const std::size_t smallestFace = binary_ ? 4 + 3 * static_cast<std::size_t>(labelBytes_) : 9;
    const ListHead head = readListHead("face", 0, smallestFace, 0);
    if (head.kind == ListStart::Uniform)
        failAt(position_, "a uniform face list (N{...}) cannot describe a valid mesh");
    if (head.kind == ListStart::Counted) {
        faceOffsets.reserve(faceOffsets.size() + head.count);
        facePoints.reserve(facePoints.size() + 4 * head.count);
    }
    const std::size_t labelBytes = static_cast<std::size_t>(labelBytes_);
    std::size_t face = 0;
    while (true) {
        skipSpace();
        if (head.kind == ListStart::Counted && face == head.count) break;
        if (atEnd())
            failAt(position_, "face list is truncated: expected " +
                                  (head.kind == ListStart::Counted ? std::to_string(head.count) + " faces" : std::string("')'")) +
                                  " but found end of file after " + std::to_string(face));
        if (text_[position_] == ')') {
            if (head.kind == ListStart::Uncounted) break;
            failAt(position_, "list of " + std::to_string(head.count) + " faces ends after " + std::to_string(face) + " faces");
        }
        const std::size_t faceStart = position_;
        const ListHead faceHead = readListHead("face point label", labelBytes, 2, std::numeric_limits<std::size_t>::max());
        if (faceHead.kind == ListStart::Uniform)
            failAt(faceStart, "face " + std::to_string(face) + " is a uniform list; a face needs distinct points");
        if (faceHead.kind == ListStart::Counted && binary_) {
            const char* data = takeBinary(faceHead.count * labelBytes, "face point label", faceHead.count);
            for (std::size_t i = 0; i < faceHead.count; ++i) facePoints.push_back(binaryLabel(data + labelBytes * i, "point label"));
        } else if (faceHead.kind == ListStart::Counted) {
            for (std::size_t i = 0; i < faceHead.count; ++i) {
                skipSpace();
                if (atEnd()) failAt(position_, "face list is truncated: the file ends inside face " + std::to_string(face));
                if (text_[position_] == ')')
                    failAt(position_, "face " + std::to_string(face) + " claims " + std::to_string(faceHead.count) +
                                          " points but lists " + std::to_string(i));
                facePoints.push_back(readAsciiLabel("point label"));
            }
            expectListEnd("face point label", faceHead.count, faceHead.count);
        } else if (faceHead.kind == ListStart::Uncounted) {
            while (true) {
                skipSpace();
                if (atEnd()) failAt(position_, "face " + std::to_string(face) + " is truncated: expected ')' but found end of file");
                if (text_[position_] == ')') break;
                facePoints.push_back(readAsciiLabel("point label"));
            }
            ++position_;
        }
        if (facePoints.size() > static_cast<std::size_t>(largestLabel))
            failAt(faceStart, "the faces hold more point labels than 32-bit face offsets can address");
        const Label pointCount = static_cast<Label>(facePoints.size()) - faceOffsets.back();
        checkFace(face, pointCount, faceStart);
        faceOffsets.push_back(static_cast<Label>(facePoints.size()));
        ++face;
    }
    if (head.kind == ListStart::Counted) {
        expectListEnd("face", head.count, face);
    } else if (head.kind == ListStart::Uncounted) {
        ++position_;
    }
}

void FoamListReader::readFaceCompactList(std::vector<Label>& faceOffsets, std::vector<Label>& facePoints)
{
    skipSpace();
    const std::size_t offsetsStart = position_;
    std::vector<Label> offsets = readLabelList("face offset", 0);
    skipSpace();
    const std::size_t labelsStart = position_;
    std::vector<Label> labels = readLabelList("face point label", 0);
    if (offsets.empty())
        failAt(offsetsStart, "faceCompactList needs at least one offset (0) but the offset list is empty");
    if (offsets.front() != 0)
        failAt(offsetsStart, "faceCompactList offsets must start at 0 but start at " + std::to_string(offsets.front()));
    for (std::size_t f = 0; f + 1 < offsets.size(); ++f) {
        const std::int64_t pointCount = std::int64_t(offsets[f + 1]) - offsets[f];
        if (pointCount < 3)
            failAt(offsetsStart, "face " + std::to_string(f) + " has " + std::to_string(pointCount) +
                                     " points (offsets " + std::to_string(offsets[f]) + " to " + std::to_string(offsets[f + 1]) +
                                     "); a face needs at least 3");
    }
    if (static_cast<std::size_t>(offsets.back()) != labels.size())
        failAt(labelsStart, "faceCompactList offsets end at " + std::to_string(offsets.back()) + " but there are " +
                                std::to_string(labels.size()) + " point labels");
    if (faceOffsets.size() <= 1 && facePoints.empty()) {
        faceOffsets = std::move(offsets);
        facePoints = std::move(labels);
        return;
    }
    const Label base = static_cast<Label>(facePoints.size());
    if (faceOffsets.empty()) faceOffsets.push_back(base);
    for (std::size_t f = 1; f < offsets.size(); ++f) faceOffsets.push_back(base + offsets[f]);
    facePoints.insert(facePoints.end(), labels.begin(), labels.end());
}

void FoamListReader::expectEnd()
{
    skipSpace();
    if (!atEnd())
        failAt(position_, "expected the end of the file after the list but found " + describeAt(position_));
}

// ---- Writing -------------------------------------------------------------------------------

std::string foamFileHeaderText(bool binary, std::string_view className, std::string_view location,
                               std::string_view object, std::string_view note)
{
    std::string out =
        "/*--------------------------------*- C++ -*----------------------------------*\\\n"
        "| =========                 |                                                 |\n"
        "| \\\\      /  F ield         | OpenFOAM: The Open Source CFD Toolbox           |\n"
        "|  \\\\    /   O peration     | Version:  v1912                                 |\n"
        "|   \\\\  /    A nd           | Website:  www.openfoam.com                      |\n"
        "|    \\\\/     M anipulation  |                                                 |\n"
        "\\*---------------------------------------------------------------------------*/\n"
        "FoamFile\n"
        "{\n"
        "    version     2.0;\n";
    out += binary ? "    format      binary;\n" : "    format      ascii;\n";
    out += "    class       ";
    out += className;
    out += ";\n    arch        \"LSB;label=32;scalar=64\";\n";
    if (!note.empty()) {
        out += "    note        \"";
        out += note;
        out += "\";\n";
    }
    out += "    location    \"";
    out += location;
    out += "\";\n    object      ";
    out += object;
    out += ";\n}\n// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n";
    return out;
}

std::string foamFileFooterText()
{
    return "\n\n// ************************************************************************* //\n";
}

void appendScalar(std::string& out, double value, int precision)
{
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, precision);
    out.append(buffer, result.ptr);
}

void appendLabel(std::string& out, std::int64_t value)
{
    char buffer[24];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, result.ptr);
}

namespace {

void appendListStart(std::string& out, std::size_t count, bool binary)
{
    out += '\n';
    appendLabel(out, static_cast<std::int64_t>(count));
    out += binary ? "\n(" : "\n(\n";
}

// "\nN\n(" before the bytes of a binary list; OpenFOAM writes an empty binary list as the bare
// count "\nN\n". Returns whether the bytes (and a closing ')') follow.
bool appendBinaryListStart(std::string& out, std::size_t count)
{
    out += '\n';
    appendLabel(out, static_cast<std::int64_t>(count));
    out += '\n';
    if (count == 0) return false;
    out += '(';
    return true;
}

void appendRaw(std::string& out, const void* data, std::size_t bytes)
{
    out.append(static_cast<const char*>(data), bytes);
}

// One ascii vector list entry: "(x y z)\n".
void appendVectorLine(std::string& out, const Vector3& v, int precision)
{
    out += '(';
    appendScalar(out, v.x, precision);
    out += ' ';
    appendScalar(out, v.y, precision);
    out += ' ';
    appendScalar(out, v.z, precision);
    out += ")\n";
}

} // namespace

void appendLabelList(std::string& out, std::span<const Label> values, bool binary)
{
    if (binary) {
        if (!appendBinaryListStart(out, values.size())) return;
        appendRaw(out, values.data(), values.size_bytes());
        out += ')';
        return;
    }
    out.reserve(out.size() + 8 * values.size() + 32);
    appendListStart(out, values.size(), false);
    for (Label v : values) {
        appendLabel(out, v);
        out += '\n';
    }
    out += ")\n";
}

void appendVectorList(std::string& out, std::span<const Vector3> values, bool binary, int precision)
{
    if (binary) {
        if (!appendBinaryListStart(out, values.size())) return;
        static_assert(sizeof(Vector3) == 3 * sizeof(double));
        appendRaw(out, values.data(), values.size_bytes());
        out += ')';
        return;
    }
    out.reserve(out.size() + static_cast<std::size_t>(3 * precision + 16) * values.size() + 32);
    appendListStart(out, values.size(), false);
    for (const Vector3& v : values) appendVectorLine(out, v, precision);
    out += ")\n";
}

// The same bytes as the std::string version above, handed to `out` a piece at a time: the
// whole list is never in memory as text (binary data goes to the file from `values` itself).
void appendVectorList(TextFileWriter& out, std::span<const Vector3> values, bool binary, int precision)
{
    if (binary) {
        if (!appendBinaryListStart(out.text(), values.size())) return;
        static_assert(sizeof(Vector3) == 3 * sizeof(double));
        out.append(std::string_view(reinterpret_cast<const char*>(values.data()), values.size_bytes()));
        out.text() += ')';
        return;
    }
    appendListStart(out.text(), values.size(), false);
    for (const Vector3& v : values) {
        appendVectorLine(out.text(), v, precision);
        out.pieceDone();
    }
    out.text() += ")\n";
}

void appendScalarList(std::string& out, std::span<const double> values, bool binary, int precision)
{
    if (binary) {
        if (!appendBinaryListStart(out, values.size())) return;
        appendRaw(out, values.data(), values.size_bytes());
        out += ')';
        return;
    }
    appendListStart(out, values.size(), false);
    for (double v : values) {
        appendScalar(out, v, precision);
        out += '\n';
    }
    out += ")\n";
}

void appendBoolList(std::string& out, const std::vector<bool>& values, bool binary)
{
    if (binary) {
        if (!appendBinaryListStart(out, values.size())) return;
        for (bool v : values) out += static_cast<char>(v ? 1 : 0);
        out += ')';
        return;
    }
    appendListStart(out, values.size(), false);
    for (bool v : values) out += v ? "1\n" : "0\n";
    out += ")\n";
}

void appendFaceList(std::string& out, std::span<const Label> faceOffsets, std::span<const Label> facePoints)
{
    const std::size_t faceCount = faceOffsets.empty() ? 0 : faceOffsets.size() - 1;
    out.reserve(out.size() + 8 * facePoints.size() + 4 * faceCount + 32);
    appendListStart(out, faceCount, false);
    for (std::size_t f = 0; f < faceCount; ++f) {
        appendLabel(out, faceOffsets[f + 1] - faceOffsets[f]);
        out += '(';
        for (Label i = faceOffsets[f]; i < faceOffsets[f + 1]; ++i) {
            if (i != faceOffsets[f]) out += ' ';
            appendLabel(out, facePoints[static_cast<std::size_t>(i)]);
        }
        out += ")\n";
    }
    out += ")\n";
}

void appendFaceCompactList(std::string& out, std::span<const Label> faceOffsets, std::span<const Label> facePoints,
                           bool binary)
{
    appendLabelList(out, faceOffsets, binary);
    appendLabelList(out, facePoints, binary);
}

} // namespace rbm::io
