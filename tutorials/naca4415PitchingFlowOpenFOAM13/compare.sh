#!/usr/bin/env bash
# Runs this case with rbm's plugin and with OpenFOAM 13's displacementLaplacian (Allrun and
# Allrun -motion laplacian, in a copy of the case) and prints the README's comparison as
# markdown: foamRun's end, checkMesh of the times written, rbm's own check of every step, CPU
# time per flow step (OpenFOAM's ExecutionTime), the lift at ten times; and the cost of the
# motion alone: `foamRun -solver movingMesh -noFunctionObjects` over the first M steps with each
# motion solver and with the mesh held still (no mover: the cost of the loop, subtracted).
#   ./compare.sh [-steps N] [-motionSteps M] [work folder]
#       default: all 500 steps, M = 150, ${TMPDIR:-/tmp}/naca4415PitchingFlowOpenFOAM13.compare
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
steps=""
motionSteps=150
while [[ ${1:-} == -* ]]; do
  case $1 in
    -steps) steps=$2; shift 2 ;;
    -motionSteps) motionSteps=$2; shift 2 ;;
    *) echo "usage: $0 [-steps N] [-motionSteps M] [work folder]" >&2; exit 2 ;;
  esac
done
work=${1:-${TMPDIR:-/tmp}/naca4415PitchingFlowOpenFOAM13.compare}
export RBM_OPENFOAM13_DIR=${RBM_OPENFOAM13_DIR:-$here/../../third_party/OpenFOAM-13}
export RBM_PLUGIN_DIR=${RBM_PLUGIN_DIR:-$here/../../build/lib}
RBM_OPENFOAM13_DIR=$(cd "$RBM_OPENFOAM13_DIR" && pwd) || exit 2
RBM_PLUGIN_DIR=$(cd "$RBM_PLUGIN_DIR" && pwd) || exit 2
deltaT=$(awk '/^deltaT/{sub(";","",$2); print $2}' "$here/system/controlDict")
allSteps=$(awk '/^deltaT/{sub(";","",$2); d=$2} /^endTime/{sub(";","",$2); e=$2} END{printf "%d", e/d + 0.5}' "$here/system/controlDict")
steps=${steps:-$allSteps}

rm -rf "$work"
mkdir -p "$work"
cp -r "$here/0" "$here/constant" "$here/system" "$here/Allrun" "$work/"
sed -i "s/^endTime .*/endTime         $(awk -v n="$steps" -v d="$deltaT" 'BEGIN{print n*d}');/" "$work/system/controlDict"
stamp() { echo "$(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)"; }
echo "rbm: $(stamp)" > "$work/started"
"$work/Allrun" > "$work/log.Allrun.rbm" 2>&1; echo $? > "$work/status.rbm"
echo "laplacian: $(stamp)" >> "$work/started"
"$work/Allrun" -motion laplacian > "$work/log.Allrun.laplacian" 2>&1; echo $? > "$work/status.laplacian"

# The motion alone: movingMesh over the first motionSteps steps, nothing written.
motionRun() {  # motionRun <rbm|laplacian|static>
  local dir=$work/motion/$1
  mkdir -p "$dir"
  cp -r "$here/0" "$here/constant" "$here/system" "$dir/"
  case $1 in
    laplacian) mv "$dir/constant/dynamicMeshDict.laplacian" "$dir/constant/dynamicMeshDict" ;;
    static) rm "$dir/constant/dynamicMeshDict" ;;
  esac
  sed -i -e "s/^endTime .*/endTime         $(awk -v n="$motionSteps" -v d="$deltaT" 'BEGIN{print n*d}');/" \
         -e "s/^writeInterval .*/writeInterval   1000000;/" "$dir/system/controlDict"
  echo "motion $1: $(stamp)" >> "$work/started"
  (set -- ; set +eu; source "$RBM_OPENFOAM13_DIR/etc/bashrc"
   export LD_LIBRARY_PATH=$RBM_PLUGIN_DIR:$LD_LIBRARY_PATH
   foamRun -case "$dir" -solver movingMesh -noFunctionObjects > "$dir/log.movingMesh" 2>&1)
}
for m in rbm laplacian static; do motionRun $m; done

