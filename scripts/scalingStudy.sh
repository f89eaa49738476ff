#!/usr/bin/env bash
# Measures a setting of rigidBodyMotionSolverCoeffs on every 2D case rbm's docs quote: by
# default `scaling` (rigid neighbourhoods, the thesis' energy; `scaling auto`, the default: in
# 2D the scale costs 0.3 × the neighbourhood's size; similar ones, the scale free), or any
# entries given with --entries (one column each, e.g. the stiffening study of
# docs/motionSolver.md, "Default stiffening"), everything else as the case has it. Prints one
# Markdown table stamped with the commit, the date and the machine; docs/motionSolver.md
# ("Neighbourhood scaling", "Default stiffening") holds its last outputs.
#
#   scripts/scalingStudy.sh > /tmp/scaling.md        # about 15 minutes on 2 cores
#   scripts/scalingStudy.sh --no-openfoam             # rbm's own cases only (2 minutes)
#   scripts/scalingStudy.sh --entries "stiffening auto;" "stiffening movingAndFixed 0.75 0.2;"
#   scripts/scalingStudy.sh --tutorials oscillatingBox,waveMakerFlap --openfoam-only --entries ...
#
# rbm's cases run build/bin/rbmMoveMesh on a copy of the inputs (OMP_NUM_THREADS=1), with
# each column's entries set in rigidBodyMotionSolverCoeffs: the squares tutorials as shipped
# (the thesis' uniform weights, no stiffening) and with rbm's defaults, the naca4415 and
# pitching airfoil tutorials, and the boundary-layer airfoil of benchmarks/airfoilMesh turned
# 4°, 20° and 45° about its trailing edge. OpenFOAM's moving-mesh tutorials (--tutorials, default
# movingCone,waveMakerFlap,waveMakerPiston,oscillatingBox; `none` skips them, as --no-openfoam
# does; --openfoam-only: these alone) run through scripts/openfoamTutorials.sh --coeffs (the plugin in moveDynamicMesh,
# beside OpenFOAM's own solver in the same run), which needs OpenFOAM v1912 and
# build/lib/librbmMotionSolver.so.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$root/build/bin
tutorials=movingCone,waveMakerFlap,waveMakerPiston,oscillatingBox
rbmCases=1
entries=("scaling rigid;" "scaling auto;" "scaling similar;")
labels=("scaling rigid: steps, worst max non-orthogonality, most inverted cells in a step"
        "scaling auto (0.3 in 2D, the default)" "scaling similar")
