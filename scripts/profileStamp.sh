# Sourced by the profiling scripts (phaseProfile.sh, memoryProfile.sh): what heads their tables.
#
#   profileCommit REPOSITORY [OVERRIDE]
# The rbm commit: OVERRIDE when given (the binary is not this checkout's HEAD), else REPOSITORY's
# HEAD, marked "+ uncommitted changes" when its working tree differs from it.
profileCommit() {
    if [ -n "${2:-}" ]; then echo "$2"; return; fi
    local commit
    commit=$(git -C "$1" rev-parse --short HEAD 2>/dev/null || echo unknown)
    git -C "$1" diff --quiet 2>/dev/null || commit="$commit + uncommitted changes"
    echo "$commit"
}

#   profileHeading TITLE STAMP RUN_LOG
# The two lines of what was profiled and where, the run's step line from its log, a blank line.
profileHeading() {
    echo "$1"
    echo "$2"
    grep -E '^Time = ' "$3" | head -1 | tr -s ' '
    echo
}
