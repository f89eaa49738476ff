#include "RunLog.hpp"

#include "WholeFile.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace rbm::io {

namespace {

// printf into a std::string (the line is short; a fixed buffer covers every field).
template <class... Arguments>
void appendFormatted(std::string& out, const char* format, Arguments... arguments)
{
    char buffer[256];
    const int length = std::snprintf(buffer, sizeof buffer, format, arguments...);
    if (length > 0) out.append(buffer, static_cast<std::size_t>(std::min<int>(length, sizeof buffer - 1)));
}

// A number in a fixed-width column, or "n/a" right-aligned in the same width.
void appendFixed(std::string& out, double value, int width, int decimals)
{
    if (std::isfinite(value)) {
        appendFormatted(out, "%*.*f", width, decimals, value);
    } else {
        appendFormatted(out, "%*s", width, "n/a");
    }
}

} // namespace

std::string formatStepLogLine(const StepLogRecord& record, int timeNameWidth)
{
    std::string line = "Time = ";
    appendFormatted(line, "%-*s", timeNameWidth, record.timeName.c_str());
    return line + "  " + formatStepFigures(record);
}

std::string formatStepFigures(const StepLogRecord& record)
{
    std::string line;
    appendFormatted(line, "sub-steps %2d  iterations %4d  residual ", record.subSteps, record.iterations);
    if (std::isfinite(record.residual)) {
        appendFormatted(line, "%8.2e", record.residual);
    } else {
        appendFormatted(line, "%8s", "n/a");
    }
    line += "  worst quality ";
    appendFixed(line, record.worstQuality, 7, 4);
    line += "  max non-orthogonality ";
    appendFixed(line, record.maxNonOrthogonality, 6, 2);
    appendFormatted(line, "  inverted %lld  wall ", record.invertedCells);
    appendFixed(line, record.wallSeconds, 7, 3);
    line += " s";
    if (!record.converged) line += "  NOT CONVERGED (" + (record.reason.empty() ? std::string("no reason given") : record.reason) + ")";
    if (record.invertedCells > 0) line += "  INVALID";
    if (record.written) line += "  written";
    return line;
}

std::string jsonNumber(double value)
{
    if (!std::isfinite(value)) return "null";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string jsonString(std::string_view text)
{
    std::string out = "\"";
    for (const char c : text) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        case '\b': out += "\\b"; break;
        case '\f': out += "\\f"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char escaped[8];
                std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
                out += escaped;
            } else {
                out += c;
            }
        }
    }
    out += '"';
    return out;
}

std::string stepLogJson(const StepLogRecord& record)
{
    std::string out = "{";
    out += "\"step\":" + std::to_string(record.step);
    out += ",\"time\":" + jsonNumber(record.time);
    out += ",\"timeName\":" + jsonString(record.timeName);
    out += ",\"subSteps\":" + std::to_string(record.subSteps);
    out += ",\"iterations\":" + std::to_string(record.iterations);
    out += ",\"residual\":" + jsonNumber(record.residual);
    out += ",\"energy\":" + jsonNumber(record.energy);
    out += std::string(",\"converged\":") + (record.converged ? "true" : "false");
    out += ",\"reason\":" + jsonString(record.reason);
    out += ",\"worstQuality\":" + jsonNumber(record.worstQuality);
    out += ",\"maxNonOrthogonality\":" + jsonNumber(record.maxNonOrthogonality);
    out += ",\"maxSkewness\":" + jsonNumber(record.maxSkewness);
    out += ",\"invertedCells\":" + std::to_string(record.invertedCells);
    out += ",\"wallSeconds\":" + jsonNumber(record.wallSeconds);
    out += std::string(",\"written\":") + (record.written ? "true" : "false");
    out += '}';
    return out;
}

JsonLinesWriter::JsonLinesWriter(const std::filesystem::path& file, bool truncate) : file_(file)
{
    if (file.has_parent_path()) {
        std::error_code error;
        std::filesystem::create_directories(file.parent_path(), error);
        if (error) {
            throw std::runtime_error("cannot create the folder " + file.parent_path().string() + ": " + error.message());
        }
    }
    fd_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (truncate ? O_TRUNC : O_APPEND), 0666);
    if (fd_ < 0) {
        const int error = errno;
        throw std::runtime_error("cannot create " + file.string() + ": " + systemErrorText(error));
    }
}

JsonLinesWriter::~JsonLinesWriter()
{
    if (fd_ >= 0) ::close(fd_);
}

JsonLinesWriter::JsonLinesWriter(JsonLinesWriter&& other) noexcept
    : file_(std::move(other.file_)), fd_(std::exchange(other.fd_, -1))
{}

JsonLinesWriter& JsonLinesWriter::operator=(JsonLinesWriter&& other) noexcept
{
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        file_ = std::move(other.file_);
        fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
}

void JsonLinesWriter::append(std::string_view jsonObject)
{
    std::string line(jsonObject);
    line += '\n';
    // A full disk may take part of the line: cut the file back to its end before it, so a
    // reader never meets half a line.
    const off_t end = ::lseek(fd_, 0, SEEK_END);
    std::size_t written = 0;
    while (written < line.size()) {
        const ssize_t result = ::write(fd_, line.data() + written, line.size() - written);
        if (result < 0 && errno == EINTR) continue;
        if (result < 0) {
            const int error = errno;
            if (end >= 0) {
                const int cut = ::ftruncate(fd_, end);   // the write's reason is the one to report
                static_cast<void>(cut);
            }
            throw std::runtime_error("cannot write " + file_.string() + ": " + systemErrorText(error));
        }
        written += static_cast<std::size_t>(result);
    }
}

} // namespace rbm::io
