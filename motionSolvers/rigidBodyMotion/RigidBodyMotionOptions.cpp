#include "RigidBodyMotionOptions.hpp"

#include "InputError.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rbm::motion {

namespace {

std::string joined(const std::vector<std::string_view>& words)
{
    std::string text;
    for (std::string_view word : words) {
        if (!text.empty()) text += ' ';
        text += word;
    }
    return text;
}

[[noreturn]] void failAt(const io::Entry& entry, const std::string& message)
{
    throw InputError(entry.file(), entry.line(), message);
}

// A single word value, one of `valid`.
std::string readChoice(const io::Entry& entry, const std::vector<std::string_view>& valid)
{
    if (entry.isDictionary()) failAt(entry, "'" + entry.keyword() + "' must be one of: " + joined(valid));
    io::TokenStream stream = entry.stream();
    if (stream.atEnd()) failAt(entry, "'" + entry.keyword() + "' has no value; valid values are: " + joined(valid));
    const io::Token& token = stream.next();
    const std::string value = token.text;
    if ((token.kind != io::Token::Kind::Word && token.kind != io::Token::Kind::String) ||
        std::find(valid.begin(), valid.end(), value) == valid.end())
        failAt(entry, "invalid value '" + value + "' for '" + entry.keyword() + "'; valid values are: " + joined(valid));
    if (!stream.atEnd())
        failAt(entry, "unexpected '" + stream.peek().text + "' after the value of '" + entry.keyword() + "'");
    return value;
}

double readPositiveScalar(const io::Entry& entry)
{
    if (entry.isDictionary()) failAt(entry, "'" + entry.keyword() + "' must be a positive number");
    io::TokenStream stream = entry.stream();
    const double value = stream.readScalar();
    if (!stream.atEnd())
        failAt(entry, "unexpected '" + stream.peek().text + "' after the value of '" + entry.keyword() + "'");
    if (!(value > 0.0) || !std::isfinite(value))
        failAt(entry, "'" + entry.keyword() + "' must be a positive number, got " + entry.valueText());
    return value;
}

// `scaling auto | rigid | similar | μ`: μ ≥ 0 the scale's stiffness (NeighbourhoodScaling.hpp).
// Returns whether it is `auto`; otherwise sets scaling.
bool readScaling(const io::Entry& entry, NeighbourhoodScaling& scaling)
{
    const std::string expected = "'scaling' must be auto, rigid, similar or a number ≥ 0 (the scale's stiffness)";
    if (entry.isDictionary()) failAt(entry, expected);
    io::TokenStream stream = entry.stream();
    if (stream.atEnd()) failAt(entry, expected);
    scaling = NeighbourhoodScaling{};
    bool automatic = false;
    if (stream.peek().kind == io::Token::Kind::Word) {
        const std::string word = stream.readWord();
        if (word == "similar") scaling.stiffness = 0.0;
        else if (word == "auto") automatic = true;
        else if (word != "rigid") failAt(entry, "invalid value '" + word + "': " + expected);
    } else {
        scaling.stiffness = stream.readScalar();
        if (!(scaling.stiffness >= 0.0) || !std::isfinite(scaling.stiffness))
            failAt(entry, expected + ", got " + entry.valueText());
    }
    if (!stream.atEnd()) failAt(entry, "unexpected '" + stream.peek().text + "' after the value of 'scaling'");
    return automatic;
}

int readCount(const io::Entry& entry, int minimum)
{
    if (entry.isDictionary()) failAt(entry, "'" + entry.keyword() + "' must be an integer");
    io::TokenStream stream = entry.stream();
    const Label value = stream.readLabel();
    if (!stream.atEnd())
        failAt(entry, "unexpected '" + stream.peek().text + "' after the value of '" + entry.keyword() + "'");
    if (value < minimum)
        failAt(entry, "'" + entry.keyword() + "' must be at least " + std::to_string(minimum) + ", got " +
                          std::to_string(value));
    return value;
}

StiffeningOptions readStiffening(const io::Entry& entry)
{
    // OpenFOAM's diffusivity syntax (motionDiffusivity::New): [quadratic] inverseDistance (patches),
    // and `power k inverseDistance (patches)`, a wrapper shaped like OpenFOAM's
    // `exponential alpha <diffusivity>` (quadratic is power 2). The exponent comes before the
    // diffusivity, not before the list: `inverseDistance 2 (a b)` would be OpenFOAM's sized list.
    const std::string valid = "auto; none; inverseDistance (patch ...); quadratic inverseDistance (patch ...); "
                              "power k inverseDistance (patch ...); movingAndFixed a b";
    if (entry.isDictionary()) failAt(entry, "'stiffening' must be one of: " + valid);
    io::TokenStream stream = entry.stream();
    if (stream.atEnd()) failAt(entry, "'stiffening' has no value; valid forms are: " + valid);
    StiffeningOptions stiffening;
    stiffening.line = entry.line();
    if (stream.peek().kind != io::Token::Kind::Word)
        failAt(entry, "invalid stiffening '" + stream.peek().text + "'; valid forms are: " + valid);
    std::string word = stream.readWord();
    if (word == "auto" || word == "none" || word == "uniform") {
        if (!stream.atEnd()) failAt(entry, "unexpected '" + stream.peek().text + "' after 'stiffening " + word + "'");
        if (word != "auto") {
            stiffening.exponent = 0.0;
            stiffening.automaticPatches = false;
            stiffening.split.reset();
        }
        return stiffening;
    }
    if (word == "movingAndFixed") {
        // auto's patches, the moving and the fixed ones each with its own exponent.
        SplitStiffeningExponents split;
        for (double* exponent : {&split.moving, &split.fixed}) {
            if (stream.atEnd() || stream.peek().kind != io::Token::Kind::Number)
                failAt(entry, "'stiffening movingAndFixed' needs two exponents, towards the moving and towards the "
                              "fixed patches, e.g. movingAndFixed 0.75 0.2");
            const std::string spelled = stream.peek().text;
            *exponent = stream.readScalar();
            if (!(*exponent >= 0.0) || !(*exponent <= maxStiffeningExponent))
                failAt(entry, "the exponents of 'stiffening movingAndFixed' must be in [0, " +
                                  std::to_string(int(maxStiffeningExponent)) + "], got " + spelled);
        }
        if (!stream.atEnd())
            failAt(entry, "unexpected '" + stream.peek().text + "' after 'stiffening movingAndFixed' and its exponents");
        if (split.moving == 0.0 && split.fixed == 0.0)
            failAt(entry, "'stiffening movingAndFixed 0 0' stiffens nothing; write 'stiffening none;'");
        stiffening.split = split;
        stiffening.splitWritten = true;
        return stiffening;
    }
    stiffening.automaticPatches = false;
    stiffening.split.reset();
    stiffening.exponent = 1.0;
    if (word == "quadratic") {
        stiffening.exponent = 2.0;
        if (stream.atEnd()) failAt(entry, "'stiffening quadratic' needs a diffusivity; valid forms are: " + valid);
        word = stream.readWord();
    } else if (word == "power") {
        if (stream.atEnd() || stream.peek().kind != io::Token::Kind::Number)
            failAt(entry, "'stiffening power' needs an exponent and a diffusivity, e.g. power 0.8 inverseDistance (wall)");
        const std::string spelled = stream.peek().text;
        stiffening.exponent = stream.readScalar();
        if (!(stiffening.exponent > 0.0) || !(stiffening.exponent <= maxStiffeningExponent))
            failAt(entry, "the exponent of 'stiffening power' must be in (0, " + std::to_string(int(maxStiffeningExponent)) +
                              "], got " + spelled);
        if (stream.atEnd() || stream.peek().kind != io::Token::Kind::Word)
            failAt(entry, "'stiffening power " + spelled + "' needs a diffusivity, e.g. power " + spelled +
                              " inverseDistance (wall)");
        word = stream.readWord();
    }
    if (word != "inverseDistance")
        failAt(entry, "invalid stiffening '" + word + "'; valid forms are: " + valid);
    if (stream.atEnd()) failAt(entry, "'stiffening " + word + "' needs a list of patches, e.g. (airfoil)");
    stiffening.patches = stream.readWordList(100000);   // bounded: a huge count is an error, not an allocation
    if (stiffening.patches.empty()) failAt(entry, "'stiffening' lists no patch");
    if (!stream.atEnd()) failAt(entry, "unexpected '" + stream.peek().text + "' after the patch list of 'stiffening'");
    return stiffening;
}

} // namespace

