#!/usr/bin/env bash
# What is alive at each rank's memory peak of a decomposed `rbmMoveMesh -parallel` run, item by
# item: runs `mpirun -np RANKS rbmMoveMesh -case CASE -parallel -noVTK` once without valgrind
# (each rank's own peak, VmHWM, through /usr/bin/time) and once with every rank under valgrind's
# massif, and prints, per rank, a markdown table of the heap at that rank's peak by item, in MiB
# and bytes per point of the rank's processor mesh, stamped with the rbm commit and the date.
# The model is scripts/memoryProfile.sh (one serial run); the items here add PETSc's matrices
# of the part's Laplacian K (PartLaplacian), its multigrid cycle and their GAMG hierarchy.
#
#   scripts/memoryProfileDecomposed.sh CASE RANKS [RBM_MOVE_MESH]
#
# CASE is a decomposed case with RANKS processor folders, used as it is: its processor*/1 and
# postProcessing/ are removed first (`rbmBenchmark --cases twist3D --ranks N --work-dir DIR --keep`
# leaves DIR/twist3D-<size>/np<N>/rbm; the 10⁴-cell cube on 2 ranks takes a few minutes under
# massif). RBM_MOVE_MESH defaults to build/bin/rbmMoveMesh; MEMORY_COMMIT names its commit when it
# is not this checkout's HEAD. OMP_NUM_THREADS (default 1) is honoured; massif's output stays in
# PROFILE_DATA (default a temporary folder, deleted). Needs Debian's valgrind and Open MPI.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
case=${1:?usage: scripts/memoryProfileDecomposed.sh CASE RANKS [RBM_MOVE_MESH]}
ranks=${2:?usage: scripts/memoryProfileDecomposed.sh CASE RANKS [RBM_MOVE_MESH]}
program=${3:-$here/build/bin/rbmMoveMesh}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
data=${PROFILE_DATA:-$(mktemp -d /tmp/memoryProfileDecomposed.XXXXXX)}
[ -n "${PROFILE_DATA:-}" ] || trap 'rm -rf "$data"' EXIT
mkdir -p "$data"
mpirun=(mpirun --oversubscribe -np "$ranks")
[ "$(id -u)" != 0 ] || mpirun+=(--allow-run-as-root)
clean() { rm -rf "$case"/processor*/1 "$case/postProcessing"; }
# Each rank's own peak, from a run without valgrind.
clean
"${mpirun[@]}" sh -c 'exec /usr/bin/time -f %M -o "$0.$OMPI_COMM_WORLD_RANK" "$@"' "$data/maxrss" \
    "$program" -case "$case" -parallel -noVTK > "$data/plain.log" 2>&1 || { cat "$data/plain.log"; exit 1; }
clean
"${mpirun[@]}" valgrind --tool=massif --massif-out-file="$data/massif.%q{OMPI_COMM_WORLD_RANK}" --threshold=0.2 \
    --depth=40 "$program" -case "$case" -parallel -noVTK > "$data/massif.log" 2>&1 || { cat "$data/massif.log"; exit 1; }
source "$here/scripts/profileStamp.sh"
commit=$(profileCommit "$here" "${MEMORY_COMMIT:-}")
profileHeading "Memory profile of \`mpirun -np $ranks $(basename "$program") -case $case -parallel -noVTK\` (OMP_NUM_THREADS=$OMP_NUM_THREADS, valgrind massif on every rank):" \
    "rbm $commit, $(date -u +%Y-%m-%d)." "$data/massif.log"
