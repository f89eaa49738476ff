#!/usr/bin/env bash
# Builds all of rbm (libraries, programs, tests) with AddressSanitizer, LeakSanitizer and
# UndefinedBehaviorSanitizer in build-asan/, and runs the whole test suite there.
#   scripts/sanitizers.sh             install dependencies, build, run ctest
#   scripts/sanitizers.sh -R regex    only the tests whose names match (ctest -R)
# Exits non-zero when the build fails, a test fails, or a sanitizer reports an error
# (memory error, leak, undefined behaviour: every report aborts the test that made it).
#
# Leaks: Open MPI (pulled in by PETSc) leaks in MPI_Init and its plugins, and libraries
# loaded with dlopen leak their initialisation; scripts/lsan.supp suppresses exactly those
# libraries, so leaks in rbm's own code (and in PETSc objects rbm fails to destroy) are still
# reported.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh --deps   # the Debian packages of the normal build (idempotent, quiet)

build=build-asan
start=$(date +%s)
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B $build -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null

# The same options while building: gtest_discover_tests runs every test program to list its tests.
export ASAN_OPTIONS="detect_leaks=1:fast_unwind_on_malloc=0:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Open MPI's shared-memory transport maps segments ASan cannot track; vader's single-copy
# mechanism (cross-memory attach) is refused inside containers anyway.
export OMPI_MCA_btl_vader_single_copy_mechanism=none

if ! cmake --build $build -j "$(nproc)" >$build/build.log 2>&1; then
  grep -E -B2 -A8 "error|Error" $build/build.log | head -80
  echo "sanitizers: build failed (log: $build/build.log)" >&2
  exit 1
fi
built=$(date +%s)
echo "sanitizers: built in $((built - start)) s"

status=0
ctest --test-dir $build --output-on-failure -j "$(nproc)" --timeout 900 "$@" || status=$?
echo "sanitizers: tests ran in $(( $(date +%s) - built )) s (total $(( $(date +%s) - start )) s)"
if [ $status -ne 0 ]; then
  echo "sanitizers: FAILED: a test failed or a sanitizer reported an error (see above)" >&2
  exit $status
fi