std::string_view couplingName(RbmCoupling coupling)
{
    return coupling == RbmCoupling::coupled ? "coupled" : "decoupled";
}

std::string_view formulationName(RbmFormulation formulation)
{
    return formulation == RbmFormulation::nonlinear ? "nonlinear" : "linearized";
}

std::string_view algorithmName(RbmAlgorithm algorithm)
{
    switch (algorithm) {
    case RbmAlgorithm::newton: return "newton";
    case RbmAlgorithm::localGlobal: return "localGlobal";
    case RbmAlgorithm::reducedNewton: return "reducedNewton";
    }
    return "newton";
}

std::string_view linearSolverName(LinearSolverKind kind)
{
    switch (kind) {
    case LinearSolverKind::automatic: return "automatic";
    case LinearSolverKind::direct: return "direct";
    case LinearSolverKind::iterative: return "iterative";
    case LinearSolverKind::matrixFree: return "matrixFree";
    }
    return "?";
}

std::vector<std::pair<std::string, std::string>> parsePetscOptionString(std::string_view text)
{
    std::vector<std::string> words;
    std::istringstream stream{std::string(text)};
    for (std::string word; stream >> word;) words.push_back(word);
    auto isName = [](const std::string& word) {
        return word.size() >= 2 && word[0] == '-' && std::isalpha(static_cast<unsigned char>(word[1]));
    };
    std::vector<std::pair<std::string, std::string>> options;
    for (const std::string& word : words) {
        if (isName(word)) {
            options.emplace_back(word, "");
        } else if (options.empty()) {
            throw std::invalid_argument("expected an option name such as -ksp_type, found '" + word + "'");
        } else {
            std::string& value = options.back().second;
            value += (value.empty() ? "" : " ") + word;
        }
    }
    return options;
}

