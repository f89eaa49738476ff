#!/usr/bin/env bash
# Runs OpenFOAM's wingMotion2D case (the flow drives a spring-mounted wing) with rbm moving the
# mesh (sixDoFRigidBodyDisplacement on the wing) and with OpenFOAM's own sixDoFRigidBodyMotion
# solver, at the tutorial's amplitude and at a larger one (Allrun -large), in copies of the
# tutorial's inputs, and prints the README's comparison as markdown: the body's trajectory, the
# wing's forces, the worst mesh quality (checkMesh at every time written), the cost per step.
#   ./compare.sh [-endTime T] [-jobs N] [-only RUNS|table] [work folder]
#       work folder  default ${TMPDIR:-/tmp}/wingMotion2D6DoF.compare
#       -endTime T   stop every run at T (default: controlDict's, 0.05)
#       -jobs N      runs at a time (default 1; each is serial)
#       -only RUNS   comma-separated runs among rbm, openfoam, rbm-large, openfoam-large to
#                    (re)run in an existing work folder, or table: print only
# Each run is the tutorial's Allrun in <work>/case (Allrun for rbm, -openfoam, -large):
#   rbm: <work>/case   openfoam: <work>/case/openfoam   rbm-large: <work>/case/large
#   openfoam-large: <work>/case/large-openfoam
# Times are OpenFOAM's ExecutionTime (CPU seconds of the process); rbm's own line per step gives
# its motion's wall time. OpenFOAM's morphing has no timer of its own: compare the whole steps.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
arguments="$*"
endTime=""
jobs=1
only=""
while [[ ${1:-} == -* ]]; do
  case $1 in
    -endTime) endTime=$2; shift 2 ;;
    -jobs) jobs=$2; shift 2 ;;
    -only) only=$2; shift 2 ;;
    *) echo "usage: $0 [-endTime T] [-jobs N] [-only RUNS|table] [work folder]" >&2; exit 2 ;;
  esac
done
work=${1:-${TMPDIR:-/tmp}/wingMotion2D6DoF.compare}
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
command -v pimpleFoam >/dev/null || { echo "compare.sh: pimpleFoam not found (apt-get install openfoam)" >&2; exit 2; }

plugin=""
if [[ -n ${RBM_PLUGIN_DIR:-} ]]; then
  [[ -f $RBM_PLUGIN_DIR/librbmMotionSolver.so ]] && plugin=$RBM_PLUGIN_DIR/librbmMotionSolver.so
elif [[ -d $here/../../build ]]; then
  plugin=$(find "$here/../../build" -name librbmMotionSolver.so -print -quit 2>/dev/null || true)
fi
runs=(openfoam openfoam-large)
if [[ -n $plugin ]]; then
  runs=(rbm openfoam rbm-large openfoam-large)
  plugin=$(cd "$(dirname "$plugin")" && pwd)/librbmMotionSolver.so
  export RBM_PLUGIN_DIR=$(dirname "$plugin")
fi
folderOf() { case $1 in rbm) echo "$work/case" ;; openfoam) echo "$work/case/openfoam" ;;
                        rbm-large) echo "$work/case/large" ;; openfoam-large) echo "$work/case/large-openfoam" ;; esac; }
optionsOf() { case $1 in rbm) echo "" ;; openfoam) echo "-openfoam" ;;
                         rbm-large) echo "-large" ;; openfoam-large) echo "-openfoam -large" ;; esac; }
stamp() { echo "$(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)"; }

if [[ $only != table ]]; then
  if [[ -z $only ]]; then
    rm -rf "$work"
    mkdir -p "$work/case"
    cp -r "$here/0.orig" "$here/constant" "$here/system" "$here/meshGeneration" "$here/Allrun" "$here/Allclean" "$work/case/"
    "$work/case/Allclean"
    echo "compare.sh: meshGeneration/Allmesh" >&2
    "$work/case/meshGeneration/Allmesh" > "$work/log.Allmesh" 2>&1 || { echo "compare.sh: Allmesh failed; see $work/log.Allmesh" >&2; exit 1; }
    todo=("${runs[@]}")
  else
    IFS=, read -r -a todo <<< "$only"
  fi
  runOne() {
    local r=$1
    echo "compare.sh: $r: Allrun $(optionsOf "$r")" >&2
    local log=$work/log.Allrun.$r
    { echo "$r: $(stamp)"; [[ $r == rbm* ]] && echo "plugin: $plugin ($(stat -c '%y' "$plugin" | cut -c1-16))"; } > "$work/started.$r"
    # shellcheck disable=SC2046
    "$work/case/Allrun" $(optionsOf "$r") ${endTime:+-endTime $endTime} > "$log" 2>&1
    echo $? > "$work/status.$r"
  }
  running=0
  for r in "${todo[@]}"; do
    runOne "$r" &
    running=$((running + 1))
    if (( running >= jobs )); then wait -n; running=$((running - 1)); fi
  done
  wait
