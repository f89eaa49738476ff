#pragma once
// A small 2D OpenFOAM case for the tests that run the built rbmMoveMesh on a case of their
// own (KillDuringWriteTest, WriteFailureTest, CaseLockTest): n × n quadrilaterals on the
// unit square, one layer; the left side moves right, the right side is fixed, top and
// bottom slide: a smooth compression, no inverted cell. deltaT 0.1, every step written as
// ascii with 17 digits (large files: writing takes a noticeable part of a step).

#include "MeshGenerators.hpp"
#include "PolyMeshWriter.hpp"
#include "ScratchFiles.hpp"

#include <filesystem>
#include <string>

namespace rbm::test {

inline std::string foamHeader(const std::string& className, const std::string& location, const std::string& object)
{
    return "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class " + className + ";\n    location \"" +
           location + "\";\n    object " + object + ";\n}\n\n";
}

inline std::string controlDict(bool compressed, const std::string& endTime = "0.3")
{
    return foamHeader("dictionary", "system", "controlDict") +
           "application rbmMoveMesh;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime " + endTime +
           ";\ndeltaT 0.1;\nwriteControl timeStep;\nwriteInterval 1;\nwriteFormat ascii;\nwritePrecision 17;\n"
           "writeCompression " +
           std::string(compressed ? "on" : "off") + ";\ntimeFormat general;\ntimePrecision 6;\n";
}

// The left side moves right by `speed` per unit time.
inline std::string pointDisplacement(const std::string& speed)
{
    return foamHeader("pointVectorField", "0", "pointDisplacement") +
           "dimensions [0 1 0 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{\n"
           "    left { type uniformFixedValue; uniformValue table ((0 (0 0 0)) (1 (" +
           speed +
           " 0 0))); value uniform (0 0 0); }\n"
           "    right { type fixedValue; value uniform (0 0 0); }\n"
           "    \"(top|bottom)\" { type slip; }\n"
           "    frontAndBack { type empty; }\n}\n";
}

// The case with `cells` × `cells` quadrilaterals (mesh in binary, to read fast), steps up to
// `endTime`, written gzip-compressed or not.
inline void writeCompressionCase(const std::filesystem::path& caseDir, Label cells, const std::string& endTime,
                                 bool compressed = true)
{
    const PolyMesh mesh = makeExtruded2D(cells, cells, Vector3{0, 0, 0}, Vector3{1, 1, 0.01});
    io::FoamWriteOptions binary;
    binary.binary = true;
    io::writePolyMesh(caseDir / "constant" / "polyMesh", mesh, binary);
    writeText(caseDir / "system" / "controlDict", controlDict(compressed, endTime));
    writeText(caseDir / "constant" / "dynamicMeshDict",
              foamHeader("dictionary", "constant", "dynamicMeshDict") +
                  "dynamicFvMesh dynamicMotionSolverFvMesh;\nmotionSolver rigidBodyMotionSolver;\n"
                  "rigidBodyMotionSolverCoeffs\n{\n    formulation linearized;\n    subSteps 1;\n}\n");
    writeText(caseDir / "0" / "pointDisplacement", pointDisplacement("0.2"));
}

} // namespace rbm::test
