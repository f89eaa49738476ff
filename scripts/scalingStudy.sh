#!/usr/bin/env bash
# Measures `scaling` (rigidBodyMotionSolverCoeffs): every 2D case rbm's docs quote, moved with
# rigid neighbourhoods (the thesis' energy), with `scaling auto` (the default: in 2D the scale
# costs 0.3 × the neighbourhood's size) and with similar ones (the scale free), everything else
# as the case has it. Prints
# one Markdown table stamped with the commit, the date and the machine; docs/motionSolver.md
# ("Neighbourhood scaling") holds its last output.
#
#   scripts/scalingStudy.sh > /tmp/scaling.md        # about 15 minutes on 2 cores
#   scripts/scalingStudy.sh --no-openfoam             # rbm's own cases only (2 minutes)
#
# rbm's cases run build/bin/rbmMoveMesh on a copy of the inputs (OMP_NUM_THREADS=1), with
# `scaling` set in rigidBodyMotionSolverCoeffs: the squares tutorials as shipped (the thesis'
# uniform weights, no stiffening) and with rbm's defaults, the pitching airfoil tutorial, and the
# boundary-layer airfoil of benchmarks/airfoilMesh turned 4°, 20° and 45° about its trailing
# edge. OpenFOAM's moving-mesh tutorials run through scripts/openfoamTutorials.sh --coeffs (the
# plugin in moveDynamicMesh, beside OpenFOAM's own solver in the same run), which needs
# OpenFOAM v1912 and build/lib/librbmMotionSolver.so.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$root/build/bin
openfoam=1
[[ ${1:-} == --no-openfoam ]] && openfoam=0
if [[ ! -x $bin/rbmMoveMesh ]]; then
  echo "scalingStudy.sh: $bin/rbmMoveMesh not found; build rbm first (scripts/setup.sh)" >&2
  exit 2
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1

# setScaling DICT VALUE [reset]: `scaling VALUE;` in the coefficients (reset: nothing else).
setScaling() {
  python3 - "$1" "$2" "${3:-}" <<'EOF'
import re, sys
path, value, reset = sys.argv[1], sys.argv[2], sys.argv[3]
text = open(path).read()
text = re.sub(r"\n[ \t]*scaling[ \t]+[^;\n]*;[^\n]*", "", text)  # the case's own, if any
match = re.search(r"rigidBodyMotionSolverCoeffs\s*\{", text)
if match is None:
    text += "\nrigidBodyMotionSolverCoeffs\n{\n    scaling %s;\n}\n" % value
elif reset:
    end = text.index("}", match.end())
    text = text[:match.end()] + "\n    scaling %s;\n" % value + text[end:]
else:
    text = text[:match.end()] + "\n    scaling %s;" % value + text[match.end():]
open(path, "w").write(text)
EOF
}

# runCase NAME SOURCE [reset] [degrees]: one row, rigid, auto, similar.
runCase() {
  local name=$1 source=$2 reset=${3:-} degrees=${4:-} row="| $1 |"
  for scaling in rigid auto similar; do
    local dir=$work/$name-$scaling
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
    setScaling "$dir/constant/dynamicMeshDict" "$scaling" "$reset"
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
echo "| case | scaling rigid: steps, worst max non-orthogonality, most inverted cells in a step | scaling auto (0.3 in 2D, the default) | scaling similar |"
echo "|---|---|---|---|"
tutorials=$root/tutorials
runCase "squares/rotating (thesis' settings)" "$tutorials/squares/rotating"
runCase "squares/translated (thesis' settings)" "$tutorials/squares/translated"
runCase "squares/rotating (rbm's defaults)" "$tutorials/squares/rotating" reset
runCase "squares/translated (rbm's defaults)" "$tutorials/squares/translated" reset
runCase "naca4415Pitching (80 steps)" "$tutorials/naca4415Pitching" reset
for degrees in 4 20 45; do
  runCase "boundary-layer airfoil (40 640 nodes a plane) turned ${degrees}°" "$root/benchmarks/airfoilMesh" reset "$degrees"
done

if [[ $openfoam == 1 ]]; then
  for scaling in rigid auto similar; do
    "$root/scripts/openfoamTutorials.sh" --cases movingCone,waveMakerFlap,waveMakerPiston,oscillatingBox \
      --work "$work/openfoam-$scaling" --coeffs "scaling $scaling;" > "$work/openfoam-$scaling.log" 2>&1 || true
  done
  python3 - "$work/openfoam-rigid.log" "$work/openfoam-auto.log" "$work/openfoam-similar.log" <<'EOF'
import re, sys
def rows(path):
    out = {}
    for line in open(path):
        m = re.match(r"(\w+): \d+ cells; steps rbm (\S+) / OpenFOAM (\S+) of (\d+); inverted (\S+) / (\S+); "
                     r"worst non-orth (\S+) / (\S+);", line)
        if m:
            out[m.group(1)] = m.groups()
    return out
runs = [rows(path) for path in sys.argv[1:]]
for case in ["movingCone", "waveMakerFlap", "waveMakerPiston", "oscillatingBox"]:
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
