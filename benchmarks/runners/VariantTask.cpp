#include "VariantTask.hpp"

#include "CaseProblem.hpp"
#include "MeshIoTask.hpp"
#include "PetscSupport.hpp"
#include "PhaseTimer.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "Process.hpp"
#include "QualityFields.hpp"
#include "StepAssessment.hpp"
#include "Variants.hpp"

#include <algorithm>
#include <iomanip>
#include <memory>
#include <sstream>

namespace rbm::benchmark {

Record runVariantTask(const std::string& caseName, const std::string& variant, const fs::path& meshCase,
                      double memoryLimitBytes)
{
    Record record;
    record.set("task", "variant");
    record.set("case", caseName);
    record.set("variant", variant);
    PhaseTimer petscTimer(record, "petscInit");
    const motion::PetscSession petsc;
    petscTimer.stop();

    PhaseTimer readTimer(record, "read");
    const PolyMesh mesh = io::readPolyMesh(meshCase / "constant" / "polyMesh");
    readTimer.stop();
    record.set("points", mesh.pointCount());
    record.set("cells", mesh.cellCount());
    record.set("meshMemoryMiB", procStatusMiB("VmRSS"));

    CaseProblem caseProblem;
    PhaseTimer graphTimer(record, "graph");
    buildGraph(mesh, caseProblem);
    graphTimer.stop();

    PhaseTimer problemTimer(record, "problem");
    buildConstraints(mesh, caseName, caseProblem);
    auto problem = std::make_unique<motion::RbmProblem>(caseProblem.dimension, caseProblem.reference, caseProblem.graph,
                                                        caseProblem.constraints);
    problemTimer.stop();
    record.set("dimension", caseProblem.dimension);
    record.set("nodes", problem->nodeCount());
    record.set("unknownNodes", problem->unknownNodeCount());
    record.set("unknowns", problem->unknownCount());
    record.set("graphEdges", problem->graph().edgeCount());
    record.set("peakAfterProblemMiB", procStatusMiB("VmHWM"));
    const double estimate = estimatedMatrixBytes(variant, *problem);
    record.set("estimatedMatrixGiB", estimate / 1073741824.0);
    if (estimate > memoryLimitBytes) {
        record.setFlag("skipped", true);
        std::ostringstream reason;
        reason << "estimated matrix memory " << std::setprecision(3) << estimate / 1073741824.0 << " GiB > limit "
               << memoryLimitBytes / 1073741824.0 << " GiB";
        record.set("skipReason", reason.str());
        record.set("peakMemoryMiB", procStatusMiB("VmHWM"));
        return record;
    }

    PhaseTimer assembleTimer(record, "assemble");
    std::unique_ptr<motion::RbmSolver> solver = makeSolver(variant, *problem);
    assembleTimer.stop();
    record.set("peakAfterAssemblyMiB", procStatusMiB("VmHWM"));

    PhaseTimer firstTimer(record, "firstSolve");
    const motion::RbmResult result = solver->solve(caseProblem.prescribed);
    firstTimer.stop();
    record.set("iterations", result.iterations);
    record.set("linearIterations", result.linearIterations);
    record.setFlag("converged", result.converged);
    record.set("reason", result.reason);
    record.set("energy", result.energy);
    record.set("residualNorm", result.residualNorm);
    record.set("peakAfterSolveMiB", procStatusMiB("VmHWM"));

    // The same step again with the matrices kept (a further time step of a linear variant). A
    // nonlinear variant repeats all its iterations; after a long first solve that is left out.
    const bool linear = variant == "linearized" || variant == "decoupledLinearized" ||
                        variant == "linearizedAssembled" || variant == "linearizedMatrixFree";
    if (linear || record.number("firstSolveSeconds") < 30.0) {
        PhaseTimer repeatTimer(record, "repeatSolve");
        const motion::RbmResult again = solver->solve(caseProblem.prescribed);
        repeatTimer.stop();
        record.set("repeatIterations", again.iterations);
        record.set("repeatLinearIterations", again.linearIterations);
        record.set("setupSeconds",
                   std::max(0.0, record.number("firstSolveSeconds") - record.number("repeatSolveSeconds")));
        record.set("setupCpuSeconds",
                   std::max(0.0, record.number("firstSolveCpuSeconds") - record.number("repeatSolveCpuSeconds")));
    }

    // What rbmMoveMesh does after a solve: its step check (StepAssessor: set-up, then the log
    // line's figures). The quality columns of the report come from the full report, untimed.
    PhaseTimer qualitySetupTimer(record, "qualitySetup");
    const std::vector<Vector3> points = movedPoints(mesh, caseProblem, result.displacement);
    motion::StepAssessor assessor(mesh);
    qualitySetupTimer.stop();
    PhaseTimer qualityEvaluateTimer(record, "qualityEvaluate");
    const StepQuality stepQuality = assessor.evaluateStep(points);
    qualityEvaluateTimer.stop();
    for (const std::string suffix : {"Seconds", "CpuSeconds"})
        record.set("quality" + suffix, record.number("qualitySetup" + suffix) + record.number("qualityEvaluate" + suffix));
    const QualityReport quality = assessor.evaluate(points);
    if (quality.invertedCellCount() != stepQuality.invertedCellCount)
        throw std::logic_error("the step check and the full report count different inverted cells");
    addQuality(record, quality, "");

    const fs::path output = meshCase / ("benchmark-" + variant);
    PhaseTimer writeTimer(record, "write");
    io::writePolyMeshPoints(output, "1", points, writeOptions("binaryGzip"));
    writeTimer.stop();
    fs::remove_all(output);

    for (const std::string suffix : {"Seconds", "CpuSeconds"}) {
        const double compute = record.number("graph" + suffix) + record.number("problem" + suffix) +
                               record.number("assemble" + suffix) + record.number("firstSolve" + suffix);
        record.set("stepCompute" + suffix, compute);
        record.set("stepTotal" + suffix, record.number("read" + suffix) + compute + record.number("quality" + suffix) +
                                             record.number("write" + suffix));
    }
    record.set("peakMemoryMiB", procStatusMiB("VmHWM"));
    return record;
}

} // namespace rbm::benchmark