declare -A folder=([rbm]=$work [laplacian]=$work/laplacian)
# quality <checkMesh log>: "times checked|Mesh OK|worst non-orthogonality (t)|worst skewness (t)|inverted|last non-orthogonality (t)"
quality() {
  awk '/^Time = /{t=$3; sub(/s$/, "", t); n++}
       /non-orthogonality Max:/{last=$4+0; if ($4+0 > no) {no=$4+0; tno=t}}
       /[Ss]kewness = /{for (i=1;i<=NF;i++) if ($i=="=") s=$(i+1); s=s+0; if (s > sk) {sk=s; tsk=t}}
       /Number of negative volume cells:/{v=$NF+0; if (v > inv) inv=v}
       /^Mesh OK/{ok++}
       END{printf "%d|%d|%.2f° (t = %s)|%.3f (t = %s)|%d|%.4f° (t = %s)", n, ok, no, tno, sk, tsk, inv, last, t}' "$1"
}
cell() { quality "${folder[$1]}/log.checkMesh" | cut -d'|' -f"$2"; }
flow() {  # "exit status, steps, last t, End | CPU s per step"
  local log=${folder[$1]}/log.foamRun
  awk -v s="$(cat "$work/status.$1")" '/^Time = /{t=$3; sub(/s$/, "", t); n++} /^ExecutionTime/{e=$3} /^End/{end=", End"}
       END{printf "exit status %s, %d steps, last t = %s%s|%.3f", s, n, t, end, (n ? e/n : 0)}' "$log"
}
motionCost() {  # CPU s per step of movingMesh, minus the static mesh's
  local e n se sn
  read -r e n < <(awk '/^Time = /{n++} /^ExecutionTime/{e=$3} END{print e+0, n+0}' "$work/motion/$1/log.movingMesh")
  read -r se sn < <(awk '/^Time = /{n++} /^ExecutionTime/{e=$3} END{print e+0, n+0}' "$work/motion/static/log.movingMesh")
  awk -v e="$e" -v n="$n" -v se="$se" -v sn="$sn" 'BEGIN{if (n > 0 && sn > 0) printf "%.3f (%d steps)", e/n - se/sn, n; else printf "—"}'
}
own=$(awk '/^Time = /{t=$3; sub(/s$/, "", t)}
  /^rigidBodyMotionSolver: sub-steps .* inverted /{
    n++
    for (i=1;i<=NF;i++) {
      if ($i=="quality" && (q=="" || $(i+1)+0 < q)) {q=$(i+1)+0; tq=t}
      if ($i=="non-orthogonality" && $(i+1)+0 > a) {a=$(i+1)+0; ta=t}
      if ($i=="inverted" && $(i+1)+0 > inv) inv=$(i+1)+0
      if ($i=="wall") w+=$(i+1)
    }
  }
  END{if (n == 0) print "—"; else printf "%d steps: min mean-ratio quality %.4f (t = %s), max non-orthogonality %.2f° (t = %s), inverted %d; motion wall %.3f s per step", n, q, tq, a, ta, inv, w/n}' "$work/log.foamRun")

commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)
echo "Measured with \`tutorials/naca4415PitchingFlowOpenFOAM13/compare.sh\` at commit $commit; $(nproc --all) cores"
echo "($(awk -F': ' '/model name/{print $2; exit}' /proc/cpuinfo)), other jobs alongside; OpenFOAM 13"
echo "(third_party/OpenFOAM-13), serial runs; $steps steps. Runs started:"
sed 's/$/;/' "$work/started"
echo
echo "| | rbm (\`rigidBodyMotionSolver\`, librbmMotionSolverOF13.so) | OpenFOAM 13 \`displacementLaplacian\`, \`quadratic inverseDistance (airfoil)\` |"
echo "|---|---|---|"
echo "| foamRun -solver incompressibleFluid | $(flow rbm | cut -d'|' -f1) | $(flow laplacian | cut -d'|' -f1) |"
echo "| checkMesh of the times written: Mesh OK / times checked | $(cell rbm 2) / $(cell rbm 1) | $(cell laplacian 2) / $(cell laplacian 1) |"
echo "| … worst max non-orthogonality | $(cell rbm 3) | $(cell laplacian 3) |"
echo "| … worst max skewness | $(cell rbm 4) | $(cell laplacian 4) |"
echo "| … inverted cells (negative volume), worst | $(cell rbm 5) | $(cell laplacian 5) |"
echo "| … max non-orthogonality at the last time (initial mesh: 27.0900°) | $(cell rbm 6) | $(cell laplacian 6) |"
echo "| rbm's own check of every step | $own | — |"
echo "| motion: CPU s per step (movingMesh − static mesh, first $motionSteps steps) | $(motionCost rbm) | $(motionCost laplacian) |"
echo "| CPU s per flow step, motion included | $(flow rbm | cut -d'|' -f2) | $(flow laplacian | cut -d'|' -f2) |"
echo
echo "| t | α (°) | h | Cl, rbm | Cl, displacementLaplacian |"
echo "|---|---|---|---|---|"
coeff() { awk '!/^#/{print $1, $4}' "${folder[$1]}"/postProcessing/forceCoeffs/0/forceCoeffs.dat 2>/dev/null; }
for k in $(seq 1 10); do
  t=$(awk -v k="$k" -v n="$steps" -v d="$deltaT" 'BEGIN{printf "%g", k*n*d/10}')
  clr=$(coeff rbm | awk -v t="$t" '($1-t)^2 < 1e-12 {printf "%.3f", $2}')
  cll=$(coeff laplacian | awk -v t="$t" '($1-t)^2 < 1e-12 {printf "%.3f", $2}')
  awk -v t="$t" -v r="${clr:-—}" -v l="${cll:-—}" 'BEGIN{pi=atan2(0,-1);
     printf "| %g | %.2f | %.4f | %s | %s |\n", t, 10*sin(2*pi*t), 0.05*sin(2*pi*t), r, l}'
done
echo
join <(coeff rbm | awk '$1 >= 0.01 {printf "%.6f %s\n", $1, $2}') \
     <(coeff laplacian | awk '$1 >= 0.01 {printf "%.6f %s\n", $1, $2}') |
  awk '{d=$2-$3; if (d<0) d=-d; if (d>m) {m=d; t=$1}; n++}
       END{printf "Largest |Cl(rbm) − Cl(displacementLaplacian)| from t = 0.01 on (%d steps): %.2g at t = %g.\n", n, m, t}'
