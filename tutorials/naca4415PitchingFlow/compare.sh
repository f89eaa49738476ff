#!/usr/bin/env bash
# Runs this case with rbm's plugin and with OpenFOAM's displacementLaplacian (the diffusivity
# of constant/dynamicMeshDict.laplacian) in copies of its inputs, and prints the README's
# comparison as markdown: mesh quality at every step, cost of the motion and of the flow step,
# lift coefficient history. With gnuplot installed it also draws the lift history into
# <work>/lift.png.
#   ./compare.sh [-steps N] [-only rbm|laplacian|static|table] [work folder]
#       default work folder: ${TMPDIR:-/tmp}/naca4415PitchingFlow.compare
#       -steps N   the first N time steps only
#       -only X    run one part only (rbm, laplacian, static) in an existing work folder, or
#                  none (table), then print the table from what the work folder holds
# For each motion solver, in <work>/<rbm|laplacian>:
#   moveDynamicMesh -noFunctionObjects  the motion alone; OpenFOAM's checkMesh runs after every
#                                       step (it is part of moveDynamicMesh) -> quality per step
#   pimpleFoam                          the flow run -> CPU time per step, Courant, lift
# and once, in <work>/static, moveDynamicMesh on the mesh held still (staticFvMesh): the cost
# of moveDynamicMesh's own loop and checkMesh, subtracted to give the motion's cost per step.
# Times are OpenFOAM's ExecutionTime (CPU seconds of the process; wall time is also shown, in
# whole seconds as OpenFOAM prints it, and depends on the machine's load).
# Without rbm's plugin (see Allrun) the rbm column says so and only the Laplacian runs.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
steps=""
only=""
while [[ ${1:-} == -* ]]; do
  case $1 in
    -steps) steps=$2; shift 2 ;;
    -only) only=$2; shift 2 ;;
    *) echo "usage: $0 [-steps N] [-only rbm|laplacian|static|table] [work folder]" >&2; exit 2 ;;
  esac
done
work=${1:-${TMPDIR:-/tmp}/naca4415PitchingFlow.compare}
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
command -v pimpleFoam >/dev/null || { echo "compare.sh: pimpleFoam not found (apt-get install openfoam)" >&2; exit 2; }

plugin=""
if [[ -n ${RBM_PLUGIN_DIR:-} ]]; then
  [[ -f $RBM_PLUGIN_DIR/librbmMotionSolver.so ]] && plugin=$RBM_PLUGIN_DIR/librbmMotionSolver.so
elif [[ -d $here/../../build ]]; then
  plugin=$(find "$here/../../build" -name librbmMotionSolver.so -print -quit 2>/dev/null || true)
fi
motions=(laplacian)
if [[ -n $plugin ]]; then
  motions=(rbm laplacian)
  export LD_LIBRARY_PATH=$(cd "$(dirname "$plugin")" && pwd)${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
fi

if [[ -z $only ]]; then
  rm -rf "$work"
fi
mkdir -p "$work"
runs() { [[ -z $only || $only == "$1" ]]; }
makeCase() {  # makeCase <folder> <dynamicMeshDict file>
  mkdir -p "$1"
  cp -r "$here/0" "$here/constant" "$here/system" "$1/"
  cp "$2" "$1/constant/dynamicMeshDict"
  rm -f "$1/constant/dynamicMeshDict.laplacian"
  if [[ -n $steps ]]; then
    sed -i "s/^endTime .*/endTime         $(awk -v n="$steps" '/^deltaT/{sub(";","",$2); print n*$2}' "$1/system/controlDict");/" "$1/system/controlDict"
  fi
}

for m in "${motions[@]}"; do
  runs "$m" || continue
  rm -rf "${work:?}/$m"
  dict=$here/constant/dynamicMeshDict
  [[ $m == laplacian ]] && dict=$here/constant/dynamicMeshDict.laplacian
  makeCase "$work/$m" "$dict"
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)" > "$work/$m/started"
  echo "compare.sh: $m: moveDynamicMesh" >&2
  moveDynamicMesh -case "$work/$m" -noFunctionObjects > "$work/$m/log.moveDynamicMesh" 2>&1
  echo $? > "$work/$m/status.moveDynamicMesh"
  find "$work/$m" -maxdepth 1 -regex '.*/[0-9.e-]+' ! -name 0 -exec rm -rf {} +
  echo "compare.sh: $m: pimpleFoam" >&2
  pimpleFoam -case "$work/$m" > "$work/$m/log.pimpleFoam" 2>&1
  echo $? > "$work/$m/status.pimpleFoam"
