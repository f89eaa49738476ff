#!/usr/bin/env bash
# Regenerates the run figures the tutorial READMEs quote: runs build/bin/rbmMoveMesh on a
# copy of each tutorial's inputs (0/, constant/, system/; never a tutorial folder itself) and
# prints one Markdown table with the date, the commit and the machine they were measured on.
#
#   scripts/tutorialFigures.sh > tutorials/figures.md   # every tutorial (2-3 min), the file the READMEs cite
#   scripts/tutorialFigures.sh cube wingBending          # some of them
#   RBM_BIN=/other/build/bin OMP_NUM_THREADS=1 scripts/tutorialFigures.sh
#
# Columns, from the run's postProcessing/rbmMoveMesh/<start>/log.jsonl and its exit status:
# steps run, sub-steps and iterations (summed over the steps), the largest final residual,
# the largest max non-orthogonality and max skewness of any step (checkMesh's definitions),
# the most inverted cells in one step, the wall seconds of the steps (solve, quality check
# and writing, as the log's `wall` column) and of the whole process (reading the case,
# PETSc's start, VTK output included), and the process's CPU seconds (user + system, all
# threads). Wall times depend on the machine and its load, CPU seconds less so: the header
# line gives both, and OMP_NUM_THREADS (unset: every core; on a loaded machine 1 is faster,
# docs/rbmMoveMesh.md "Threads").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${RBM_BIN:-$root/build/bin}
if [[ ! -x $bin/rbmMoveMesh ]]; then
  echo "tutorialFigures.sh: $bin/rbmMoveMesh not found; build rbm (scripts/setup.sh) or set RBM_BIN" >&2
  exit 2
fi
tutorials=("$@")
if [[ ${#tutorials[@]} -eq 0 ]]; then
  tutorials=(naca4415 naca4415Pitching squares/rotating squares/translated squares/freeOuterBoundary cube wingBending)
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
if [[ -n $(git -C "$root" status --porcelain --untracked-files=no 2>/dev/null) ]]; then commit="$commit+changes"; fi
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
echo "# Tutorial figures"
echo
echo "Written by \`scripts/tutorialFigures.sh\` (do not edit by hand: run it again). One run of \`rbmMoveMesh\` on a copy of each tutorial's inputs, with VTK output."
echo
echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC'), commit $commit, ${cpu:-unknown CPU} ($(getconf _NPROCESSORS_ONLN) cores), load average $(cut -d ' ' -f 1-3 /proc/loadavg) before the runs; OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset}"
echo
echo "| tutorial | exit | steps | sub-steps | iterations | largest residual | max non-orthogonality | max skewness | inverted | steps' wall s | process wall s | process CPU s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for tutorial in "${tutorials[@]}"; do
  source=$root/tutorials/$tutorial
  if [[ ! -f $source/system/controlDict ]]; then
    echo "tutorialFigures.sh: tutorials/$tutorial is not a case" >&2
    exit 2
  fi
  case=$work/$(basename "$tutorial")
  rm -rf "$case"
  mkdir -p "$case"
  cp -r "$source/0" "$source/constant" "$source/system" "$case/"
  status=0
  # bash's own timing: wall, user and system seconds of the process, without /usr/bin/time.
  TIMEFORMAT='%R %U %S'
  { time "$bin/rbmMoveMesh" -case "$case" > "$case.log" 2>&1 || status=$?; } 2> "$case.time"
  read -r processWall user system < "$case.time"
  log=$(ls "$case"/postProcessing/rbmMoveMesh/*/log.jsonl 2>/dev/null | head -n 1 || true)
  # The log's objects are flat: "key":value pairs split on commas.
  awk -v tutorial="$tutorial" -v status="$status" -v processWall="$processWall" -v cpu="$(echo "$user $system" | awk '{ print $1 + $2 }')" '
    function value(key,    pattern, found) {
      pattern = "\"" key "\":[^,}]*"
      if (match($0, pattern) == 0) return ""
      found = substr($0, RSTART + length(key) + 3, RLENGTH - length(key) - 3)
      return found
    }
    BEGIN { steps = 0; subSteps = 0; iterations = 0; residual = 0; nonOrtho = 0; skew = 0; inverted = 0; wall = 0 }
    {
      steps++
      subSteps += value("subSteps"); iterations += value("iterations"); wall += value("wallSeconds")
      r = value("residual"); if (r != "null" && r + 0 > residual) residual = r + 0
      n = value("maxNonOrthogonality"); if (n != "null" && n + 0 > nonOrtho) nonOrtho = n + 0
      s = value("maxSkewness"); if (s != "null" && s + 0 > skew) skew = s + 0
      i = value("invertedCells"); if (i + 0 > inverted) inverted = i + 0
    }
    END {
      printf "| %s | %d | %d | %d | %d | %.2g | %.4g° | %.3g | %d | %.2f | %.2f | %.2f |\n", tutorial, status, steps, subSteps,
             iterations, residual, nonOrtho, skew, inverted, wall, processWall, cpu
    }' "${log:-/dev/null}"
  if [[ $status -ne 0 ]]; then
    echo "tutorialFigures.sh: rbmMoveMesh on tutorials/$tutorial exited with $status:" >&2
    tail -n 5 "$case.log" >&2
  fi
done
