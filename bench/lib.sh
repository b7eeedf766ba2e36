# shellcheck shell=sh disable=SC2154
# Sourced by the bench scripts after their options: the checks every one of
# them makes first, with its name (NAME) in the messages. Each expects
# $here (the project) and $build (the build folder) set.

# $data: the CFM 5.3 500 m set beside the project; skipped (exit 0) when
# it is absent, as the tests skip.
bench_data() {
    data="$here/../shared/cfm/CFM5.3/500m"
    if [ ! -d "$data" ]; then
        echo "$1: $data absent, skipped"
        exit 0
    fi
}

# $exe: the built faultmesh; exit 2 when it is not built.
bench_exe() {
    exe="$build/faultmesh"
    [ -x "$exe" ] || { echo "$1: build $exe first" >&2; exit 2; }
}

# $timer: GNU time, for wall and CPU time and peak memory; exit 2 without.
bench_timer() {
    timer=/usr/bin/time
    [ -x "$timer" ] || { echo "$1: needs GNU time (/usr/bin/time)" >&2; exit 2; }
}
