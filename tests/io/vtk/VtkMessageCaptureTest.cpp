// Tests of VTK's messages captured (io/vtk/VtkMessageCapture).

#include "CompressedFile.hpp"
#include "InputError.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"
#include "PolyMeshWriter.hpp"
#include "RunLog.hpp"
#include "ScratchFiles.hpp"
#include "SmallTmpfs.hpp"
#include "TimeFolderWriter.hpp"
#include "VtkMessageCapture.hpp"
#include "VtkWriter.hpp"
#include "WholeFile.hpp"

#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace rbm;

TEST(VtkMessageCapture, VtkMessagesAreKeptAndNotPrinted)
{
    vtkNew<vtkPoints> source;
    ::testing::internal::CaptureStderr();
    ::testing::internal::CaptureStdout();
    {
        io::VtkMessageCapture capture;
        vtkErrorWithObjectMacro(source.GetPointer(), << "the disk is full");
        vtkGenericWarningMacro(<< "a warning");
        ASSERT_EQ(capture.messages().size(), 2u);
        EXPECT_TRUE(capture.hasErrors());
        EXPECT_NE(capture.messages()[0].find("the disk is full"), std::string::npos) << capture.messages()[0];
        EXPECT_EQ(capture.messages()[0].find("ERROR: In"), std::string::npos) << capture.messages()[0];
        EXPECT_NE(capture.summary().find("the disk is full"), std::string::npos);
        EXPECT_NE(capture.summary().find("; "), std::string::npos);
    }
    const std::string printed = ::testing::internal::GetCapturedStderr() + ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(printed, "");
    // VTK's own window is back afterwards.
    EXPECT_STRNE(vtkOutputWindow::GetInstance()->GetClassName(), "Window");
}

} // namespace
