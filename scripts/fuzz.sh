#!/usr/bin/env bash
# Coverage-guided fuzzing of rbm's input readers (fuzz/README.md).
#   scripts/fuzz.sh [SECONDS_PER_TARGET]      default 45; two targets run at a time
#   scripts/fuzz.sh --ci                      deterministic, for CI (.ci/run): see below
#   FUZZ_TARGETS="dictionaryFuzzer polyMeshFuzzer" scripts/fuzz.sh 600   only those targets
#   JOBS=1 scripts/fuzz.sh --ci               build with one job (default: all cores)
#
# Installs clang-14 and its sanitizer/libFuzzer runtimes from Debian 12 when missing, builds
# the targets of fuzz/ in build-fuzz/, then runs each one for SECONDS_PER_TARGET seconds on
# its seeds (fuzz/corpus/<target>), its regression inputs (fuzz/regressions/<target>) and
# the inputs earlier runs found (build-fuzz/corpus/<target>, kept between runs).
#
# --ci: the same run every time. Each target executes a fixed number of inputs (ci_runs
# below, sized for about a minute each on the 2-core CI machine; FUZZ_CI_RUNS_<target>
# overrides one) with -seed=1, starting from the committed corpus and regressions only
# (build-fuzz/ci-corpus/<target> is emptied first and receives what the run finds), without
# address randomisation (setarch -R), without comparison-operand mutations (-use_cmp=0) and
# with a fixed sandbox folder: two runs execute the same inputs, so a finding reproduces with
# the same command on any machine with the same clang.
# Exits non-zero when any target crashed, hung (-timeout), ran out of memory (-rss_limit_mb,
# and any single allocation above it), leaked, or a sanitizer reported an error; the
# reproducer's path and the command to replay it are printed.
set -euo pipefail
cd "$(dirname "$0")/.."

ci=0
if [ "${1:-}" = "--ci" ]; then
  ci=1
  shift
fi
seconds=${1:-45}
jobs=${JOBS:-$(nproc)}
targets=(${FUZZ_TARGETS:-dictionaryFuzzer asciiListFuzzer binaryListFuzzer pointFieldFuzzer polyMeshFuzzer})
parallel=${FUZZ_PARALLEL:-2}

# clang-14 brings libFuzzer and the sanitizers with libclang-rt-14-dev (libclang_rt.fuzzer*.a).
packages=(clang-14 libclang-rt-14-dev cmake make pkg-config zlib1g-dev libdeflate-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "fuzz: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build=build-fuzz
start=$(date +%s)
cmake -S fuzz -B $build -DCMAKE_CXX_COMPILER=clang++-14 -DRBM_FUZZ=ON >/dev/null
cmake --build $build -j "$jobs" -- --no-print-directory | grep -E "error|warning|Error" || true
for t in "${targets[@]}"; do
  [ -x "$build/$t" ] || { echo "fuzz: $build/$t was not built" >&2; exit 1; }
done
if [ $ci -eq 1 ]; then
  echo "fuzz: built in $(( $(date +%s) - start )) s; CI mode: ${targets[*]} for a fixed number of inputs each (-seed=1), $parallel at a time"
else
  echo "fuzz: built in $(( $(date +%s) - start )) s; fuzzing ${targets[*]} for $seconds s each, $parallel at a time"
fi

# Longest input per target: a little above the largest seed (whole meshes need more).
max_len() {
  case $1 in
    polyMeshFuzzer) echo 65536 ;;
    dictionaryFuzzer|pointFieldFuzzer) echo 8192 ;;
    *) echo 16384 ;;
  esac
}

# CI mode: inputs executed per target, about a minute each on the 2-core CI machine at the
# rates measured there (dictionary ~90/s, asciiList ~1800/s, binaryList ~7000/s, pointField
# ~600/s, polyMesh ~450/s; fuzz/README.md).
ci_runs() {
  local override
  override=FUZZ_CI_RUNS_$1
  if [ -n "${!override:-}" ]; then echo "${!override}"; return; fi
  case $1 in
    dictionaryFuzzer) echo 6000 ;;
    asciiListFuzzer) echo 100000 ;;
    binaryListFuzzer) echo 400000 ;;
    pointFieldFuzzer) echo 36000 ;;
    polyMeshFuzzer) echo 27000 ;;
    *) echo 20000 ;;
  esac
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
unset FOAM_CASE FOAM_CASESRC

