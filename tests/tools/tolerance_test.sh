#!/bin/bash
# Fault tolerance of `faultmesh remesh` (issue 7, item 5):
#  - a broken fault among the synthetic system's (garbage in a VRTX line;
#    a file cut off mid-triangle; every triangle degenerate, so that it
#    fails after reading): exit 1, stderr and report.json name the file
#    (and line), every other fault is meshed and written, and no
#    junction of the good faults is made with the broken one; its
#    neighbours come out as they do when it is left out of the run;
#  - interrupted runs: SIGTERM, SIGINT and SIGHUP at moments from start-up
#    to the writing of the outputs leave no temporary file, and every file
#    under a real name is byte-identical to the one of an uninterrupted
#    run (report.json, which holds times, parses and lists the same
#    faults); SIGKILL, which cannot be caught, may leave hidden temporary
#    files but no truncated file under a real name;
#  - the same with a few CFM faults when ../shared/cfm is there (a longer
#    run, so that signals land in the fit and connect phases too).
# MODE: broken (the first part), interrupt (the rest), or interrupt-quick
# (fewer and shorter runs, no CFM: for the sanitizer build, whose runs are
# ten times slower).
# usage: tolerance_test.sh FAULTMESH TMPDIR MODE [CFM_DIR]
set -u
exe=$1 tmp=$2 mode=$3 cfm=${4:-}
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"
# Background jobs get SIGINT ignored unless job control is on (and a
# signal ignored at start stays ignored, as for nohup).
set -m

expect_rc 0 "synth" "$exe" synth -o "$tmp/in"
main=SYNT-MAIN-SS-Main_strike_slip_fault-SYN1
[ -f "$tmp/in/$main.ts" ] && ok || bad "synthetic input $main.ts missing"