const std::vector<std::string_view>& RigidBodyMotionOptions::keywords()
{
    static const std::vector<std::string_view> words{
        "coupling",  "formulation",   "algorithm",         "weighting",     "subSteps",
        "maxSubStepSplits", "maxSubSteps", "tolerance", "relativeTolerance", "displacementTolerance", "maxIterations",
        "linearSolver", "petscOptions", "stiffening", "untangle", "scaling", "transverseStiffness", "floatingPatches"};
    return words;
}

std::string RigidBodyMotionOptions::describe() const
{
    std::ostringstream text;
    text << couplingName(coupling) << ' ' << formulationName(formulation);
    if (coupling == RbmCoupling::coupled && formulation == RbmFormulation::nonlinear)
        text << " (" << algorithmName(algorithm) << ')';
    text << ", weighting " << edgeWeightingName(weighting) << ", subSteps ";
    if (subSteps == 0) text << "auto";
    else text << subSteps;
    if (stiffening.split && *stiffening.split != defaultSplitStiffening) {
        text << ", stiffening movingAndFixed " << stiffening.split->moving << ' ' << stiffening.split->fixed;
    } else if (stiffening.enabled() && stiffening.automaticPatches) {
        text << ", stiffening auto";
    } else if (stiffening.enabled()) {
        text << ", stiffening ";
        if (stiffening.exponent == 2.0) text << "quadratic ";
        else if (stiffening.exponent != 1.0) text << "power " << stiffening.exponent << ' ';
        text << "inverseDistance (";
        for (std::size_t k = 0; k < stiffening.patches.size(); ++k) text << (k ? " " : "") << stiffening.patches[k];
        text << ')';
    }
    if (!untangle) text << ", untangle off";
    if (!automaticScaling) {
        if (scaling.rigid()) text << ", scaling rigid";
        else if (scaling.stiffness == 0.0) text << ", scaling similar";
        else text << ", scaling " << scaling.stiffness;
    }
    if (!automaticTransverseStiffness) {
        if (transverseStiffness > 0.0) text << ", transverseStiffness " << transverseStiffness;
        else text << ", transverseStiffness none";
    }
    return text.str();
}

