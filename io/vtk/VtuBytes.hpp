#pragma once
// The one entry point of the VTK module librbm_vtk.so (io/vtk/): the bytes of an XML .vtu
// file for a grid. rbmMoveMesh loads the module, and with it VTK's libraries (a fifth of the
// program's start-up), only when it writes VTK output: writeVtu (VtkWriter.hpp) opens it at
// its first call. Nothing else of rbm includes VTK.

#include "VtkWriter.hpp"

#include <string>
#include <vector>

namespace rbm::io {

// The arguments of writeVtu; `bytes` receives the file, or `error` why VTK could not write it
// (a field of the wrong length, VTK's own messages on one line); returns whether it wrote.
struct VtuRequest {
    const std::vector<Vector3>* points = nullptr;
    const VtkCells* cells = nullptr;
    const std::vector<VtkField>* pointFields = nullptr;
    const std::vector<VtkField>* cellFields = nullptr;
    std::string bytes;
    std::string error;
};

} // namespace rbm::io

// The module's symbol (C linkage, so dlsym finds it by this name).
extern "C" bool rbmVtuBytes(rbm::io::VtuRequest* request);