fi

# --- Figures ------------------------------------------------------------------------------------
for r in "${runs[@]}"; do
  [[ -f $work/status.$r ]] || { echo "compare.sh: $r has not run in $work" >&2; exit 1; }
done
# checkQuality <checkMesh log>: "checked|failed checks, worst (t)|worst non-orthogonality (t)|
# worst skewness (t)|negative volumes, worst (t)"
checkQuality() {
  awk '
    /^Time = [^ ]+$/{t=$3; n++}
    /non-orthogonality Max:/{if ($4+0 > no) {no=$4+0; tno=t}}
    /Max skewness = /{for (i=1;i<=NF;i++) if ($i=="=") s=$(i+1); s=s+0; if (s > sk) {sk=s; tsk=t}}
    /Number of negative volume cells:/{v=$NF+0; if (v > inv) {inv=v; tinv=t}}
    /^Mesh OK/{f=0; if (f >= fw) {}}
    /Failed [0-9]+ mesh checks/{f=$2+0; if (f > fw) {fw=f; tfw=t}}
    END{
      printf "%d|%s|%.1f° (t = %s)|%.2f (t = %s)|%s", n, (fw==0 ? "0" : fw " (t = " tfw ")"), no, tno, sk, tsk,
             (inv==0 ? "0" : inv " (t = " tinv ")")
    }' "$1"
}
# state <pimpleFoam log> <t>: "y of the centre of rotation|rotation from the start (degrees)" at the
# last step with time <= t (the body's state is reported after its update, each step)
state() {
  awk -v T="$2" '
    function angle(s,   a) { gsub(/[()]/, "", s); split(s, a, " "); return atan2(a[4], a[1]) * 180 / atan2(0, -1) }
    /^Time = [^ ]+$/{t=$3+0}
    /Centre of rotation:/{c=$0; sub(/.*: *\(/, "", c); sub(/\).*/, "", c); split(c, p, " ")}
    /    Orientation:/{o=$0; sub(/.*Orientation: */, "", o); th=angle(o); if (a0=="") a0=th
                       if (t <= T + 1e-12) {y=p[2]; a=th - a0}}
    END{if (t < T * (1 - 1e-6)) printf "—|—"; else printf "%.6f|%.3f", y, a}' "$1"
}
# extremes <pimpleFoam log>: "min y|max y|min rotation|max rotation"
extremes() {
  awk '
    function angle(s,   a) { gsub(/[()]/, "", s); split(s, a, " "); return atan2(a[4], a[1]) * 180 / atan2(0, -1) }
    /Centre of rotation:/{c=$0; sub(/.*: *\(/, "", c); sub(/\).*/, "", c); split(c, p, " "); y=p[2]+0
                          if (n++ == 0) {y0=y; ymin=y; ymax=y}; if (y<ymin) ymin=y; if (y>ymax) ymax=y}
    /    Orientation:/{o=$0; sub(/.*Orientation: */, "", o); th=angle(o); if (a0=="") {a0=th; amin=0; amax=0}
                       d=th-a0; if (d<amin) amin=d; if (d>amax) amax=d}
    END{printf "%.4f … %.4f|%.2f° … %.2f°", ymin, ymax, amin, amax}' "$1"
}
# force <run folder> <t>: "Fy|Mz" (total, about (0.25 0.007 0.125)) at the last step with time <= t
force() {
  local f=$1/postProcessing/forces/0
  [[ -f $f/force.dat && -f $f/moment.dat ]] || { echo "—|—"; return; }
  paste <(tr -d '()' < "$f/force.dat") <(tr -d '()' < "$f/moment.dat") |
    awk -v T="$2" '!/^#/ {last=$1+0} !/^#/ && $1+0 <= T + 1e-12 {fy=$3; mz=$14} END{if (last < T * (1 - 1e-6)) printf "—|—"; else printf "%.2f|%.2f", fy, mz}'
}
lastTime() { awk '/^Time = [^ ]+$/{t=$3} END{print t}' "$1"; }