# The items of a rank's heap at its peak (scripts/massifPeakItems.awk): each leaf goes to the item of
# the first frame, from the allocation outwards, that itemOf names.
items='function itemOf(frame) {
    if (frame ~ /PartLaplacian::assemble/) return "the scalar K as a PETSc MPIAIJ matrix (PartLaplacian::assemble)"
    if (frame ~ /PartThreeVectorCycle::PartThreeVectorCycle|galerkinOperator|distributedSmoothedProlongator/) return "the parts'"'"' cycle: P and its set-up'"'"'s products KT, PᵀKP (DistributedAggregation)"
    if (frame ~ /SinglePrecisionPartLaplacian/) return "K in single precision, the cycle'"'"'s fine level (SinglePrecisionPartLaplacian)"
    if (frame ~ /PCSetUp_GAMG|PCGAMG|MatCoarsen/) return "PETSc GAMG hierarchy of that matrix (PCSetUp_GAMG: coarsening graph, prolongators, Galerkin products)"
    if (frame ~ /KSPSetUp|KSPSolve|PCSetUp|PCApply|VecDuplicate|KSPCreateVecs/) return "other PETSc solver work (vectors, smoothers)"
    if (frame ~ /ReducedHessian3D|ReducedEnergy::ReducedEnergy|PlanarReducedKernels/) return "reduced Hessian and energy: per-node data (ReducedHessian3D)"
    if (frame ~ /coupledDisplacementLaplacian/) return "K in rbm'"'"'s own arrays (coupledDisplacementLaplacian, before PETSc)"
    if (frame ~ /computeEdgeWeights/) return "edge weights w_ij (RbmProblem)"
    if (frame ~ /stiffeningFactors|EdgeStiffening|Stiffening/) return "stiffening distances and factors"
    if (frame ~ /RbmProblem::|rebuildProblem/) return "RbmProblem: block pattern, constraints"
    if (frame ~ /buildCellNeighbourGraph/) return "cell-neighbour graph of the part"
    if (frame ~ /MeshPart|localCellsOf|PointOwnership|LocalCells/) return "MeshPart: halo cells, node lists, ownership"
    if (frame ~ /NodeExchange|PetscSF/) return "NodeExchange: star forests"
    if (frame ~ /classifyNodes|NodeClasses|partBoundaryDescription|PartBoundary|UnconstrainedPatches/) return "node classes, the part'"'"'s boundary"
    if (frame ~ /fitNodeRotations/) return "rotations R_i"
    if (frame ~ /NewtonCg::/) return "Newton-CG vectors"
    if (frame ~ /WarmStart::|TurnedStart|HarmonicChangeBasis/) return "warm start"
    if (frame ~ /ReducedNewtonSolver::|CompactUnknowns|RelativeDisplacement/) return "reduced Newton'"'"'s other vectors"
    if (frame ~ /PartQuality|QualityEvaluator|StepAssessor|CheckMesh|MeshGeometry|InvertedCellCounter|buildMeshTopology/) return "quality check (PartQuality), topology"
    if (frame ~ /readLabelList|readFaceCompactList|readPolyMesh|readProcessorMesh|readVectorList|readPointVectorField/) return "processor mesh and fields as read"
    if (frame ~ /rbm::io::write|appendVectorList|writeTime|Gzip|deflate/) return "output (points file)"
    if (frame ~ /opal_|ompi_|mca_|pmix|PMIx/) return "Open MPI"
    if (match(frame, /rbm::[A-Za-z_:]+/)) return "other rbm (" substr(frame, RSTART, RLENGTH) ")"
    return ""
}
'
for ((rank = 0; rank < ranks; ++rank)); do
    # The rank's points: the count line at the head of its processor mesh's points file.
    points=$( (zcat -f "$case/processor$rank/constant/polyMesh/"points* || true) | head -c 4096 | grep -a -m1 -E '^[0-9]+$')
    echo "Rank $rank: $points points in processor$rank; whole process without valgrind: peak $(( $(tail -1 "$data/maxrss.$rank") / 1024 )) MiB (VmHWM)."
    echo
    awk -v points="$points" -f <(printf '%s\n' "$items") -f "$here/scripts/massifPeakItems.awk" "$data/massif.$rank"
    echo
done