if [ "$mode" = broken ]; then
    # The reference: all ten, and the T junctions of the main fault made.
    expect_rc 0 "clean run" "$exe" remesh --quiet -o "$tmp/ref" "$tmp/in"
    [ "$(json "$tmp/ref/report.json" "sum(1 for j in r['connect']['junctions'] if '$main' in j['faults'] and j['type'] != 'unjoined')")" = 3 ] &&
        ok || bad "clean run: the main fault's three T junctions not made"

    # Without the main fault at all: what its neighbours should fall back to.
    mkdir -p "$tmp/in8" && cp "$tmp/in"/*.ts "$tmp/in8/" && rm "$tmp/in8/$main.ts"
    expect_rc 0 "run without the main fault" "$exe" remesh --quiet -o "$tmp/out8" "$tmp/in8"

    broken_case() { # name, folder with the broken main fault, expected "FILE:LINE: "
        local what=$1 in=$2 where=$3 out=$tmp/out_$1
        expect_rc 1 "$what: remesh" "$exe" remesh --quiet -o "$out" "$in"
        grep -qF "$where" "$tmp/err" && ok || bad "$what: stderr lacks '$where': $(cat "$tmp/err")"
        local r=$out/report.json
        if [ ! -f "$r" ]; then
            bad "$what: no report.json"
            return
        fi
        [ "$(json "$r" "r['summary']['faults'], r['summary']['meshed'], r['summary']['failed']")" = "10 9 1" ] &&
            ok || bad "$what: summary $(json "$r" "r['summary']")"
        [ "$(json "$r" "[(f['status'], f['error']) for f in r['faults'] if f['file'].endswith('$main.ts')][0][0]")" = error ] &&
            ok || bad "$what: the broken fault is not reported as an error"
        json "$r" "[f['error'] for f in r['faults'] if f['file'].endswith('$main.ts')][0]" | grep -qF "$where" &&
            ok || bad "$what: report error lacks '$where'"
        # every other fault meshed and written, in every format
        local n
        n=$(ls "$out"/*.ts 2>/dev/null | wc -l)
        [ "$n" = 9 ] && ok || bad "$what: $n .ts files written, expected 9"
        [ ! -e "$out/$main.ts" ] && ok || bad "$what: the broken fault was written"
        for f in mesh.vtu mesh.msh mesh.stl mesh.obj mesh.exo mesh.eqsim mesh.rsqsim model.igs; do
            [ -s "$out/$f" ] && ok || bad "$what: $f not written"
        done
        [ "$(grep -c '^2 [0-9]* "SYNT-' "$out/mesh.msh")" = 9 ] && ! grep -q "\"$main\"" "$out/mesh.msh" &&
            ok || bad "$what: mesh.msh does not name the 9 good faults"
        # no junction made with it; the neighbours as without it
        [ "$(json "$r" "sum(1 for j in r['connect']['junctions'] if '$main' in j['faults'] and j['type'] != 'unjoined')")" = 0 ] &&
            ok || bad "$what: a junction with the broken fault is made"
        for f in SYNT-MAIN-TJNC-T_junction_gap_fault-SYN1 SYNT-MAIN-XOVR-Overshooting_fault-SYN1; do
            cmp -s "$out/$f.ts" "$tmp/out8/$f.ts" && ok ||
                bad "$what: neighbour $f differs from the run without the broken fault"
        done
    }

    # garbage in a VRTX line
    mkdir -p "$tmp/garbage" && cp "$tmp/in"/*.ts "$tmp/garbage/"
    line=$(grep -n '^VRTX' "$tmp/in/$main.ts" | sed -n 50p | cut -d: -f1)
    awk -v n="$line" 'NR == n { $3 = "garbage" } { print }' "$tmp/in/$main.ts" >"$tmp/garbage/$main.ts"
    broken_case garbage "$tmp/garbage" "$main.ts:$line: "

    # cut off in the middle of a triangle
    mkdir -p "$tmp/cut" && cp "$tmp/in"/*.ts "$tmp/cut/"
    line=$(grep -n '^TRGL' "$tmp/in/$main.ts" | sed -n 100p | cut -d: -f1)
    { head -n $((line - 1)) "$tmp/in/$main.ts"; printf 'TRGL 1500 15'; } >"$tmp/cut/$main.ts"
    broken_case cut "$tmp/cut" "$main.ts:$line: "

    # read, but nothing left of it to fit: every triangle degenerate (its
    # vertices on one line)
    mkdir -p "$tmp/flat" && cp "$tmp/in"/*.ts "$tmp/flat/"
    awk '$1 == "VRTX" { $4 = 3750000; $5 = -1000 } { print }' "$tmp/in/$main.ts" >"$tmp/flat/$main.ts"
    broken_case flat "$tmp/flat" "$main.ts: $main: nothing left after repair"
fi

# Interrupted runs. The outputs of a run are deterministic, so a file under
# a real name is complete exactly when it equals the uninterrupted run's.
# check_after NAME OUT REF RC SIG ALLOW_TMP
interrupted=0
check_after() {
    local what=$1 out=$2 ref=$3 rc=$4 sig=$5 allow_tmp=$6 f
    if [ "$rc" = $((128 + sig)) ]; then
        interrupted=$((interrupted + 1))
    elif [ "$rc" != 0 ]; then
        bad "$what: exit $rc, neither the signal ($((128 + sig))) nor 0 (finished first)"
    fi
    if [ -d "$out" ]; then
        local left
        left=$(find "$out" -name '*.tmp.*')
        if [ "$allow_tmp" = 0 ]; then
            [ -z "$left" ] && ok || bad "$what: temporary files left: $left"
        else
            # what SIGKILL may leave: hidden, and named after an output
            for f in $left; do
                case $(basename "$f") in
                    .*.tmp.*) ok ;;
                    *) bad "$what: temporary file not hidden: $f" ;;
                esac
            done
        fi
        for f in "$out"/*; do
            [ -e "$f" ] || continue
            local b
            b=$(basename "$f")
            if [ "$b" = report.json ]; then
                [ "$(json "$f" "[f['status'] for f in r['faults']]")" = \
                  "$(json "$ref/report.json" "[f['status'] for f in r['faults']]")" ] && ok ||
                    bad "$what: report.json incomplete or different"
            else
                cmp -s "$f" "$ref/$b" && ok || bad "$what: $b differs from the uninterrupted run's"
            fi
        done
    fi
}

# SIG DELAYS... on INPUT with OPTIONS, against REF; a delay wD is D
# seconds after the first output file is begun (a temporary appears).
rounds() {
    local sig=$1 input=$2 ref=$3 opts=$4 d pid rc out
    shift 4
    for d in "$@"; do
        out=$tmp/sig_${sig}_$d
        "$exe" remesh --quiet $opts -o "$out" "$input" >/dev/null 2>"$tmp/err" &
        pid=$!
        if [ "${d#w}" != "$d" ]; then
            until compgen -G "$out/.*.tmp.*" >/dev/null || ! kill -0 "$pid" 2>/dev/null; do
                sleep 0.005
            done
        fi
        sleep "${d#w}"
        kill -s "$sig" "$pid" 2>/dev/null
        # (the shell's job report of the signal is noise here)
        { wait "$pid"; } 2>/dev/null
        rc=$?
        check_after "$sig after ${d}s" "$out" "$ref" "$rc" "$(kill -l "$sig")" \
            "$([ "$sig" = KILL ] && echo 1 || echo 0)"
        rm -rf "$out"
    done
}

# REF for INPUT with OPTIONS; sets t, its run time
reference() {
    local t0
    t0=$(date +%s.%N)
    expect_rc 0 "reference $1" "$exe" remesh --quiet $3 -o "$1" "$2"
    t=$(python3 -c "import sys; print(float(sys.argv[2]) - float(sys.argv[1]))" "$t0" "$(date +%s.%N)")
}
# delays at fractions of the run time t
at() { python3 -c "import sys; t = float(sys.argv[1]); print(' '.join('%.3f' % (float(f) * t) for f in sys.argv[2:]))" "$t" "$@"; }

if [ "$mode" = interrupt ]; then
    # 250 m triangles: ~2.5 s here, the last fifth of it writing 75 MB of
    # outputs; signals spread over the run, then during the writes (when
    # the first is begun, and a few moments on)
    opts="--size 250"
    reference "$tmp/ref" "$tmp/in" "$opts"
    rounds TERM "$tmp/in" "$tmp/ref" "$opts" $(at 0.02 0.1 0.3 0.6) w0 w0.02 w0.1 w0.2 w0.3
    rounds INT "$tmp/in" "$tmp/ref" "$opts" $(at 0.1 0.6) w0.01 w0.15
    rounds HUP "$tmp/in" "$tmp/ref" "$opts" $(at 0.3) w0.05
    rounds KILL "$tmp/in" "$tmp/ref" "$opts" $(at 0.6) w0 w0.05 w0.15 w0.25
    # most signals must have landed while it ran, or the test proved nothing
    [ "$interrupted" -ge 16 ] && ok || bad "only $interrupted of 20 runs were interrupted (run time ${t}s)"
elif [ "$mode" = interrupt-quick ]; then
    opts="--size 500"
    reference "$tmp/ref" "$tmp/in" "$opts"
    rounds TERM "$tmp/in" "$tmp/ref" "$opts" $(at 0.1 0.5) w0 w0.1
    rounds INT "$tmp/in" "$tmp/ref" "$opts" w0.05
    rounds HUP "$tmp/in" "$tmp/ref" "$opts" w0.02
    rounds KILL "$tmp/in" "$tmp/ref" "$opts" w0 w0.1
    [ "$interrupted" -ge 6 ] && ok || bad "only $interrupted of 8 runs were interrupted (run time ${t}s)"
fi

# A few CFM faults (every 40th file of the 500 m set), when present.
if [ "$mode" != interrupt ]; then
    :
elif [ -n "$cfm" ] && [ -d "$cfm/CFM5.3/500m" ]; then
    mkdir -p "$tmp/cfm"
    cfm=$(cd "$cfm" && pwd)
    ls "$cfm/CFM5.3/500m"/*.ts | awk 'NR % 40 == 1' | while read -r f; do ln -s "$f" "$tmp/cfm/"; done
    opts="--size 1000"
    reference "$tmp/cfmref" "$tmp/cfm" "$opts"
    interrupted=0
    rounds TERM "$tmp/cfm" "$tmp/cfmref" "$opts" $(at 0.2 0.5 0.8) w0 w0.1
    rounds INT "$tmp/cfm" "$tmp/cfmref" "$opts" $(at 0.5) w0.05
    rounds KILL "$tmp/cfm" "$tmp/cfmref" "$opts" $(at 0.8) w0.05
    [ "$interrupted" -ge 7 ] && ok || bad "CFM: only $interrupted of 9 runs were interrupted (run time ${t}s)"
else
    echo "tolerance: no CFM in ${cfm:-(not given)}, its rounds skipped"
fi

echo "tolerance: $pass passed, $fail failed"
[ "$fail" = 0 ] && rm -rf "$tmp"
[ "$fail" = 0 ]
