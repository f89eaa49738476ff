#!/usr/bin/env bash
# Where one rbmMoveMesh run's CPU time goes, phase by phase: runs `rbmMoveMesh -case CASE
# -noVTK` once under `perf record` (sampling the CPU clock with call graphs, one thread) and
# prints a markdown table of each phase's share of the samples and its seconds (samples /
# frequency), stamped with the rbm commit, the date and the machine. The phases are the
# functions that do them, counted with their callees (perf's "children"); "solve, other"
# is the rest of the solve (warm start, line search, displacement tests).
#
#   scripts/phaseProfile.sh CASE [RBM_MOVE_MESH]
#
# CASE is used as it is: its `1/` and `postProcessing/` are removed first (a case made by
# `rbmBenchmark --cases twist3D --work-dir DIR --keep` is DIR/twist3D-<size>/rbm-defaults).
# RBM_MOVE_MESH defaults to build/bin/rbmMoveMesh; PHASE_COMMIT names its commit when it is not
# this checkout's HEAD. PERF_FREQUENCY (default 200 Hz) and
# OMP_NUM_THREADS (default 1) are honoured; the perf data stays in PROFILE_DATA (default
# a temporary file, deleted). Needs Debian's linux-perf; perf's software clock event works on
# virtual machines without hardware counters.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
case=${1:?usage: scripts/phaseProfile.sh CASE [RBM_MOVE_MESH]}
program=${2:-$here/build/bin/rbmMoveMesh}
frequency=${PERF_FREQUENCY:-200}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
data=${PROFILE_DATA:-$(mktemp /tmp/phaseProfile.XXXXXX)}
[ -n "${PROFILE_DATA:-}" ] || trap 'rm -f "$data" "$data.old"' EXIT
rm -rf "$case/1" "$case/postProcessing"
# The singleton MPI start of rbmBenchmark's runs (no orted daemon).
OMPI_MCA_ess_singleton_isolated=1 perf record -q -F "$frequency" -e cpu-clock --call-graph dwarf,16384 -o "$data" \
    "$program" -case "$case" -noVTK > "$data.log" 2>&1 || { cat "$data.log"; exit 1; }
source "$here/scripts/profileStamp.sh"
commit=$(profileCommit "$here" "${PHASE_COMMIT:-}")
profileHeading "Phase profile of \`$(basename "$program") -case $case -noVTK\` (OMP_NUM_THREADS=$OMP_NUM_THREADS, perf $frequency Hz):" \
    "rbm $commit, $(date -u +%Y-%m-%d), $(nproc --all) cores ($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')), load average $(cut -d' ' -f1-3 /proc/loadavg)." \
    "$data.log"
echo "| phase | share | CPU s |"
echo "|---|---:|---:|"
# Each sample goes to the innermost function of its call stack that names a phase (the
# stack is printed leaf first), so the phases are disjoint and add up to the whole; a
# V-cycle inside the warm start counts as a V-cycle, and the initial mesh's report is a
# quality check like the moved mesh's.
perf script -i "$data" -F ip,sym 2>/dev/null | awk -v f="$frequency" '
BEGIN {
    n = split("read|setup|stiffening|problem|preconditioner|rnsetup|vcycle|hessian|cg|solve|inverted|quality|write|rest", order, "|")
    name["read"] = "read and topology check"
    name["setup"] = "solver set-up: graph, node classes (without the stiffening)"
    name["stiffening"] = "stiffening distances and factors"
    name["problem"] = "problem (weights, pattern) for the step"
    name["preconditioner"] = "preconditioner set-up (K, its multigrid hierarchy)"
    name["rnsetup"] = "reduced Newton'"'"'s other set-up"
    name["vcycle"] = "V-cycles of K⁻¹ (CG and warm start)"
    name["hessian"] = "Hessian products S v"
    name["cg"] = "CG'"'"'s other work"
    name["solve"] = "solve, other (warm start, fits and energy of the line search, tests)"
    name["inverted"] = "inverted-cell check"
    name["quality"] = "quality checks (the initial and the moved mesh)"
    name["write"] = "write"
    name["rest"] = "the rest (loading, MPI and PETSc start and end, boundary conditions)"
}
function phaseOf(symbol) {
    if (symbol ~ /^rbm::app::MoveMeshRun::readCheckedMesh/) return "read"
    if (symbol ~ /^rbm::motion::EdgeStiffening::EdgeStiffening/) return "stiffening"
    if (symbol ~ /^rbm::motion::RigidBodyMotionSolver::RigidBodyMotionSolver/) return "setup"
    if (symbol ~ /^rbm::motion::RigidBodyMotionSolver::Impl::updateProblem/) return "problem"
    if (symbol ~ /^rbm::motion::LaplacianPreconditioner::LaplacianPreconditioner/) return "preconditioner"
    if (symbol ~ /^rbm::motion::makeRbmSolver/) return "rnsetup"
    if (symbol ~ /^rbm::motion::LaplacianPreconditioner::apply/) return "vcycle"
    if (symbol ~ /^rbm::motion::ReducedHessian3D::apply/) return "hessian"
    if (symbol ~ /^rbm::motion::NewtonCg::direction/) return "cg"
    if (symbol ~ /^rbm::motion::ReducedNewtonSolver::solve/) return "solve"
    if (symbol ~ /^rbm::motion::InvertedCellCounter::count/) return "inverted"
    if (symbol ~ /^rbm::QualityEvaluator::evaluateStep/) return "quality"
    if (symbol ~ /^rbm::app::MoveMeshRun::writeTime/) return "write"
    return ""
}
NF == 0 { if (inSample) { count[phase == "" ? "rest" : phase]++; total++ } inSample = 0; phase = ""; next }
{
    if (!inSample) { inSample = 1; phase = "" }
    if (phase == "") { symbol = $2; phase = phaseOf(symbol) }
}
END {
    if (inSample) { count[phase == "" ? "rest" : phase]++; total++ }
    for (k = 1; k <= n; ++k)
        printf "| %s | %.1f %% | %.2f |\n", name[order[k]], 100 * count[order[k]] / total, count[order[k]] / f
    printf "| **whole process** (samples / frequency) | 100 %% | %.2f |\n", total / f
}'
rm -f "$data.log"
