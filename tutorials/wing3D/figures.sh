#!/usr/bin/env bash
# Regenerates the measured table of tutorials/wing3D/README.md: runs ./Allrun and ./Allrun
# -parallel at one resolution, then reads each run's logs (checkMesh of every time written,
# /usr/bin/time -v of each process) and writes the table to figures.md (and prints it),
# stamped with rbm's commit, the date, the machine and its load average.
#   ./figures.sh [-resolution R] [-skipRuns]
# -skipRuns tabulates the runs already in runs/ (made at the resolution of constant/polyMesh).
# Times are whole processes (moveDynamicMesh reads the mesh, moves it, checks it at every step
# and writes every step; pimpleFoam adds the flow) divided by the steps; the peak is the largest
# resident set of a process (of a rank, for 2 ranks).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
resolution=1
runs=true
while [[ $# -gt 0 ]]; do
  case $1 in
    -resolution) resolution=${2:?}; shift 2 ;;
    -skipRuns) runs=false; shift ;;
    *) echo "usage: $0 [-resolution R] [-skipRuns]" >&2; exit 2 ;;
  esac
done
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
loadBefore=$(cut -d' ' -f1-3 /proc/loadavg)
started=$(date -u '+%Y-%m-%d %H:%M UTC')
if $runs; then
  "$here/Allrun" -resolution "$resolution"
  "$here/Allrun" -parallel -resolution "$resolution"
fi
loadAfter=$(cut -d' ' -f1-3 /proc/loadavg)

# checkMesh of every time written, in each run folder (reconstructed for the decomposed runs)
for run in rbm laplacian rbmParallel laplacianParallel; do
  dir=$here/runs/$run
  [[ -d $dir ]] || continue
  (cd "$dir" && checkMesh -noZero -time '0:' > log.checkMesh.allTimes 2>&1 || true)
done

commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)
if [[ -n $(git -C "$here" status --porcelain -- . ../../openfoam ../../motionSolvers 2>/dev/null) ]]; then
  commit="$commit (with uncommitted changes)"
fi
machine="$(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores, $(free -g | awk '/^Mem:/{print $2}') GB"

python3 - "$here" "$resolution" "$commit" "$started" "$machine" "$loadBefore" "$loadAfter" <<'PY'
import glob, os, re, sys
here, resolution, commit, started, machine, load_before, load_after = sys.argv[1:8]

def read(path):
    try:
        with open(path) as f:
            return f.read()
    except OSError:
        return ""

def seconds(clock):   # /usr/bin/time's "h:mm:ss" or "m:ss.ss"
    parts = [float(p) for p in clock.split(":")]
    total = 0.0
    for p in parts:
        total = total * 60 + p
    return total

def process_figures(files):
    """(CPU s summed over the processes, wall s of the slowest, peak MiB of the largest)"""
    cpu = wall = peak = 0.0
    for path in files:
        text = read(path)
        user = re.search(r"User time \(seconds\): ([0-9.]+)", text)
        system = re.search(r"System time \(seconds\): ([0-9.]+)", text)
        clock = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([0-9:.]+)", text)
        rss = re.search(r"Maximum resident set size \(kbytes\): ([0-9]+)", text)
        if not (user and system and clock and rss):
            continue
        cpu += float(user.group(1)) + float(system.group(1))
        wall = max(wall, seconds(clock.group(1)))
        peak = max(peak, int(rss.group(1)) / 1024)
    return cpu, wall, peak

cells = re.search(r"^\s*cells:\s+([0-9]+)", read(os.path.join(here, "log.checkMesh")), re.M)
cells = int(cells.group(1)) if cells else 0
initial = re.search(r"non-orthogonality Max: ([0-9.]+)", read(os.path.join(here, "log.checkMesh")))

rows = []
for run, label, motion, ranks, log in [
        ("rbm", "rbm (plugin), moveDynamicMesh", True, 1, "log.moveDynamicMesh"),
        ("laplacian", "displacementLaplacian, moveDynamicMesh", True, 1, "log.moveDynamicMesh"),
        ("rbmParallel", "rbm (plugin), moveDynamicMesh -parallel", True, 2, "log.moveDynamicMesh"),
        ("laplacianParallel", "displacementLaplacian, moveDynamicMesh -parallel", True, 2, "log.moveDynamicMesh"),
        ("flow", "rbm (plugin), pimpleFoam", False, 1, "log.pimpleFoam"),
        ("flowParallel", "rbm (plugin), pimpleFoam -parallel", False, 2, "log.pimpleFoam")]:
    directory = os.path.join(here, "runs", run)
    if not os.path.isdir(directory):
        continue
    text = read(os.path.join(directory, log))
    steps = len(re.findall(r"^Time = ", text, re.M))
    finished = "\nEnd" in text
    name = "moveDynamicMesh" if motion else "pimpleFoam"
    files = glob.glob(os.path.join(directory, f"log.time.{name}*"))
    cpu, wall, peak = process_figures(files)
    if motion:
        check = read(os.path.join(directory, "log.checkMesh.allTimes"))
        negative = [int(n) for n in re.findall(r"Number of negative volume cells: ([0-9]+)", check)]
        inverted = str(max(negative)) if negative else ("0" if "non-orthogonality Max" in check else "–")
        orthogonality = [float(x) for x in re.findall(r"non-orthogonality Max: ([0-9.]+)", check)]
        worst = f"{max(orthogonality):.1f}°" if orthogonality else "–"
    else:
        lines = re.findall(r"^rigidBodyMotionSolver: sub-steps .* inverted ([0-9]+)", text, re.M)
        inverted = str(max(int(n) for n in lines)) if lines else "–"
        worst = "–"
    per = max(steps, 1)
    rows.append(f"| {label} | {ranks} | {steps}{'' if finished else ' (stopped)'} | {inverted} | {worst} | "
                f"{cpu / per:.2f} | {wall / per:.2f} | {peak:.0f} |")

table = [f"Measured by `tutorials/wing3D/figures.sh -resolution {resolution}` (rbm {commit}, started {started};",
         f"{machine}; load average {load_before} before, {load_after} after, shared with other jobs).",
         f"{cells} cells (resolution {resolution}); initial max non-orthogonality "
         f"{float(initial.group(1)):.1f}° (checkMesh)." if initial else "",
         "",
         "| run | ranks | steps | inverted cells (checkMesh, worst time) | max non-orthogonality (checkMesh, worst time) | CPU s per step | wall s per step | peak MiB (per rank) |",
         "|---|---:|---:|---:|---:|---:|---:|---:|"] + rows
compare = read(os.path.join(here, "runs", "rbmParallel", "log.comparison"))
if compare:
    table += ["", "Decomposed against serial (rbm, every processor point, relative to its shortest edge):", ""]
    table += ["    " + line for line in compare.strip().splitlines()]
text = "\n".join(table) + "\n"
with open(os.path.join(here, "figures.md"), "w") as f:
    f.write(text)
print(text)
PY
