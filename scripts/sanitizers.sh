#!/usr/bin/env bash
# Builds all of rbm (libraries, programs, tests) with AddressSanitizer, LeakSanitizer and
# UndefinedBehaviorSanitizer in build-asan/, and runs the whole test suite there.
#   scripts/sanitizers.sh             install dependencies, build, run ctest
#   scripts/sanitizers.sh -R regex    only the tests whose names match (ctest -R)
#   JOBS=1 scripts/sanitizers.sh      build and test with one job (default: all cores)
# Exits non-zero when the build fails, a test fails, or a sanitizer reports an error
# (memory error, leak, undefined behaviour: every report aborts the test that made it).
#
# Leaks: Open MPI (pulled in by PETSc) leaks in MPI_Init from plugins it unloads before the
# leak check, which no suppression can name (scripts/lsan.supp explains). Leak detection is
# therefore off for the programs that start MPI (those importing PetscInitialize or MPI_Init)
# and on for all others; address and undefined-behaviour checks are on everywhere.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh --deps   # the Debian packages of the normal build (idempotent, quiet)

build=build-asan
jobs=${JOBS:-$(nproc)}
start=$(date +%s)
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# The OpenFOAM plugins are left out: an instrumented librbmMotionSolver.so (or
# librbmMotionSolverOF13.so) cannot be loaded by
# OpenFOAM's uninstrumented programs (ASan's runtime must come first in the process), so its
# tests report themselves skipped here and run in the plain build; the core it calls is
# instrumented and tested through rbmMoveMesh and the HostMotionSolver tests.
cmake -S . -B $build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRBM_BUILD_OPENFOAM_PLUGIN=OFF \
  -DRBM_BUILD_OPENFOAM13_PLUGIN=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null

# The same options while building: gtest_discover_tests runs every test program to list its
# tests. include_if_exists: per-program overrides in $build/sanitizer-options/<program>.
mkdir -p $build/sanitizer-options
export ASAN_OPTIONS="detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:include_if_exists=$PWD/$build/sanitizer-options/%b"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"

if ! cmake --build $build -j "$jobs" >$build/build.log 2>&1; then
  grep -E -B2 -A8 "error|Error" $build/build.log | head -80
  echo "sanitizers: build failed (log: $build/build.log)" >&2
  exit 1
fi
built=$(date +%s)
echo "sanitizers: built in $((built - start)) s"

# Programs that start MPI: no leak detection (see above).
rm -f $build/sanitizer-options/*
for program in $build/tests/* $build/bin/*; do
  [ -f "$program" ] && [ -x "$program" ] || continue
  # (grep without -q: with pipefail, -q would make nm die of SIGPIPE and the test fail)
  if nm -D --undefined-only "$program" 2>/dev/null | grep -wE "PetscInitialize|MPI_Init|MPI_Init_thread" >/dev/null; then
    echo "detect_leaks=0" >$build/sanitizer-options/"$(basename "$program")"
  fi
done
echo "sanitizers: leak detection off for the MPI programs: $(ls $build/sanitizer-options | tr '\n' ' ')"

status=0
ctest --test-dir $build --output-on-failure -j "$jobs" --timeout 900 "$@" || status=$?
echo "sanitizers: tests ran in $(( $(date +%s) - built )) s (total $(( $(date +%s) - start )) s)"
if [ $status -ne 0 ]; then
  echo "sanitizers: FAILED: a test failed or a sanitizer reported an error (see above)" >&2
  exit $status
fi
