#include "Options.hpp"

#include "BenchmarkCases.hpp"
#include "Variants.hpp"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <stdexcept>

#ifndef RBM_SOURCE_DIR
#define RBM_SOURCE_DIR "."
#endif

namespace rbm::benchmark {

std::vector<std::string> splitList(const std::string& text)
{
    std::vector<std::string> items;
    std::string item;
    std::istringstream in(text);
    while (std::getline(in, item, ','))
        if (!item.empty()) items.push_back(item);
    return items;
}

const char* usage =
    "usage: rbmBenchmark [--sizes 1e4,1e5,1e6] [--variants decoupled,linearized,newton,localGlobal]\n"
    "                    [--cases quad2D,tri2D,hex3D,tet3D,twist3D,airfoil] [--json FILE] [--markdown FILE]\n"
    "                    [--quick] [--openfoam auto|off] [--whole-process auto|off] [--pitching-steps N]\n"
    "                    [--pitching-nonlinear-steps N] [--run-timeout SECONDS]\n"
    "                    [--memory-limit-gb G] [--diffusivity inverseDistance|uniform] [--airfoil DIR]\n"
    "                    [--work-dir DIR] [--keep] [--ranks 2,4]\n"
    "  --quick: sizes 1e4 (unless --sizes), 10 pitching steps (linearized only), no OpenFOAM, no rbmMoveMesh runs.\n"
    "  Variants: decoupled, linearized, newton, localGlobal, reducedNewton, decoupledLinearized, linearizedAssembled\n"
    "  (the linearized system assembled: direct in 2D and small 3D, else CG + GAMG), linearizedMatrixFree\n"
    "  ('linearized' takes the automatic choice: direct in 2D, matrix-free in 3D).\n"
    "  Sizes: RBM nodes (2D: nodes per plane) for the box-with-hole cases, cells for twist3D;\n"
    "  the airfoil mesh has one size.\n"
    "  --ranks: twist3D also decomposed (decomposePar, method simple) over each rank count, moved by\n"
    "  mpirun -np N rbmMoveMesh -parallel and mpirun -np N moveMesh -parallel (OpenFOAM needed).\n";

Options parseOptions(int argc, char** argv)
{
    Options options;
    bool openfoamGiven = false;
    bool wholeGiven = false;
    bool pitchingGiven = false;
    options.commandLine = "rbmBenchmark";
    for (int k = 1; k < argc; ++k) options.commandLine += std::string(" ") + argv[k];
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        auto value = [&]() -> std::string {
            if (k + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
            return argv[++k];
        };
        if (arg == "--sizes") {
            options.sizes.clear();
            for (const std::string& item : splitList(value())) options.sizes.push_back(std::stod(item));
            options.sizesGiven = true;
        } else if (arg == "--variants") {
            options.variants = splitList(value());
            for (const std::string& variant : options.variants)
                if (std::find(allVariants().begin(), allVariants().end(), variant) == allVariants().end())
                    throw std::invalid_argument("unknown variant " + variant);
        } else if (arg == "--cases") {
            options.cases = splitList(value());
            for (const std::string& name : options.cases) caseInfo(name);
        } else if (arg == "--json") {
            options.json = value();
        } else if (arg == "--markdown") {
            options.markdown = value();
        } else if (arg == "--quick") {
            options.quick = true;
        } else if (arg == "--openfoam") {
            options.openfoam = value();
            openfoamGiven = true;
        } else if (arg == "--whole-process") {
            options.wholeProcess = value();
            wholeGiven = true;
        } else if (arg == "--pitching-steps") {
            options.pitchingSteps = std::stoi(value());
            pitchingGiven = true;
        } else if (arg == "--pitching-nonlinear-steps") {
            options.pitchingNonlinearSteps = std::stoi(value());
        } else if (arg == "--run-timeout") {
            options.runTimeout = std::stoi(value());
        } else if (arg == "--memory-limit-gb") {
            options.memoryLimitGiB = std::stod(value());
        } else if (arg == "--diffusivity") {
            options.diffusivity = value();
        } else if (arg == "--airfoil") {
            options.airfoilDir = value();
        } else if (arg == "--work-dir") {
            options.workDir = value();
        } else if (arg == "--ranks") {
            options.ranks.clear();
            for (const std::string& item : splitList(value())) {
                options.ranks.push_back(std::stoi(item));
                if (options.ranks.back() < 2) throw std::invalid_argument("--ranks: counts of at least 2");
            }
        } else if (arg == "--keep") {
            options.keep = true;
        } else if (arg == "--help" || arg == "-h") {
            std::cout << usage;
            std::exit(0);
        } else {
            throw std::invalid_argument("unknown option " + arg);
        }
    }
    if (options.quick) {
        if (!options.sizesGiven) options.sizes = {1e4};
        if (!openfoamGiven) options.openfoam = "off";
        if (!wholeGiven) options.wholeProcess = "off";
        if (!pitchingGiven) {
            options.pitchingSteps = 10;
            options.pitchingNonlinearSteps = 0;
        }
    }
    if (options.diffusivity != "inverseDistance" && options.diffusivity != "uniform")
        throw std::invalid_argument("--diffusivity must be inverseDistance or uniform");
    return options;
}

} // namespace rbm::benchmark
