#!/usr/bin/env bash
# Runs this case with rbm's plugin and with OpenFOAM's displacementLaplacian (the diffusivity
# of constant/dynamicMeshDict.laplacian), in copies of its inputs, and prints the README's
# comparison as markdown: mesh quality, cost of the motion and of the flow step, lift history.
# With gnuplot installed it also draws the lift history into <work>/lift.png.
#   ./compare.sh [-steps N] [-motionSteps M] [-only rbm|laplacian|static|table] [work folder]
#       work folder   default ${TMPDIR:-/tmp}/naca4415PitchingFlow.compare
#       -steps N      pimpleFoam runs the first N time steps (default: all, 500)
#       -motionSteps M  moveDynamicMesh runs the first M steps (default 150, at most N)
#       -only X       run one part only (rbm, laplacian or static) in an existing work folder,
#                     or none (table); then print the table from what the work folder holds
# For each motion solver m:
#   <work>/m/flow    pimpleFoam, then OpenFOAM's checkMesh of every time written (every 25th
#                    step) -> flow CPU time per step, Courant, lift, quality at the times written;
#                    with rbm, also rbm's own quality line of every step (its log)
#   <work>/m/motion  moveDynamicMesh -noFunctionObjects: the motion alone, OpenFOAM's checkMesh
#                    after every step (part of moveDynamicMesh) -> quality of every step
# and <work>/static: moveDynamicMesh with the mesh held still (staticFvMesh): the cost of its
# own loop and checkMesh, subtracted to give the motion's cost per step.
# Times are OpenFOAM's ExecutionTime: CPU seconds of the process, much less sensitive to the
# machine's load than the wall time (also shown: OpenFOAM prints it in whole seconds).
# Without rbm's plugin (see Allrun) the rbm column says "not run" and only the Laplacian runs.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
arguments="$*"
steps=""
motionSteps=150
only=""
while [[ ${1:-} == -* ]]; do
  case $1 in
    -steps) steps=$2; shift 2 ;;
    -motionSteps) motionSteps=$2; shift 2 ;;
    -only) only=$2; shift 2 ;;
    *) echo "usage: $0 [-steps N] [-motionSteps M] [-only rbm|laplacian|static|table] [work folder]" >&2; exit 2 ;;
  esac
done
work=${1:-${TMPDIR:-/tmp}/naca4415PitchingFlow.compare}
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
command -v pimpleFoam >/dev/null || { echo "compare.sh: pimpleFoam not found (apt-get install openfoam)" >&2; exit 2; }
deltaT=$(awk '/^deltaT/{sub(";","",$2); print $2}' "$here/system/controlDict")
allSteps=$(awk '/^deltaT/{sub(";","",$2); d=$2} /^endTime/{sub(";","",$2); e=$2} END{printf "%d", e/d + 0.5}' "$here/system/controlDict")
steps=${steps:-$allSteps}
(( motionSteps > steps )) && motionSteps=$steps

plugin=""
if [[ -n ${RBM_PLUGIN_DIR:-} ]]; then
  [[ -f $RBM_PLUGIN_DIR/librbmMotionSolver.so ]] && plugin=$RBM_PLUGIN_DIR/librbmMotionSolver.so
elif [[ -d $here/../../build ]]; then
  plugin=$(find "$here/../../build" -name librbmMotionSolver.so -print -quit 2>/dev/null || true)
fi
motions=(laplacian)
if [[ -n $plugin ]]; then
  motions=(rbm laplacian)
  plugin=$(cd "$(dirname "$plugin")" && pwd)/librbmMotionSolver.so
  export LD_LIBRARY_PATH=$(dirname "$plugin")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
fi

[[ -z $only ]] && rm -rf "$work"
mkdir -p "$work"
runs() { [[ -z $only || $only == "$1" ]]; }
stamp() { echo "$(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)"; }
makeCase() {  # makeCase <folder> <dynamicMeshDict file> <steps>
  mkdir -p "$1"
  cp -r "$here/0" "$here/constant" "$here/system" "$1/"
  cp "$2" "$1/constant/dynamicMeshDict"
  rm -f "$1/constant/dynamicMeshDict.laplacian"
  sed -i "s/^endTime .*/endTime         $(awk -v n="$3" -v d="$deltaT" 'BEGIN{print n*d}');/" "$1/system/controlDict"
}

