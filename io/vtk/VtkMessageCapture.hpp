#pragma once
// Keeps VTK's messages from the terminal while it lives: VTK reports a problem as a dump of
// several lines per object involved ("ERROR: In .../vtkExecutive.cxx, line 752
// vtkCompositeDataPipeline (0x...): Algorithm vtkXMLUnstructuredGridWriter ... returned
// failure ..."), through its output window and, with VTK's logger, through loguru on stderr.
// While a capture lives, both are redirected into it, and the caller reports them as one rbm
// message. One capture at a time, on the thread that uses VTK (VTK's output window is global).
//
//   VtkMessageCapture capture;
//   if (writer->Write() != 1) throw std::runtime_error("VTK could not write x: " + capture.summary());

#include <string>
#include <vector>

class vtkOutputWindow;

namespace rbm::io {

class VtkMessageCapture {
public:
    VtkMessageCapture();
    ~VtkMessageCapture();   // VTK's own output window and stderr logging again
    VtkMessageCapture(const VtkMessageCapture&) = delete;
    VtkMessageCapture& operator=(const VtkMessageCapture&) = delete;

    // The messages so far, each as its text without VTK's "ERROR: In <file>, line <n>" line.
    const std::vector<std::string>& messages() const;
    bool hasErrors() const;
    // The first messages on one line ("a; b (and 3 more)"), or "no message from VTK".
    std::string summary() const;

private:
    class Window;
    Window* window_;              // the capturing output window (VTK reference counted)
    vtkOutputWindow* previous_;   // VTK's window, referenced while replaced
};

} // namespace rbm::io