RigidBodyMotionOptions RigidBodyMotionOptions::read(const io::Dictionary& coefficients)
{
    RigidBodyMotionOptions options;
    options.file = coefficients.file();
    const std::vector<std::string_view>& valid = keywords();
    for (const io::Entry& entry : coefficients.entries()) {
        const std::string& keyword = entry.keyword();
        if (std::find(valid.begin(), valid.end(), keyword) == valid.end())
            failAt(entry, "unknown keyword '" + keyword + "' in " + coefficients.name() +
                              ". Valid keywords are: " + joined(valid));
        if (keyword == "coupling") {
            options.coupling = readChoice(entry, {"coupled", "decoupled"}) == "coupled" ? RbmCoupling::coupled
                                                                                       : RbmCoupling::decoupled;
        } else if (keyword == "formulation") {
            options.formulation = readChoice(entry, {"nonlinear", "linearized"}) == "nonlinear"
                                      ? RbmFormulation::nonlinear
                                      : RbmFormulation::linearized;
        } else if (keyword == "algorithm") {
            const std::string choice = readChoice(entry, {"newton", "localGlobal", "reducedNewton"});
            options.algorithm = choice == "newton"        ? RbmAlgorithm::newton
                                : choice == "localGlobal" ? RbmAlgorithm::localGlobal
                                                          : RbmAlgorithm::reducedNewton;
        } else if (keyword == "weighting") {
            options.weighting =
                edgeWeightingFromName(readChoice(entry, {"uniform", "inverseDistance", "inverseDistanceSquared"}));
        } else if (keyword == "subSteps") {
            if (entry.isDictionary()) failAt(entry, "'subSteps' must be 'auto' or a positive integer");
            io::TokenStream stream = entry.stream();
            if (!stream.atEnd() && stream.peek().kind == io::Token::Kind::Word) {
                const std::string word = stream.readWord();
                if (word != "auto")
                    failAt(entry, "invalid value '" + word + "' for 'subSteps'; valid values are: auto, or a positive integer");
                if (!stream.atEnd()) failAt(entry, "unexpected '" + stream.peek().text + "' after 'subSteps auto'");
                options.subSteps = 0;
            } else {
                options.subSteps = readCount(entry, 1);
            }
        } else if (keyword == "maxSubStepSplits") {
            options.maxSubStepSplits = readCount(entry, 0);
        } else if (keyword == "maxSubSteps") {
            options.maxSubSteps = readCount(entry, 1);
        } else if (keyword == "tolerance") {
            options.tolerance = readPositiveScalar(entry);
        } else if (keyword == "relativeTolerance") {
            options.relativeTolerance = readPositiveScalar(entry);
        } else if (keyword == "displacementTolerance") {
            // 0 switches the displacement test off, so 0 is valid here.
            const bool zero = !entry.isDictionary() && entry.valueText() == "0";
            options.displacementTolerance = zero ? 0.0 : readPositiveScalar(entry);
        } else if (keyword == "maxIterations") {
            options.maxIterations = readCount(entry, 1);
        } else if (keyword == "linearSolver") {
            const std::string kind = readChoice(entry, {"automatic", "direct", "iterative", "matrixFree"});
            options.linearSolver = kind == "automatic"   ? LinearSolverKind::automatic
                                   : kind == "direct"    ? LinearSolverKind::direct
                                   : kind == "iterative" ? LinearSolverKind::iterative
                                                         : LinearSolverKind::matrixFree;
        } else if (keyword == "petscOptions") {
            if (entry.isDictionary()) failAt(entry, "'petscOptions' must be a string, e.g. \"-ksp_type cg\"");
            io::TokenStream stream = entry.stream();
            if (stream.atEnd()) failAt(entry, "'petscOptions' has no value");
            options.petscOptions = stream.readWordOrString();
            if (!stream.atEnd())
                failAt(entry, "'petscOptions' must be one quoted string, e.g. petscOptions \"-ksp_type cg -pc_type gamg\";");
            try {
                options.petscOptionList = parsePetscOptionString(options.petscOptions);
            } catch (const std::invalid_argument& error) {
                failAt(entry, std::string("'petscOptions': ") + error.what());
            }
        } else if (keyword == "stiffening") {
            options.stiffening = readStiffening(entry);
        } else if (keyword == "untangle") {
            options.untangle = readChoice(entry, {"on", "off"}) == "on";
        } else if (keyword == "scaling") {
            options.automaticScaling = readScaling(entry, options.scaling);
            options.scalingLine = entry.line();
        } else if (keyword == "transverseStiffness") {
            const std::string expected = "'transverseStiffness' must be auto, none or a number ≥ 0";
            if (entry.isDictionary()) failAt(entry, expected);
            io::TokenStream stream = entry.stream();
            if (stream.atEnd()) failAt(entry, expected);
            if (stream.peek().kind == io::Token::Kind::Word) {
                const std::string word = stream.readWord();
                if (word != "none" && word != "auto") failAt(entry, "invalid value '" + word + "': " + expected);
                options.automaticTransverseStiffness = word == "auto";
                options.transverseStiffness = 0.0;
            } else {
                options.automaticTransverseStiffness = false;
                options.transverseStiffness = stream.readScalar();
                if (!(options.transverseStiffness >= 0.0) || !std::isfinite(options.transverseStiffness))
                    failAt(entry, expected + ", got " + entry.valueText());
            }
            if (!stream.atEnd())
                failAt(entry, "unexpected '" + stream.peek().text + "' after the value of 'transverseStiffness'");
            options.transverseStiffnessLine = entry.line();
        } else if (keyword == "floatingPatches") {
            io::TokenStream stream = entry.stream();
            if (stream.atEnd()) failAt(entry, "'floatingPatches' needs a list of patches, e.g. (outlet)");
            options.floatingPatches = stream.readWordList(100000);
            if (!stream.atEnd()) failAt(entry, "unexpected '" + stream.peek().text + "' after the patch list of 'floatingPatches'");
            options.floatingPatchesLine = entry.line();
        }
    }
    if (!options.automaticScaling && !options.scaling.rigid() &&
        (options.coupling != RbmCoupling::coupled || options.formulation != RbmFormulation::nonlinear ||
         options.algorithm != RbmAlgorithm::reducedNewton))
        throw InputError(options.file, options.scalingLine,
                         "'scaling' other than rigid needs the default solver (coupling coupled, formulation "
                         "nonlinear, algorithm reducedNewton); the thesis' variants fit rotations only");
    if (options.transverseStiffness > 0.0 &&
        (options.coupling != RbmCoupling::coupled || options.formulation != RbmFormulation::nonlinear ||
         options.algorithm != RbmAlgorithm::reducedNewton))
        throw InputError(options.file, options.transverseStiffnessLine,
                         "'transverseStiffness' needs the default solver (coupling coupled, formulation nonlinear, "
                         "algorithm reducedNewton)");
    return options;
}

} // namespace rbm::motion