for m in "${motions[@]}"; do
  runs "$m" || continue
  rm -rf "${work:?}/$m"
  dict=$here/constant/dynamicMeshDict
  [[ $m == laplacian ]] && dict=$here/constant/dynamicMeshDict.laplacian
  makeCase "$work/$m/flow" "$dict" "$steps"
  makeCase "$work/$m/motion" "$dict" "$motionSteps"
  { echo "$m: $(stamp)"; [[ $m == rbm ]] && echo "plugin: $plugin ($(stat -c '%y' "$plugin" | cut -c1-16))"; } > "$work/$m/started"
  echo "compare.sh: $m: pimpleFoam, $steps steps" >&2
  pimpleFoam -case "$work/$m/flow" > "$work/$m/flow/log.pimpleFoam" 2>&1
  echo $? > "$work/$m/flow/status"
  checkMesh -case "$work/$m/flow" -noZero -time 0: > "$work/$m/flow/log.checkMesh" 2>&1
  echo "compare.sh: $m: moveDynamicMesh, $motionSteps steps" >&2
  moveDynamicMesh -case "$work/$m/motion" -noFunctionObjects > "$work/$m/motion/log.moveDynamicMesh" 2>&1
done
if runs static; then
  rm -rf "${work:?}/static"
  makeCase "$work/static" "$here/constant/dynamicMeshDict.laplacian" "$motionSteps"
  sed -i 's/^dynamicFvMesh .*/dynamicFvMesh       staticFvMesh;/' "$work/static/constant/dynamicMeshDict"
  echo "static: $(stamp)" > "$work/static/started"
  echo "compare.sh: static mesh: moveDynamicMesh, $motionSteps steps (the cost of its loop and checkMesh)" >&2
  moveDynamicMesh -case "$work/static" -noFunctionObjects > "$work/static/log.moveDynamicMesh" 2>&1
fi
for m in "${motions[@]}" static; do
  if [[ ! -f $work/$m/started ]]; then
    echo "compare.sh: $work/$m has not run; run $0 without -only, or with -only $m" >&2
    exit 1
  fi
done

# --- Figures ------------------------------------------------------------------------------------
# checkQuality <checkMesh output>: "checked|OK|worst non-orthogonality (t)|worst skewness (t)|
# inverted cells (t, first t)|first time failing"
checkQuality() {
  awk '
    /^Time = [^ ]+$/{t=$3; n++}
    /non-orthogonality Max:/{if ($4+0 > no) {no=$4+0; tno=t}}
    /[Ss]kewness = /{for (i=1;i<=NF;i++) if ($i=="=") s=$(i+1); s=s+0; if (s > sk) {sk=s; tsk=t}}
    /Number of negative volume cells:/{v=$NF+0; if (v > inv) {inv=v; tinv=t}; if (first=="") first=t}
    /^Mesh OK/{ok++}
    /Failed [0-9]+ mesh checks/{if (firstBad=="") firstBad=t}
    END{
      printf "%d|%d|%.1f° (t = %s)|%.3f (t = %s)|%s|%s", n, ok, no, tno, sk, tsk,
             (inv==0 ? "0" : inv " (t = " tinv "; first at t = " first ")"),
             (firstBad=="" ? "none" : "t = " firstBad)
    }' "$1"
}
lastExec() { awk '/^ExecutionTime/{e=$3; c=$7} END{print e+0, c+0}' "$1"; }
read staticExec staticClock < <(lastExec "$work/static/log.moveDynamicMesh")
staticSteps=$(grep -c '^ExecutionTime' "$work/static/log.moveDynamicMesh")

