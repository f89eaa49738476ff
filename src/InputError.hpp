#pragma once
// The one exception type for bad user input: a file, a line (0 when not known) and
// what was expected. what() reads "FILE:LINE: message", like a compiler's diagnostic,
// so a command-line program only has to print it and exit non-zero.

#include <sstream>
#include <stdexcept>
#include <string>

namespace rbm {

class InputError : public std::runtime_error {
public:
    InputError(std::string file, int line, const std::string& message)
        : std::runtime_error(format(file, line, message)), file_(std::move(file)), line_(line), message_(message)
    {}

    const std::string& file() const { return file_; }
    int line() const { return line_; }
    const std::string& message() const { return message_; }

private:
    static std::string format(const std::string& file, int line, const std::string& message)
    {
        // A stream, not string concatenation: GCC 12 warns falsely (-Wrestrict) on the latter.
        std::ostringstream text;
        text << (file.empty() ? std::string("<input>") : file);
        if (line > 0) text << ':' << line;
        text << ": " << message;
        return text.str();
    }

    std::string file_;
    int line_;
    std::string message_;
};

} // namespace rbm