while [[ $# -gt 0 ]]; do
  case $1 in
    --no-openfoam) tutorials=none; shift ;;
    --openfoam-only) rbmCases=0; shift ;;
    --tutorials) tutorials=$2; shift 2 ;;
    --entries)
      shift; entries=(); labels=()
      while [[ $# -gt 0 && $1 != --* ]]; do entries+=("$1"); labels+=("\`$1\`"); shift; done
      [[ ${#entries[@]} -gt 0 ]] || { echo "scalingStudy.sh: --entries needs at least one entry" >&2; exit 2; } ;;
    *) echo "scalingStudy.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
openfoam=1
[[ $tutorials == none ]] && openfoam=0
if [[ ! -x $bin/rbmMoveMesh ]]; then
  echo "scalingStudy.sh: $bin/rbmMoveMesh not found; build rbm first (scripts/setup.sh)" >&2
  exit 2
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1

# setEntries DICT ENTRIES [reset]: ENTRIES (e.g. `scaling rigid;`) in the coefficients, each
# replacing the case's own entry of that keyword (reset: nothing else).
setEntries() {
  python3 - "$1" "$2" "${3:-}" <<'EOF'
import re, sys
path, entries, reset = sys.argv[1], sys.argv[2], sys.argv[3]
text = open(path).read()
for keyword in re.findall(r"(?:^|;)\s*(\w+)", entries):
    text = re.sub(r"\n[ \t]*%s[ \t]+[^;\n]*;[^\n]*" % keyword, "", text)  # the case's own, if any
match = re.search(r"rigidBodyMotionSolverCoeffs\s*\{", text)
if match is None:
    text += "\nrigidBodyMotionSolverCoeffs\n{\n    %s\n}\n" % entries
elif reset:
    end = text.index("}", match.end())
    text = text[:match.end()] + "\n    %s\n" % entries + text[end:]
else:
    text = text[:match.end()] + "\n    %s" % entries + text[match.end():]
open(path, "w").write(text)
EOF
}

# runCase NAME SOURCE [reset] [degrees]: one row, a column per entry.
runCase() {
  local name=$1 source=$2 reset=${3:-} degrees=${4:-} row="| $1 |" column
  for column in "${!entries[@]}"; do
    local dir=$work/$name-$column
    mkdir -p "$dir/constant"
    if [[ -z $degrees ]]; then
      cp -r "$source/0" "$source/system" "$dir/"
      cp -r "$source/constant/." "$dir/constant/"
    else  # the boundary-layer airfoil's mesh with naca4415's motion, turned by $degrees
      cp -r "$root/tutorials/naca4415/0" "$root/tutorials/naca4415/system" "$dir/"
      cp "$root/tutorials/naca4415/constant/dynamicMeshDict" "$dir/constant/"
      cp -r "$source/constant/polyMesh" "$dir/constant/"
      local omega
      omega=$(python3 -c "import math; print(repr(math.radians($degrees)))")
      sed -i -E "s/^([[:space:]]*omega[[:space:]]+)[^;]*;/\1$omega;/" "$dir/0/pointDisplacement"
    fi
    setEntries "$dir/constant/dynamicMeshDict" "${entries[$column]}" "$reset"
    local status=0
    "$bin/rbmMoveMesh" -case "$dir" -noVTK > "$dir/log" 2>&1 || status=$?
    local summary
    summary=$(python3 - "$dir/log" "$status" <<'EOF'
import re, sys
log, status = open(sys.argv[1]).read(), sys.argv[2]
steps = re.search(r"^End: (\d+) of (\d+) steps?", log, re.M)
nonorth = re.search(r"max non-orthogonality\s+([0-9.]+)", log.split("End:")[-1]) if steps else None
inverted = re.search(r"inverted cells\s+(\d+)", log.split("End:")[-1]) if steps else None
print("%s of %s steps, %s°, %s inverted%s" % (steps.group(1) if steps else "?", steps.group(2) if steps else "?",
      nonorth.group(1) if nonorth else "?", inverted.group(1) if inverted else "?",
      "" if status == "0" else " (exit %s)" % status))
EOF
)
    row="$row $summary |"
  done
  echo "$row"
}

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
if [[ -n $(git -C "$root" status --porcelain --untracked-files=no 2>/dev/null) ]]; then commit="$commit+changes"; fi
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
echo "Written by \`scripts/scalingStudy.sh\`: rbm $commit, $(date -u '+%Y-%m-%d %H:%M UTC'), $cpu ($(nproc --all) cores), OMP_NUM_THREADS=1."
echo
header="| case |"; rule="|---|"
for label in "${labels[@]}"; do header+=" $label |"; rule+="---|"; done
echo "$header"
echo "$rule"
cases=$root/tutorials
[[ $rbmCases == 1 ]] && {
runCase "squares/rotating (thesis' settings)" "$cases/squares/rotating"
runCase "squares/translated (thesis' settings)" "$cases/squares/translated"
runCase "squares/rotating (rbm's defaults)" "$cases/squares/rotating" reset
runCase "squares/translated (rbm's defaults)" "$cases/squares/translated" reset
runCase "naca4415 (turned 4°)" "$cases/naca4415" reset
runCase "naca4415Pitching (80 steps)" "$cases/naca4415Pitching" reset
for degrees in 4 20 45; do
  runCase "boundary-layer airfoil (40 640 nodes a plane) turned ${degrees}°" "$root/benchmarks/airfoilMesh" reset "$degrees"
done
}

if [[ $openfoam == 1 ]]; then
  logs=()
  for column in "${!entries[@]}"; do
    "$root/scripts/openfoamTutorials.sh" --cases "$tutorials" \
      --work "$work/openfoam-$column" --coeffs "${entries[$column]}" > "$work/openfoam-$column.log" 2>&1 || true
    logs+=("$work/openfoam-$column.log")
  done
  python3 - "$tutorials" "${logs[@]}" <<'EOF'
import re, sys
def rows(path):
    out = {}
    for line in open(path):
        m = re.match(r"(\w+): \d+ cells; steps rbm (\S+) / OpenFOAM (\S+) of (\d+); inverted (\S+) / (\S+); "
                     r"worst non-orth (\S+) / (\S+);", line)
        if m:
            out[m.group(1)] = m.groups()
    return out
runs = [rows(path) for path in sys.argv[2:]]
for case in sys.argv[1].split(","):
    def cell(r):
        if case not in r:
            return "not run"
        g = r[case]
        return "%s of %s steps, %s, %s inverted" % (g[1], g[3], g[6], g[4])
    openfoam = next((r[case] for r in runs if case in r), None)
    reference = " (OpenFOAM's own solver: %s of %s steps, %s)" % (openfoam[2], openfoam[3], openfoam[7]) if openfoam else ""
    print("| OpenFOAM tutorial %s%s | %s |" % (case, reference, " | ".join(cell(r) for r in runs)))
EOF
fi