declare -A row
for m in "${motions[@]}"; do
  f=$work/$m/flow
  row[$m,written]=$(checkQuality "$f/log.checkMesh")
  row[$m,steps]=$(checkQuality "$work/$m/motion/log.moveDynamicMesh")
  row[$m,last]=$(awk '/^Time = /{t=$3} /non-orthogonality Max:/{no=$4} END{printf "%.4f° (t = %s)", no, t}' "$f/log.checkMesh")
  read mExec mClock < <(lastExec "$work/$m/motion/log.moveDynamicMesh")
  mSteps=$(grep -c '^ExecutionTime' "$work/$m/motion/log.moveDynamicMesh")
  read fExec fClock < <(lastExec "$f/log.pimpleFoam")
  fSteps=$(grep -c '^ExecutionTime' "$f/log.pimpleFoam")
  row[$m,motion]=$(awk -v e="$mExec" -v n="$mSteps" -v se="$staticExec" -v sn="$staticSteps" \
                   'BEGIN{if (n > 0 && sn > 0) printf "%.3f", e/n - se/sn; else printf "—"}')
  row[$m,flow]=$(awk -v e="$fExec" -v c="$fClock" -v n="$fSteps" \
                 'BEGIN{if (n > 0) printf "%.3f (%.2f)", e/n, c/n; else printf "—"}')
  row[$m,share]=$(awk -v a="${row[$m,motion]}" -v b="${row[$m,flow]%% *}" \
                  'BEGIN{if (b > 0) printf "%.0f %%", 100*a/b; else printf "—"}')
  row[$m,end]="exit status $(cat "$f/status"), $fSteps steps, last t = $(awk '/^Time = /{t=$3} END{print t}' "$f/log.pimpleFoam")"
  if grep -q '^End' "$f/log.pimpleFoam"; then
    row[$m,end]+=", End"
  else
    row[$m,end]+=", $(grep -m1 -E 'FOAM FATAL|Floating point|[Ee]rror' "$f/log.pimpleFoam" | sed 's/^ *//; s/|/\\|/g' | cut -c1-70)"
  fi
  row[$m,co]=$(awk '/^Time = [^ ]+$/{n++} /^Courant Number/{if (n <= 20) {if ($6+0 > a) a=$6+0} else if ($6+0 > b) b=$6+0}
                    END{printf "%.2f, %.2f", a, b}' "$f/log.pimpleFoam")
  # rbm's own line per step (plugin), after OpenFOAM's "Time = t": "rigidBodyMotionSolver:
  # sub-steps n  iterations n  residual r  worst quality q  max non-orthogonality a  inverted n
  # wall s s".
  row[$m,own]=$(awk '
    /^Time = [^ ]+$/{t=$3}
    /^rigidBodyMotionSolver: sub-steps .* inverted /{
      n++
      for (i=1;i<=NF;i++) {
        if ($i=="quality" && (q=="" || $(i+1)+0 < q)) {q=$(i+1)+0; tq=t}
        if ($i=="non-orthogonality" && $(i+1)+0 > a) {a=$(i+1)+0; ta=t}
        if ($i=="inverted" && $(i+1)+0 > inv) inv=$(i+1)+0
        if ($i=="wall") w+=$(i+1)
      }
    }
    END{ if (n == 0) print "—"; else printf "%d steps: min mean-ratio quality %.4f (t = %s), max non-orthogonality %.2f° (t = %s), inverted %d; motion wall %.3f s per step", n, q, tq, a, ta, inv, w/n }' "$f/log.pimpleFoam")
done

cell() { # cell <motion> <key> [field]: a table cell, "not run" without the plugin
  if [[ $1 == rbm && -z $plugin ]]; then echo "not run (plugin not built)"; return; fi
  if [[ -n ${3:-} ]]; then echo "${row[$1,$2]}" | cut -d'|' -f"$3"; else echo "${row[$1,$2]}"; fi
}

commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)
cpu=$(awk -F': ' '/model name/{print $2; exit}' /proc/cpuinfo)
echo "Measured with \`tutorials/naca4415PitchingFlow/compare.sh${arguments:+ $arguments}\` at commit $commit;"
echo "$(nproc --all) cores ($cpu), other jobs running alongside; OpenFOAM v1912 (Debian), serial runs;"
echo "26 656 prisms (13 575 nodes per plane); pimpleFoam $steps steps, moveDynamicMesh $motionSteps steps. Runs started:"
for m in "${motions[@]}" static; do sed 's/$/;/' "$work/$m/started"; done
echo
echo "| | rbm (\`rigidBodyMotionSolver\`) | OpenFOAM \`displacementLaplacian\`, \`$(sed -n 's/^ *diffusivity *\(.*\);/\1/p' "$here/constant/dynamicMeshDict.laplacian")\` |"
echo "|---|---|---|"
echo "| pimpleFoam | $(cell rbm end) | $(cell laplacian end) |"
echo "| checkMesh of the times written: Mesh OK / times checked | $(cell rbm written 2) / $(cell rbm written 1) | $(cell laplacian written 2) / $(cell laplacian written 1) |"
echo "| … first time failing | $(cell rbm written 6) | $(cell laplacian written 6) |"
echo "| … worst max non-orthogonality | $(cell rbm written 3) | $(cell laplacian written 3) |"
echo "| … worst max skewness | $(cell rbm written 4) | $(cell laplacian written 4) |"
echo "| … inverted cells (negative volume), worst | $(cell rbm written 5) | $(cell laplacian written 5) |"
echo "| … max non-orthogonality at the last time (initial mesh: 27.0900°) | $(cell rbm last) | $(cell laplacian last) |"
echo "| checkMesh after each of the first $motionSteps steps (moveDynamicMesh): Mesh OK / steps | $(cell rbm steps 2) / $(cell rbm steps 1) | $(cell laplacian steps 2) / $(cell laplacian steps 1) |"
echo "| … first step failing | $(cell rbm steps 6) | $(cell laplacian steps 6) |"
echo "| … worst max non-orthogonality | $(cell rbm steps 3) | $(cell laplacian steps 3) |"
echo "| … inverted cells (negative volume), worst | $(cell rbm steps 5) | $(cell laplacian steps 5) |"
echo "| rbm's own check of every step of the pimpleFoam run | $(cell rbm own) | — |"
echo "| motion: CPU s per step (moveDynamicMesh − static mesh, first $motionSteps steps) | $(cell rbm motion) | $(cell laplacian motion) |"
echo "| pimpleFoam: CPU s per step, motion included (wall s per step) | $(cell rbm flow) | $(cell laplacian flow) |"
echo "| motion's share of the flow step's CPU time | $(cell rbm share) | $(cell laplacian share) |"
echo "| max Courant number: first 20 steps, after | $(cell rbm co) | $(cell laplacian co) |"
echo
echo "Lift coefficient Cl (forceCoeffs) against the angle of attack α = 10° sin(2πt) (nose up) and"
echo "the plunge h = 0.05 sin(2πt):"
echo
echo "| t | α (°) | h | Cl, rbm | Cl, displacementLaplacian |"
echo "|---|---|---|---|---|"
coeff() { # coeff <motion>: "time Cl" lines
  local file
  file=$(ls "$work/$1"/flow/postProcessing/forceCoeffs/0/coefficient*.dat 2>/dev/null | head -1)
  [[ -n $file ]] && awk '!/^#/{print $1, $4}' "$file"
}
for k in $(seq 1 10); do
  t=$(awk -v k="$k" -v n="$steps" -v d="$deltaT" 'BEGIN{printf "%g", k*n*d/10}')
  clr="—"
  [[ -n $plugin ]] && clr=$(coeff rbm | awk -v t="$t" '($1-t)^2 < 1e-12 {printf "%.3f", $2}')
  cll=$(coeff laplacian | awk -v t="$t" '($1-t)^2 < 1e-12 {printf "%.3f", $2}')
  awk -v t="$t" -v r="${clr:-—}" -v l="${cll:-—}" 'BEGIN{pi=atan2(0,-1);
     printf "| %g | %.2f | %.4f | %s | %s |\n", t, 10*sin(2*pi*t), 0.05*sin(2*pi*t), r, l}'