done
if runs static; then
  rm -rf "${work:?}/static"
  makeCase "$work/static" "$here/constant/dynamicMeshDict.laplacian"
  sed -i 's/^dynamicFvMesh .*/dynamicFvMesh       staticFvMesh;/' "$work/static/constant/dynamicMeshDict"
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)" > "$work/static/started"
  echo "compare.sh: static mesh: moveDynamicMesh (the cost of its loop and checkMesh)" >&2
  moveDynamicMesh -case "$work/static" -noFunctionObjects > "$work/static/log.moveDynamicMesh" 2>&1
fi
for m in rbm laplacian static; do
  if [[ ! -f $work/$m/log.moveDynamicMesh ]] && [[ $m != rbm || -n $plugin ]]; then
    echo "compare.sh: $work/$m has not run; run $0 without -only, or with -only $m" >&2
    exit 1
  fi
done

# --- Figures ------------------------------------------------------------------------------------
lastExec() { awk '/^ExecutionTime/{e=$3; c=$7} END{print e+0, c+0}' "$1"; }
nSteps() { grep -c '^Time = ' "$1"; }
read staticExec staticClock < <(lastExec "$work/static/log.moveDynamicMesh")
staticSteps=$(nSteps "$work/static/log.moveDynamicMesh")

declare -A row
for m in "${motions[@]}"; do
  d=$work/$m
  # Quality after every step (OpenFOAM's checkMesh inside moveDynamicMesh).
  row[$m,quality]=$(awk '
    /^Time = /{t=$3; n++}
    /non-orthogonality Max:/{if ($4+0 > no) {no=$4+0; tno=t}}
    /[Ss]kewness = /{for (i=1;i<=NF;i++) if ($i=="=") s=$(i+1); s=s+0; if (s > sk) {sk=s; tsk=t}}
    /Number of negative volume cells:/{v=$NF+0; if (v > inv) {inv=v; tinv=t}; if (first=="") first=t}
    /incorrectly oriented/{for (i=1;i<=NF;i++) if ($i=="pyramids:") f=$(i+1); if (f+0 > pyr) {pyr=f+0; tpyr=t}}
    /^Mesh OK/{ok++}
    /Failed [0-9]+ mesh checks/{bad++; if (firstBad=="") firstBad=t}
    END{
      printf "%d|%d|%s|%.1f° (t = %s)|%.3f (t = %s)|%s|%s", n, ok, (firstBad==""?"never":"t = " firstBad), no, tno, sk, tsk,
             (inv==0 ? "0" : inv " (t = " tinv "; first at t = " first ")"),
             (pyr==0 ? "0" : pyr " (t = " tpyr ")")
    }' "$d/log.moveDynamicMesh")
  read mExec mClock < <(lastExec "$d/log.moveDynamicMesh")
  mSteps=$(nSteps "$d/log.moveDynamicMesh")
  read fExec fClock < <(lastExec "$d/log.pimpleFoam")
  fSteps=$(grep -c '^ExecutionTime' "$d/log.pimpleFoam")
  row[$m,motion]=$(awk -v e="$mExec" -v n="$mSteps" -v se="$staticExec" -v sn="$staticSteps" \
                   'BEGIN{printf "%.3f", (n>0 && sn>0) ? e/n - se/sn : 0}')
  row[$m,flow]=$(awk -v e="$fExec" -v n="$fSteps" 'BEGIN{printf "%.3f", (n>0) ? e/n : 0}')
  row[$m,flowClock]=$(awk -v e="$fClock" -v n="$fSteps" 'BEGIN{printf "%.2f", (n>0) ? e/n : 0}')
  row[$m,share]=$(awk -v a="${row[$m,motion]}" -v b="${row[$m,flow]}" 'BEGIN{printf "%.0f %%", (b>0) ? 100*a/b : 0}')
  row[$m,end]="$(cat "$d/status.pimpleFoam"), $fSteps steps, $(awk '/^Time = /{t=$3} END{print t}' "$d/log.pimpleFoam")"
  grep -q '^End' "$d/log.pimpleFoam" && row[$m,end]+=", End" || row[$m,end]+=", $(grep -m1 -E 'FOAM FATAL|Floating point|error' "$d/log.pimpleFoam" | sed 's/^ *//; s/|/\\|/g' | cut -c1-60)"
  row[$m,co]=$(awk '/^Time = /{n++} /^Courant Number/{if (n <= 20) {if ($6+0 > a) a=$6+0} else if ($6+0 > b) b=$6+0}
                    END{printf "%.2f, %.2f", a, b}' "$d/log.pimpleFoam")
done

rbmCell() { # rbmCell <key>
  if [[ -n $plugin ]]; then echo "${row[rbm,$1]}"; else echo "not run (plugin not built)"; fi
}
q() { echo "${row[$1,quality]}" | cut -d'|' -f"$2"; }
qr() { if [[ -n $plugin ]]; then q rbm "$1"; else echo "not run"; fi; }

commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)
cpu=$(awk -F': ' '/model name/{print $2; exit}' /proc/cpuinfo)
echo "Measured with \`tutorials/naca4415PitchingFlow/compare.sh${steps:+ -steps $steps}\` at commit $commit, $(nproc) cores ($cpu),"
echo "other jobs running alongside; runs started:"
for m in rbm laplacian static; do
  [[ -f $work/$m/started ]] && echo "$m $(cat "$work/$m/started");"
done
echo "OpenFOAM v1912 (Debian), serial runs, 26 656 prisms (13 575 nodes per plane)."
echo
echo "| | rbm (\`rigidBodyMotionSolver\`) | OpenFOAM \`displacementLaplacian\`, $(sed -n 's/^ *diffusivity *\(.*\);/\1/p' "$here/constant/dynamicMeshDict.laplacian") |"
echo "|---|---|---|"
echo "| steps moved by moveDynamicMesh | $(qr 1) | $(q laplacian 1) |"
echo "| steps whose mesh passes checkMesh (\"Mesh OK\") | $(qr 2) | $(q laplacian 2) |"
echo "| first step failing checkMesh | $(qr 3) | $(q laplacian 3) |"
echo "| worst max non-orthogonality over the steps | $(qr 4) | $(q laplacian 4) |"
echo "| worst max skewness over the steps | $(qr 5) | $(q laplacian 5) |"
echo "| inverted cells (checkMesh: negative volume), worst step | $(qr 6) | $(q laplacian 6) |"
echo "| faces with wrongly oriented pyramids, worst step | $(qr 7) | $(q laplacian 7) |"
echo "| motion: CPU s per step (moveDynamicMesh − static mesh) | $(rbmCell motion) | ${row[laplacian,motion]} |"
echo "| pimpleFoam: CPU s per step (wall s per step) | $(rbmCell flow) ($(rbmCell flowClock)) | ${row[laplacian,flow]} (${row[laplacian,flowClock]}) |"
echo "| motion's share of the flow step | $(rbmCell share) | ${row[laplacian,share]} |"
echo "| pimpleFoam: exit status, steps, last time | $(rbmCell end) | ${row[laplacian,end]} |"
echo "| max Courant number: first 20 steps, then the rest | $(rbmCell co) | ${row[laplacian,co]} |"
echo
echo "Lift coefficient (forceCoeffs, Cl) against the angle of attack α = 10° sin(2πt) (nose up) and"
echo "the plunge h = 0.05 sin(2πt):"
echo
echo "| t | α (°) | h | Cl, rbm | Cl, displacementLaplacian |"
echo "|---|---|---|---|---|"
coeff() { # coeff <motion> -> "time Cl" lines
  local f
  f=$(ls "$work/$1"/postProcessing/forceCoeffs/0/coefficient*.dat 2>/dev/null | head -1)
  [[ -n $f ]] && awk '!/^#/{print $1, $4}' "$f"
}
endTime=$(awk '/^endTime/{sub(";","",$2); print $2}' "$work/laplacian/system/controlDict")
for k in $(seq 1 10); do
  t=$(awk -v k="$k" -v e="$endTime" 'BEGIN{printf "%g", k*e/10}')
  clr="—"; cll="—"
  [[ -n $plugin ]] && clr=$(coeff rbm | awk -v t="$t" '($1-t)^2 < 1e-12 {printf "%.3f", $2}')
  cll=$(coeff laplacian | awk -v t="$t" '($1-t)^2 < 1e-12 {printf "%.3f", $2}')
  awk -v t="$t" -v r="${clr:-—}" -v l="${cll:-—}" 'BEGIN{pi=atan2(0,-1);
     printf "| %g | %.2f | %.4f | %s | %s |\n", t, 10*sin(2*pi*t), 0.05*sin(2*pi*t), r, l}'
done

if command -v gnuplot >/dev/null; then
  for m in "${motions[@]}"; do coeff "$m" > "$work/$m.cl"; done
  plots="'$work/laplacian.cl' using 1:2 with lines title 'displacementLaplacian'"
  [[ -n $plugin ]] && plots="'$work/rbm.cl' using 1:2 with lines lw 2 title 'rbm', $plots"
  gnuplot <<GNUPLOT && echo && echo "Plot: $work/lift.png"
set terminal png size 800,450
set output '$work/lift.png'
set xlabel 't (s)'
set ylabel 'Cl'
set grid
set key top right
plot $plots
GNUPLOT
fi
