#!/usr/bin/env bash
# What is alive at one rbmMoveMesh run's memory peak, item by item: runs `rbmMoveMesh -case
# CASE -noVTK` once under valgrind's massif (heap profile) and prints a markdown table of the
# heap at the peak by item, in MiB, bytes per mesh point and MiB extrapolated to the
# 10⁶-cell cube (1 030 301 points; every item grows with the points), stamped with the rbm
# commit, the date, the phase of the peak and the process's own peak (VmHWM, heap plus code
# and libraries, which massif does not count).
#
#   scripts/memoryProfile.sh CASE [RBM_MOVE_MESH]
#
# CASE is used as it is: its `1/` and `postProcessing/` are removed first (a case made by
# `rbmBenchmark --cases twist3D --work-dir DIR --keep` is DIR/twist3D-<size>/rbm-defaults; the
# 1.25·10⁵-cell cube takes about two minutes under massif). RBM_MOVE_MESH defaults to
# build/bin/rbmMoveMesh; MEMORY_COMMIT names its commit when it is not this checkout's HEAD.
# OMP_NUM_THREADS (default 1) is honoured; massif's output stays in PROFILE_DATA (default a
# temporary file, deleted). Needs Debian's valgrind.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
case=${1:?usage: scripts/memoryProfile.sh CASE [RBM_MOVE_MESH]}
program=${2:-$here/build/bin/rbmMoveMesh}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
data=${PROFILE_DATA:-$(mktemp /tmp/memoryProfile.XXXXXX)}
[ -n "${PROFILE_DATA:-}" ] || trap 'rm -f "$data" "$data.log"' EXIT
# The process's own peak, from a run without valgrind.
rm -rf "$case/1" "$case/postProcessing"
OMPI_MCA_ess_singleton_isolated=1 /usr/bin/time -f '%M' -o "$data.log" "$program" -case "$case" -noVTK > /dev/null 2>&1 ||
    { echo "rbmMoveMesh failed" >&2; exit 1; }
maxRssKiB=$(tail -1 "$data.log")
rm -rf "$case/1" "$case/postProcessing"
OMPI_MCA_ess_singleton_isolated=1 valgrind --tool=massif --massif-out-file="$data" --threshold=0.2 --depth=40 \
    "$program" -case "$case" -noVTK > "$data.log" 2>&1 || { cat "$data.log"; exit 1; }
points=$(sed -n 's/^Mesh *: \([0-9]*\) points.*/\1/p' "$data.log" | head -1)
source "$here/scripts/profileStamp.sh"
commit=$(profileCommit "$here" "${MEMORY_COMMIT:-}")
profileHeading "Memory profile of \`$(basename "$program") -case $case -noVTK\` (OMP_NUM_THREADS=$OMP_NUM_THREADS, valgrind massif):" \
    "rbm $commit, $(date -u +%Y-%m-%d), $points points; whole process without valgrind: peak $((maxRssKiB / 1024)) MiB (VmHWM)." \
    "$data.log"
# The peak snapshot's heap tree by item (scripts/massifPeakItems.awk): each leaf goes to the item
# of the first frame, from the allocation outwards, that itemOf names.
items='function itemOf(frame) {
    if (frame ~ /ReducedHessian3D|ReducedEnergy::ReducedEnergy|PlanarReducedKernels/) return "reduced Hessian and energy: per-node data (ReducedHessian3D)"
    if (frame ~ /ThreeVectorMultigrid|buildSmoothedAggregation|SmoothedAggregation/) return "K'"'"'s multigrid: finest values in single precision, transfers, coarse levels, cycle vectors"
    if (frame ~ /coupledDisplacementLaplacian/) return "K in double precision (LaplacianPreconditioner)"
    if (frame ~ /computeEdgeWeights/) return "edge weights w_ij (RbmProblem)"
    if (frame ~ /stiffeningFactors/) return "stiffening factors f_ij (EdgeStiffening, shared with the problem)"
    if (frame ~ /RbmProblem::buildBlockPattern|RbmProblem::edgeBlock|RbmProblem::edgeTransposeBlock/) return "block pattern of K (columns; per-edge positions where built)"
    if (frame ~ /buildCellNeighbourGraph/) return "cell-neighbour graph"
    if (frame ~ /classifyNodes|NodeClasses/) return "node classes (RbmProblem constraints)"
    if (frame ~ /fitNodeRotations/) return "rotations R_i (iterate, line-search trial)"
    if (frame ~ /NewtonCg::/) return "Newton-CG vectors (CG, step, trial point)"
    if (frame ~ /WarmStart::|TurnedStart|HarmonicChangeBasis/) return "warm start (results kept, predictor, start candidates)"
    if (frame ~ /ReducedNewtonSolver::|CompactUnknowns|RelativeDisplacement/) return "reduced Newton'"'"'s other vectors (iterate, gradient, displacement test, result)"
    if (frame ~ /buildMeshTopology/) return "mesh topology (cells'"'"' points, points'"'"' cells)"
    if (frame ~ /readLabelList|readFaceCompactList/) return "mesh faces, owner, neighbour"
    if (frame ~ /InvertedCellCounter/) return "inverted-cell check"
    if (frame ~ /computeFaceCentres|computeCellCentres|CheckMesh|Quality|StepAssessor|MeshGeometry/) return "quality check (face and cell geometry)"
    if (frame ~ /rbm::io::write|appendVectorList|writeTime|Gzip|deflate/) return "output (points file)"
    if (frame ~ /BoundaryPath|RigidBodyMotionSolver|MotionSolver|readVectorList|readPointVectorField|MoveMeshRun|PointPatch/) return "point arrays: mesh points, points0, displacement, target, state"
    return ""
}
'
awk -v points="$points" -v scaleTo=1030301 -v other="other (below massif's threshold, libraries, MPI and PETSc)" \
    -f <(printf '%s\n' "$items") -f "$here/scripts/massifPeakItems.awk" "$data"