done

if [[ -n $plugin ]]; then
  echo
  join <(coeff rbm | awk '$1 >= 0.01 {printf "%.6f %s\n", $1, $2}') \
       <(coeff laplacian | awk '$1 >= 0.01 {printf "%.6f %s\n", $1, $2}') |
    awk '{d=$2-$3; if (d<0) d=-d; if (d>m) {m=d; t=$1}; n++}
         END{printf "Largest |Cl(rbm) − Cl(displacementLaplacian)| from t = 0.01 on (%d steps): %.2g at t = %g.\n", n, m, t}'
fi

if command -v gnuplot >/dev/null; then
  plots=""
  for m in "${motions[@]}"; do
    coeff "$m" | awk '$1 >= 0.01' > "$work/$m.cl"
    style="with lines lw 2"
    [[ $m == laplacian ]] && style="with linespoints lw 1 pt 6 pointinterval 25"
    [[ -s $work/$m.cl ]] && plots+="${plots:+, }'$work/$m.cl' using 1:2 $style title '$m'"
  done
  if [[ -n $plots ]]; then
    gnuplot <<GNUPLOT && echo && echo "Plot (from t = 0.01, after the impulsive start): $work/lift.png"
set terminal png size 800,450
set output '$work/lift.png'
set xlabel 't (s)'
set ylabel 'Cl'
set grid
set title 'naca4415PitchingFlow: lift coefficient, α = 10° sin(2πt), h = 0.05 sin(2πt)'
plot $plots
GNUPLOT
  fi
fi
