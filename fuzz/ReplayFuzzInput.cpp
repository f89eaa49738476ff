// replayFuzzInput TARGET FILE...: runs fuzz inputs through the entry function of a target
// (dictionaryFuzzer, asciiListFuzzer, binaryListFuzzer, pointFieldFuzzer, polyMeshFuzzer)
// and prints, per file, "OK" or the rbm::InputError message. For triage: a libFuzzer binary
// only says whether an input crashed, not what the reader made of it.

#include "FuzzEntryPoints.hpp"

#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>

int main(int argc, char** argv)
{
    const std::map<std::string, std::function<void(std::string_view)>> targets = {
        {"dictionaryFuzzer", rbm::fuzz::parseDictionary}, {"asciiListFuzzer", rbm::fuzz::readListFile},
        {"binaryListFuzzer", rbm::fuzz::readBinaryListFile}, {"pointFieldFuzzer", rbm::fuzz::readPointField},
        {"polyMeshFuzzer", rbm::fuzz::readPolyMeshFolder}};
    const auto target = argc > 1 ? targets.find(argv[1]) : targets.end();
    if (target == targets.end()) {
        std::cerr << "usage: replayFuzzInput TARGET FILE...  (TARGET: dictionaryFuzzer, asciiListFuzzer, "
                     "binaryListFuzzer, pointFieldFuzzer, polyMeshFuzzer)\n";
        return 2;
    }
    for (int i = 2; i < argc; ++i) {
        std::ifstream in(argv[i], std::ios::binary);
        std::stringstream bytes;
        bytes << in.rdbuf();
        try {
            target->second(bytes.str());
            std::cout << argv[i] << ": OK\n";
        } catch (const rbm::InputError& error) {
            std::cout << argv[i] << ": InputError: " << error.what() << '\n';
        }
    }
    return 0;
}
