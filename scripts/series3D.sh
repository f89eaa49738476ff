#!/usr/bin/env bash
# The cost of a further time step of a 3D series, rbm beside OpenFOAM's moveMesh, as whole
# processes: the hexahedral cube of rbmBenchmark's twist3D case with its top turning about the
# vertical axis (rotatingMotion, 30°/s), 20 steps of 0.05 s (1.5° each, 30° at the end), both
# writing at the end only. Each program runs the 1-step and the 20-step case, alternately, REPEATS
# times; a further step = (CPU of 20 steps − CPU of 1 step) / 19, from the medians (user + system
# time, one thread each: OMP_NUM_THREADS=1). Prints a Markdown table stamped with the commit, the
# date and the machine's load, with rbm's step lines (iterations, worst quality, inverted cells)
# and OpenFOAM's checkMesh of its last mesh.
#
#   scripts/series3D.sh [--size CELLS] [--repeats N] [--work-dir DIR] > series.md
#
# CELLS (default 1.25e5) is rbmBenchmark's --sizes value; the cases come from `rbmBenchmark
# --cases twist3D --keep` (rbm's case with its defaults and `floatingPatches (sides)`, OpenFOAM's
# with displacementLaplacian, quadratic inverseDistance and GAMG). Needs build/bin/rbmBenchmark,
# build/bin/rbmMoveMesh and OpenFOAM v1912 (moveMesh, checkMesh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/scripts/profileStamp.sh"
size=1.25e5
repeats=3
work=$(mktemp -d /tmp/series3D.XXXXXX)
while [[ $# -gt 0 ]]; do
  case $1 in
    --size) size=$2; shift 2 ;;
    --repeats) repeats=$2; shift 2 ;;
    --work-dir) work=$2; mkdir -p "$work"; shift 2 ;;
    *) echo "series3D.sh: unknown argument $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
bashrc=/usr/share/openfoam/etc/bashrc
[ -x /usr/bin/moveMesh ] && [ -f "$bashrc" ] || { echo "series3D.sh: needs OpenFOAM v1912 (moveMesh)" >&2; exit 2; }
export OMP_NUM_THREADS=1 OMPI_MCA_ess_singleton_isolated=1
loadBefore=$(cut -d' ' -f1-3 /proc/loadavg)

OMP_NUM_THREADS=1 "$root/build/bin/rbmBenchmark" --sizes "$size" --cases twist3D --variants reducedNewton \
    --pitching-steps 0 --whole-process auto --work-dir "$work/cases" --keep > "$work/rbmBenchmark.log" 2>&1 ||
    { echo "series3D.sh: rbmBenchmark failed, see $work/rbmBenchmark.log" >&2; exit 1; }
source=$(ls -d "$work"/cases/twist3D-*/ | head -1); source=${source%/}
[ -d "$source/rbm-defaults" ] && [ -d "$source/openfoam" ] || { echo "series3D.sh: no cases under $source" >&2; exit 1; }