run_target() {
  local t=$1
  local corpus=$build/corpus/$t artifacts=$build/artifacts/$t/
  local limit=(-max_total_time="$seconds")
  local launcher=()
  if [ $ci -eq 1 ]; then
    # Deterministic: a fixed number of inputs from a fixed seed, over the committed inputs
    # only (-max_total_time only guards against a machine far slower than expected).
    corpus=$build/ci-corpus/$t
    rm -rf "$corpus"
    # -use_cmp=0: the operands of traced comparisons include heap addresses, which differ
    # between runs even without ASLR (measured: two runs parted after ~500 inputs); without
    # them two runs execute the same inputs (checked on dictionaryFuzzer and pointFieldFuzzer).
    limit=(-runs="$(ci_runs "$t")" -seed=1 -use_cmp=0 -max_total_time=900)
    # Same addresses (no ASLR) and the same sandbox path in every run.
    if setarch "$(uname -m)" -R true 2>/dev/null; then launcher=(setarch "$(uname -m)" -R); fi
    export RBM_FUZZ_SANDBOX=$PWD/$build/ci-sandbox/$t
  fi
  mkdir -p "$corpus" "$artifacts" fuzz/regressions/$t
  local began
  began=$(date +%s)
  set +e
  "${launcher[@]}" "$build/$t" "${limit[@]}" -max_len="$(max_len "$t")" -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -timeout=10 -dict=fuzz/foam.dict -artifact_prefix="$artifacts" -print_final_stats=1 \
    "$corpus" "fuzz/corpus/$t" "fuzz/regressions/$t" >"$build/$t.log" 2>&1
  local status=$?
  set -e
  local stats
  stats=$(grep -E "^stat::(number_of_executed_units|new_units_added|peak_rss_mb)" "$build/$t.log" | sed 's/stat:://' | tr -s ' \n' ' ')
  # One line per run, for fuzz/README.md's account of the time fuzzed.
  echo "$(date -u +%FT%TZ) $t seconds=$(( $(date +%s) - began )) exit=$status $stats$([ $ci -eq 1 ] && echo ' ci')" >>$build/history.log
  if [ $status -ne 0 ]; then
    echo "fuzz: $t FAILED (exit $status) $stats"
    grep -E "^==[0-9]+==ERROR|SUMMARY|runtime error|ERROR: libFuzzer|terminate called|what\(\)" "$build/$t.log" | head -8 | sed 's/^/    /'
    local reproducer
    reproducer=$(grep -oE "Test unit written to [^ ]+" "$build/$t.log" | tail -1 | cut -d' ' -f5- || true)
    echo "    log: $build/$t.log"
    if [ -n "$reproducer" ]; then
      echo "    reproducer: $reproducer"
      echo "    replay: $build/$t $reproducer   (then add it as fuzz/regressions/$t/<name> once fixed)"
    fi
    return 1
  fi
  echo "fuzz: $t ok: $stats"
}

# Two targets at a time (one per core); every failure is reported, the exit status says whether any.
failed=0
pids=()
names=()
for t in "${targets[@]}"; do
  run_target "$t" &
  pids+=($!)
  names+=("$t")
  if [ ${#pids[@]} -ge "$parallel" ]; then
    wait "${pids[0]}" || failed=1
    pids=("${pids[@]:1}")
    names=("${names[@]:1}")
  fi
done
for pid in "${pids[@]}"; do
  wait "$pid" || failed=1
done
echo "fuzz: total $(( $(date +%s) - start )) s"
if [ $failed -ne 0 ]; then
  echo "fuzz: FAILED: a target crashed, hung, ran out of memory or leaked (see above)" >&2
  exit 1
fi
