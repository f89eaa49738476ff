#include "VtkMessageCapture.hpp"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>

#include <sstream>

namespace rbm::io {

// An output window that keeps the messages instead of printing them.
class VtkMessageCapture::Window : public vtkOutputWindow {
public:
    static Window* New();
    vtkTypeMacro(Window, vtkOutputWindow)

    void DisplayText(const char* text) override { keep(text, false); }
    void DisplayErrorText(const char* text) override { keep(text, true); }
    void DisplayWarningText(const char* text) override { keep(text, false); }
    void DisplayGenericWarningText(const char* text) override { keep(text, false); }
    void DisplayDebugText(const char*) override {}

    std::vector<std::string> messages;
    bool errors = false;

private:
    void keep(const char* text, bool error)
    {
        errors = errors || error;
        // Drop VTK's "ERROR: In <source file>, line <n>" line and the blank lines; keep the rest
        // on one line.
        std::istringstream lines(text ? text : "");
        std::string message;
        for (std::string line; std::getline(lines, line);) {
            if (line.empty() || line.rfind("ERROR: In ", 0) == 0 || line.rfind("Warning: In ", 0) == 0 ||
                line.rfind("Generic Warning: In ", 0) == 0) {
                continue;
            }
            message += (message.empty() ? "" : " ") + line;
        }
        if (!message.empty()) messages.push_back(message);
    }
};

vtkStandardNewMacro(VtkMessageCapture::Window);

VtkMessageCapture::VtkMessageCapture() : window_(Window::New()), previous_(vtkOutputWindow::GetInstance())
{
    previous_->Register(nullptr);   // SetInstance below releases VTK's own reference
    vtkOutputWindow::SetInstance(window_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

VtkMessageCapture::~VtkMessageCapture()
{
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_INFO);   // VTK's default; rbm sets no other
    vtkOutputWindow::SetInstance(previous_);
    previous_->UnRegister(nullptr);
    window_->Delete();
}

const std::vector<std::string>& VtkMessageCapture::messages() const
{
    return window_->messages;
}

bool VtkMessageCapture::hasErrors() const
{
    return window_->errors;
}

std::string VtkMessageCapture::summary() const
{
    const std::vector<std::string>& all = window_->messages;
    if (all.empty()) return "no message from VTK";
    constexpr std::size_t shown = 2;
    std::string text;
    for (std::size_t i = 0; i < all.size() && i < shown; ++i) text += (i > 0 ? "; " : "") + all[i];
    if (all.size() > shown) text += " (and " + std::to_string(all.size() - shown) + " more)";
    return text;
}

} // namespace rbm::io