# prepare DIR FROM STEPS: a copy of FROM running STEPS steps of 0.05 s, writing at the last one.
prepare() {
  rm -rf "$1"; cp -r "$2" "$1"; rm -rf "$1"/1 "$1"/postProcessing "$1"/log*
  local end; end=$(awk -v s="$3" 'BEGIN { printf "%g", 0.05 * s }')
  sed -i "s/^deltaT .*/deltaT 0.05;/; s/^endTime .*/endTime $end;/; s/^writeInterval .*/writeInterval $3;/" \
      "$1/system/controlDict"
}
# openfoam COMMAND: COMMAND in a shell with OpenFOAM's environment (its bashrc does not run under set -eu).
openfoam() { bash -c ". $bashrc > /dev/null 2>&1; $1"; }
# cpuOf FILE: user + system seconds from /usr/bin/time's "%U %S".
cpuOf() { awk '{ printf "%.3f", $1 + $2 }' "$1"; }
declare -A times
for ((r = 1; r <= repeats; ++r)); do
  for steps in 1 20; do
    prepare "$work/openfoam$steps" "$source/openfoam" "$steps"
    (cd "$work/openfoam$steps" && openfoam "/usr/bin/time -f '%U %S' -o time.txt /usr/bin/moveMesh -case . > log.moveMesh 2>&1") ||
      { echo "series3D.sh: moveMesh failed in $work/openfoam$steps" >&2; exit 1; }
    times[openfoam$steps]+="$(cpuOf "$work/openfoam$steps/time.txt") "
    prepare "$work/rbm$steps" "$source/rbm-defaults" "$steps"
    (cd "$work/rbm$steps" && /usr/bin/time -f "%U %S" -o time.txt "$root/build/bin/rbmMoveMesh" -case . -noVTK \
       > log.rbmMoveMesh 2>&1) || { echo "series3D.sh: rbmMoveMesh failed in $work/rbm$steps" >&2; exit 1; }
    times[rbm$steps]+="$(cpuOf "$work/rbm$steps/time.txt") "
  done
done
median() { tr ' ' '\n' <<< "$1" | grep . | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
further() { awk -v a="$(median "$1")" -v b="$(median "$2")" 'BEGIN { printf "%.3f", (b - a) / 19 }'; }
rbmStep=$(further "${times[rbm1]}" "${times[rbm20]}")
openfoamStep=$(further "${times[openfoam1]}" "${times[openfoam20]}")
(cd "$work/openfoam20" && openfoam "checkMesh -case . -time 1 > log.checkMesh 2>&1") || true
openfoamNonOrth=$(grep -o "Mesh non-orthogonality Max: [0-9.e+-]*" "$work/openfoam20/log.checkMesh" | awk '{ printf "%.1f", $4 }')
openfoamInvalid=$(grep -c "\*\*\*" "$work/openfoam20/log.checkMesh" || true)
lastStep=$(grep -E '^Time = 1 ' "$work/rbm20/log.rbmMoveMesh" | tr -s ' ')
iterations=$(grep -E '^Time = ' "$work/rbm20/log.rbmMoveMesh" | awk '{ for (i = 1; i < NF; ++i) if ($i == "iterations") s += $(i + 1) } END { print s }')
mesh=$(grep -E '^Mesh +:' "$work/rbm20/log.rbmMoveMesh" | sed 's/^Mesh *: //')

echo "3D series, a further step: rbm beside OpenFOAM's moveMesh (\`scripts/series3D.sh --size $size --repeats $repeats\`)"
echo "rbm $(profileCommit "$root"), $(date +%F); $(nproc --all) cores, load average $loadBefore at the start and $(cut -d' ' -f1-3 /proc/loadavg) at the end; one thread each."
echo
echo "The twist3D cube ($mesh), its top turning 1.5° a step for 20 steps (30° at the end), both programs writing at the end only. CPU seconds (user + system) of whole processes, medians of $repeats alternating runs; a further step = (20 steps − 1 step) / 19."
echo
echo "| program | 1 step: CPU s (runs) | 20 steps: CPU s (runs) | a further step, CPU s | ratio to OpenFOAM | last mesh |"
echo "|---|---:|---:|---:|---:|---|"
echo "| rbmMoveMesh (defaults) | $(median "${times[rbm1]}") (${times[rbm1]% }) | $(median "${times[rbm20]}") (${times[rbm20]% }) | **$rbmStep** | $(awk -v a="$rbmStep" -v b="$openfoamStep" 'BEGIN { printf "%.2f", a / b }')× | $iterations Newton and subspace steps in all; last step: \`$lastStep\` |"
echo "| moveMesh (displacementLaplacian) | $(median "${times[openfoam1]}") (${times[openfoam1]% }) | $(median "${times[openfoam20]}") (${times[openfoam20]% }) | **$openfoamStep** | 1 | checkMesh at time 1: max non-orthogonality ${openfoamNonOrth:-?}°, $openfoamInvalid failed checks |"