declare -A row
for r in "${runs[@]}"; do
  d=$(folderOf "$r")
  log=$d/log.pimpleFoam
  steps=$(grep -c '^ExecutionTime' "$log")
  row[$r,end]="exit status $(cat "$work/status.$r"), $steps steps, last t = $(lastTime "$log")"
  if grep -q '^End' "$log"; then row[$r,end]+=", End"
  elif grep -q 'sigFpe::sigHandler' "$log"; then row[$r,end]+=", floating point exception (sigFpe, in $(grep -m1 -A2 'sigFpe::sigHandler' "$log" | tail -1 | sed -E 's/^#[0-9]+ +Foam::([A-Za-z:]+).*/\1/'))"
  else row[$r,end]+=", $(grep -m1 -E 'FOAM FATAL|sigSegv|[Ee]rror' "$log" | sed 's/^ *//; s/|/\\|/g' | cut -c1-70)"; fi
  row[$r,dt]=$(awk '/^deltaT = /{d=$3+0; if (n==0 || d < m) m=d; n++; if (d < 1e-6 && c=="") c=t} /^Time = [^ ]+$/{t=$3}
                    END{printf "%.3g s", m; if (c != "") printf " (below 1e-6 s from t = %s on)", c}' "$log")
  row[$r,q]=$(checkQuality "$d/log.checkMesh")
  row[$r,lastq]=$(awk '/^Time = [^ ]+$/{t=$3} /non-orthogonality Max:/{no=$4} END{printf "%.4f° (t = %s)", no, t}' "$d/log.checkMesh")
  row[$r,ext]=$(extremes "$log")
  row[$r,cpu]=$(awk -v n="$steps" '/^ExecutionTime/{e=$3; c=$7} END{if (n>0) printf "%.3f (%.3f)", e/n, c/n; else printf "—"}' "$log")
  row[$r,own]=$(awk '/^rigidBodyMotionSolver: sub-steps .* inverted /{n++; for (i=1;i<=NF;i++) {
                       if ($i=="wall") w+=$(i+1); if ($i=="non-orthogonality" && $(i+1)+0 > a) a=$(i+1)+0; if ($i=="inverted" && $(i+1)+0 > v) v=$(i+1)+0}}
                     END{if (n==0) printf "—"; else printf "%.4f s wall per step (%d steps; its worst max non-orthogonality %.2f°, inverted %d)", w/n, n, a, v+0}' "$log")
done

commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)
cpu=$(awk -F': ' '/model name/{print $2; exit}' /proc/cpuinfo)
end=${endTime:-$(awk '/^endTime/{sub(";","",$2); print $2}' "$here/system/controlDict")}
echo "Measured with \`tutorials/wingMotion2D6DoF/compare.sh${arguments:+ $arguments}\` at commit $commit;"
echo "$(nproc --all) cores ($cpu), shared with other jobs; OpenFOAM v1912 (Debian), serial runs;"
echo "12 556 cells (snappyHexMesh + extrudeMesh, OpenFOAM's wingMotion tutorial), t = 0 … $end. Runs started:"
for r in "${runs[@]}"; do sed 's/$/;/' "$work/started.$r"; done
cell() { if [[ $1 == rbm* && -z $plugin ]]; then echo "not run (plugin not built)"; else echo "${row[$1,$2]}" | cut -d'|' -f"${3:-1-}"; fi; }
for amp in "" -large; do
  echo
  if [[ -z $amp ]]; then echo "**The tutorial's amplitude** (angularMomentum (0 0 -2), OpenFOAM's values):"
  else echo "**The larger amplitude** (\`-large\`: angularMomentum (0 0 -60), the wing kicked nose up at 29 rad/s):"; fi
  echo
  echo "| | rbm (\`sixDoFRigidBodyDisplacement\` + \`rigidBodyMotionSolver\`) | OpenFOAM \`sixDoFRigidBodyMotion\` |"
  echo "|---|---|---|"
  a=rbm$amp; b=openfoam$amp
  echo "| pimpleFoam | $(cell "$a" end) | $(cell "$b" end) |"
  echo "| smallest time step (Courant 0.9) | $(cell "$a" dt) | $(cell "$b" dt) |"
  echo "| checkMesh at the times written: times checked | $(cell "$a" q 1) | $(cell "$b" q 1) |"
  echo "| … failed checks, worst (the initial mesh fails 1: one face of skewness 4.77) | $(cell "$a" q 2) | $(cell "$b" q 2) |"
  echo "| … inverted cells (negative volume), worst | $(cell "$a" q 5) | $(cell "$b" q 5) |"
  echo "| … worst max non-orthogonality (initial 49.8°) | $(cell "$a" q 3) | $(cell "$b" q 3) |"
  echo "| … max non-orthogonality at the last time written | $(cell "$a" lastq) | $(cell "$b" lastq) |"
  echo "| … worst max skewness (initial 4.77) | $(cell "$a" q 4) | $(cell "$b" q 4) |"
  echo "| body: centre of rotation y (m), rotation from the start (negative: clockwise, nose up), range over the run | $(cell "$a" ext 1), $(cell "$a" ext 2) | $(cell "$b" ext 1), $(cell "$b" ext 2) |"
  echo "| pimpleFoam CPU s per step, motion included (wall) | $(cell "$a" cpu) | $(cell "$b" cpu) |"
  echo "| … rbm − OpenFOAM, CPU s per step (the motion's cost difference: same flow solver, same steps) | $(awk -v x="$(cell "$a" cpu)" -v y="$(cell "$b" cpu)" 'BEGIN{if (x+0 > 0 && y+0 > 0) printf "%+.4f", x - y; else printf "—"}') | |"
  echo "| rbm's own motion timer | $(cell "$a" own) | — |"
  echo
  echo "| t (s) | y rbm (m) | y OpenFOAM (m) | rotation rbm (°) | rotation OpenFOAM (°) | Fy rbm (N) | Fy OpenFOAM (N) | Mz rbm (N m) | Mz OpenFOAM (N m) |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for t in $(awk -v e="$end" 'BEGIN{for (k=1;k<=5;k++) printf "%g ", k*e/5}'); do
    sa="—|—"; fa="—|—"
    if [[ -n $plugin ]]; then sa=$(state "$(folderOf "$a")/log.pimpleFoam" "$t"); fa=$(force "$(folderOf "$a")" "$t"); fi
    sb=$(state "$(folderOf "$b")/log.pimpleFoam" "$t"); fb=$(force "$(folderOf "$b")" "$t")
    echo "| $t | ${sa%|*} | ${sb%|*} | ${sa#*|} | ${sb#*|} | ${fa%|*} | ${fb%|*} | ${fa#*|} | ${fb#*|} |"
  done
  if [[ -n $plugin ]]; then
    echo
    # Step by step while both runs are at the same time (to 1e-3 of it: the time step adapts to
    # the Courant number, so the runs may part).
    fa=$(folderOf "$a")/postProcessing/forces/0; fb=$(folderOf "$b")/postProcessing/forces/0
    common=$(awk -v x="$(lastTime "$(folderOf "$a")/log.pimpleFoam")" -v y="$(lastTime "$(folderOf "$b")/log.pimpleFoam")" -v e="$end" \
             'BEGIN{m = (x + 0 < y + 0 ? x : y); w = e / 5; printf "%g", int(m / w + 1e-6) * w}')
    paste <(tr -d '()' < "$fa/force.dat" | grep -v '^#') <(tr -d '()' < "$fa/moment.dat" | grep -v '^#') \
          <(tr -d '()' < "$fb/force.dat" | grep -v '^#') <(tr -d '()' < "$fb/moment.dat" | grep -v '^#') |
      awk -v W="$common" 'function abs(x) {return x < 0 ? -x : x}
           NF >= 40 { if (abs($1 - $21) > 1e-3 * abs($21)) {parted = $1; exit}
                      if ($1 <= W + 1e-12) {
                        if (abs($23) > wf) wf = abs($23); if (abs($34) > wm) wm = abs($34)
                        if (abs($3 - $23) > wdf) wdf = abs($3 - $23); if (abs($14 - $34) > wdm) wdm = abs($14 - $34) }
                      n++; t = $1
                      if (abs($23) > fmax) fmax = abs($23); if (abs($34) > mmax) mmax = abs($34)
                      if (abs($3 - $23) > df) {df = abs($3 - $23); tf = $1}
                      if (abs($14 - $34) > dm) {dm = abs($14 - $34); tm = $1} }
           END { printf "Step by step, %d steps at the same time (to t = %s%s): largest |Fy(rbm) − Fy(OpenFOAM)| %.3g N at t = %s (largest |Fy| %.4g N), largest |Mz(rbm) − Mz(OpenFOAM)| %.3g N m at t = %s (largest |Mz| %.4g N m).\n",
                        n, t, (parted == "" ? "" : "; the time steps part after it"), df, tf, fmax, dm, tm, mmax
                 if (W + 0 < t + 0) printf "Up to t = %s, the last time both runs wrote: largest |Fy(rbm) − Fy(OpenFOAM)| %.3g N (largest |Fy| %.4g N), largest |Mz(rbm) − Mz(OpenFOAM)| %.3g N m (largest |Mz| %.4g N m).\n", W, wdf, wf, wdm, wm }'
  fi
done
