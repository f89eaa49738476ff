#pragma once
// The log of a time-stepped mesh-motion run (rbmMoveMesh): one readable line per time step
// on standard output, and the same figures as one JSON object per line ("JSON lines") in
// postProcessing/rbmMoveMesh/<startTime>/log.jsonl, for scripts and plots.
//
// Readable line (fixed columns; the time name is padded to `timeNameWidth`):
//
//   Time = 0.025     sub-steps  1  iterations    3  residual 2.10e-10  worst quality  0.3100  max non-orthogonality  28.40  inverted 0  wall   0.120 s
//
// followed, when they apply, by "  NOT CONVERGED (<reason>)", "  INVALID" (inverted cells)
// and "  written" (the step was written to its time folder).
//
// JSON line (keys in this order; non-finite numbers as null, numbers in the shortest form
// that reads back to the same double):
//
//   {"step":1,"time":0.025,"timeName":"0.025","subSteps":1,"iterations":3,"residual":2.1e-10,
//    "energy":0.5,"converged":true,"reason":"CONVERGED_RTOL","worstQuality":0.31,
//    "maxNonOrthogonality":28.4,"maxSkewness":0.8,"invertedCells":0,"wallSeconds":0.12,
//    "written":true}
//
// This file only formats and writes: the figures come from the motion solver and the
// quality evaluation (rbm_app's MoveMeshRun).

#include <filesystem>
#include <limits>
#include <string>
#include <string_view>

namespace rbm::io {

// The figures of one time step.
struct StepLogRecord {
    int step = 0;                  // 1 for the first step of the run
    double time = 0.0;
    std::string timeName;          // the time folder name of `time`
    int subSteps = 0;
    int iterations = 0;            // summed over sub-steps
    double residual = 0.0;         // final residual of the last sub-step
    double energy = 0.0;           // RBM energy of the result
    bool converged = false;
    std::string reason;            // the solver's converged / diverged reason
    double worstQuality = std::numeric_limits<double>::quiet_NaN();  // smallest cell quality
    double maxNonOrthogonality = 0.0;   // degrees, checkMesh's definition
    double maxSkewness = 0.0;           // checkMesh's definition
    long long invertedCells = 0;
    double wallSeconds = 0.0;      // solve + quality evaluation + writing of this step
    bool written = false;          // written to its time folder
};

// The readable line (no trailing newline): "Time = <name>  " and formatStepFigures.
std::string formatStepLogLine(const StepLogRecord& record, int timeNameWidth = 8);

// The step's figures without the time: "sub-steps  1  iterations    2  residual ... wall ... s"
// and the verdict words. Inside a host that prints its own "Time = " line (OpenFOAM), rbm's
// line starts with its solver's name instead, so that log parsers count each step once.
std::string formatStepFigures(const StepLogRecord& record);

// The JSON object of a step, on one line (no trailing newline).
std::string stepLogJson(const StepLogRecord& record);

// JSON helpers: a number in its shortest round-trip form ("null" when not finite), and a
// string in double quotes with JSON's escapes.
std::string jsonNumber(double value);
std::string jsonString(std::string_view text);

// Appends JSON lines to a file, one object per line, each written with one write() call
// (no buffer) so that an interrupted run keeps every step it logged, and a failure names
// the OS reason.
class JsonLinesWriter {
public:
    JsonLinesWriter() = default;
    // Creates the folders; `truncate` starts the file anew, otherwise lines are appended.
    // Throws std::runtime_error naming the file (or folder) and the OS reason when it cannot
    // be opened.
    JsonLinesWriter(const std::filesystem::path& file, bool truncate);
    ~JsonLinesWriter();
    JsonLinesWriter(JsonLinesWriter&& other) noexcept;
    JsonLinesWriter& operator=(JsonLinesWriter&& other) noexcept;

    bool isOpen() const { return fd_ >= 0; }
    const std::filesystem::path& file() const { return file_; }
    // Writes `jsonObject` and a newline. Throws std::runtime_error naming the file and the OS
    // reason when writing fails; the file then ends after the previous line.
    void append(std::string_view jsonObject);

private:
    std::filesystem::path file_;
    int fd_ = -1;
};

} // namespace rbm::io
