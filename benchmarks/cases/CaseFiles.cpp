#include "CaseFiles.hpp"

#include "BenchmarkCases.hpp"

#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace rbm::benchmark {

std::string pitchingBoundaryField(const std::string& airfoilType)
{
    return R"(
    airfoil
    {
        type                    )" + airfoilType + R"(;
        solidBodyMotionFunction multiMotion;
        multiMotionCoeffs
        {
            plunge
            {
                solidBodyMotionFunction oscillatingLinearMotion;
                oscillatingLinearMotionCoeffs { amplitude (0 0.05 0); omega 6.28318530717959; }
            }
            pitch
            {
                solidBodyMotionFunction oscillatingRotatingMotion;
                oscillatingRotatingMotionCoeffs { origin (0.25 0 0); amplitude (0 0 5); omega 6.28318530717959; }
            }
        }
        value uniform (0 0 0);
    }
    farfield { type fixedValue; value uniform (0 0 0); }
    frontAndBack { type empty; }
)";
}

std::string pointDisplacementFile(const std::string& boundaryField)
{
    return "FoamFile { version 2.0; format ascii; class pointVectorField; location \"0\"; object pointDisplacement; }\n"
           "dimensions [0 1 0 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{" +
           boundaryField + "}\n";
}

void writeText(const fs::path& file, const std::string& text)
{
    fs::create_directories(file.parent_path());
    std::ofstream out(file);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::string foamHeader(const std::string& className, const std::string& location, const std::string& object)
{
    return "FoamFile { version 2.0; format ascii; class " + className + "; location \"" + location + "\"; object " +
           object + "; }\n";
}

std::string vectorText(const Vector3& v)
{
    std::ostringstream out;
    out << std::setprecision(17) << "(" << v.x << " " << v.y << " " << v.z << ")";
    return out.str();
}

std::string stepBoundaryField(const std::string& caseName, const std::vector<Patch>& patches)
{
    const CaseMotion motion = caseMotion(caseName);
    std::ostringstream out;
    out << std::setprecision(17);
    for (const Patch& patch : patches) {
        out << "\n    " << patch.name << "\n    {\n";
        switch (patchRole(caseName, patch)) {
        case PatchRole::moving:
            out << "        type solidBodyMotionDisplacement;\n        solidBodyMotionFunction rotatingMotion;\n"
                << "        rotatingMotionCoeffs { origin " << vectorText(motion.centre) << "; axis "
                << vectorText(motion.axis) << "; omega " << motion.angle << "; }\n        value uniform (0 0 0);\n";
            break;
        case PatchRole::fixed: out << "        type fixedValue;\n        value uniform (0 0 0);\n"; break;
        case PatchRole::free: out << "        type zeroGradient;\n"; break;
        case PatchRole::ignored: out << "        type " << patch.type << ";\n"; break;
        }
        out << "    }\n";
    }
    return out.str();
}

void writeMotionCase(const fs::path& dir, const fs::path& polyMeshSource, const std::string& application,
                     const std::string& dynamicMeshBody, const std::string& boundaryField, int steps)
{
    fs::remove_all(dir);
    fs::create_directories(dir / "constant");
    fs::copy(polyMeshSource, dir / "constant" / "polyMesh", fs::copy_options::recursive);
    std::ostringstream control;
    control << std::setprecision(17) << foamHeader("dictionary", "system", "controlDict") << "application " << application
            << ";\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime 1;\ndeltaT " << 1.0 / steps
            << ";\nwriteControl timeStep;\nwriteInterval " << steps
            << ";\npurgeWrite 0;\nwriteFormat binary;\nwritePrecision 12;\nwriteCompression on;\n"
               "timeFormat general;\ntimePrecision 6;\nrunTimeModifiable false;\n";
    writeText(dir / "system" / "controlDict", control.str());
    writeText(dir / "system" / "fvSchemes",
              foamHeader("dictionary", "system", "fvSchemes") +
                  "ddtSchemes { default Euler; }\ngradSchemes { default Gauss linear; }\ndivSchemes { default none; }\n"
                  "laplacianSchemes { default Gauss linear corrected; }\ninterpolationSchemes { default linear; }\n"
                  "snGradSchemes { default corrected; }\n");
    writeText(dir / "system" / "fvSolution",
              foamHeader("dictionary", "system", "fvSolution") +
                  "solvers\n{\n    cellDisplacement\n    {\n        solver GAMG;\n        smoother GaussSeidel;\n"
                  "        tolerance 1e-08;\n        relTol 0;\n    }\n}\n");
    writeText(dir / "constant" / "dynamicMeshDict",
              foamHeader("dictionary", "constant", "dynamicMeshDict") + dynamicMeshBody);
    writeText(dir / "0" / "pointDisplacement", pointDisplacementFile(boundaryField));
}

} // namespace rbm::benchmark
