# Sourced by the memory profiling scripts (memoryProfile.sh, memoryProfileDecomposed.sh) after
# their own `function itemOf(frame)`: the peak snapshot of a massif file by item, as a markdown
# table. Every leaf of the peak's heap tree (an allocation site's bytes, or massif's "in N
# places" remainder) goes to the item of the first frame, from the allocation outwards, that
# itemOf names; the items are disjoint and add up to the heap at the peak.
#
#   awk -v points=N [-v other=TEXT] [-v scaleTo=M] -f ITEMS -f scripts/massifPeakItems.awk MASSIF_FILE
# points: the mesh points bytes are counted per; other: the item of the unnamed leaves; scaleTo:
# adds a column of MiB extrapolated to M points (every item taken to grow with the points).
/^heap_tree=peak/ { inPeak = 1; next }
/^snapshot=/ && inPeak { inPeak = 0 }
inPeak && /^ *n[0-9]+: / {
    match($0, /^ */); depth = RLENGTH
    line = substr($0, depth + 1)
    split(line, field, " ")
    children = field[1]; sub(/^n/, "", children); sub(/:$/, "", children)
    bytes = field[2]
    frame[depth] = line
    if (children + 0 == 0) {
        item = ""
        for (d = 1; d <= depth && item == ""; ++d) item = itemOf(frame[d])
        if (item == "") item = other != "" ? other : "other (below massif's threshold, libraries)"
        total[item] += bytes; heap += bytes
    }
}
function row(name, bytes, bold) {
    printf "| %s%s%s | %s%.1f%s | %s%.0f%s |", bold, name, bold, bold, bytes / 1048576, bold, bold, bytes / points, bold
    if (scaleTo > 0) printf " %s%.0f%s |", bold, bytes / points * scaleTo / 1048576, bold
    printf "\n"
}
END {
    if (scaleTo > 0) {
        scaled = sprintf("%d", scaleTo)
        while (scaled ~ /[0-9][0-9][0-9][0-9]/) sub(/[0-9][0-9][0-9]( |$)/, " &", scaled)
        sub(/  /, " ", scaled)
        printf "| item at the peak (heap) | MiB | bytes per point | MiB at %s points |\n|---|---:|---:|---:|\n", scaled
    } else {
        printf "| item at the peak (heap) | MiB | bytes per point |\n|---|---:|---:|\n"
    }
    n = 0
    for (item in total) keys[++n] = item
    for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (total[keys[j]] > total[keys[i]]) { t = keys[i]; keys[i] = keys[j]; keys[j] = t }
    for (i = 1; i <= n; ++i) row(keys[i], total[keys[i]], "")
    row("heap at the peak", heap, "**")
}
