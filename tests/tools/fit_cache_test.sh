#!/bin/bash
# The fit cache (issue 20, "fit once"): `faultmesh demo` with a cache
# fitted once, read back in later runs (all hits, at another size too),
# and the outputs byte for byte those of a run without the cache
# (report.json differs only in the cache's fields and the times); an
# option that reaches the fit is a miss; a truncated or damaged model is
# rejected, the fault fitted again and its model stored anew; the default
# place ($XDG_CACHE_HOME/faultmesh, else ~/.cache/faultmesh) and the
# settings file's `cache`; a cache that cannot be made is a note, not a
# failure; two runs filling one cache at once.
# usage: fit_cache_test.sh FAULTMESH TMPDIR
set -u
exe=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp"
. "$(dirname "$0")/cli_lib.sh"
# never the real cache of whoever runs the tests
export XDG_CACHE_HOME="$tmp/xdg" HOME="$tmp/home"
c="$tmp/cache"
nfaults=10

# what the report says of the cache: hits misses rejected enabled
cache_of() { json "$1/report.json" "'%d %d %d %s' % (r['fit_cache']['hits'], r['fit_cache']['misses'], r['fit_cache']['rejected'], r['fit_cache']['enabled'])"; }
# every output but report.json the same as the reference run's
same_outputs() { # what dir
    if diff -r -x report.json "$tmp/ref" "$2" >/dev/null; then ok; else
        bad "$1: outputs differ from the run without the cache: $(diff -rq -x report.json "$tmp/ref" "$2" | head -3)"
    fi
}
# report.json the same as the reference's but for the cache and the times
same_report() { # what dir
    python3 - "$tmp/ref" "$2" <<'PY' && ok || bad "$1: report.json differs beyond the cache and the times"
import json, sys
def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items()
                if not k.startswith('time') and k not in ('fit_cache', 'fit_cached')}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v
# the output folder (which holds the demo's input) named alike
a, b = (strip(json.loads(open(d + '/report.json').read().replace(d, 'DIR'))) for d in sys.argv[1:3])
sys.exit(0 if a == b else 1)
PY
}

# 1. Without the cache: the reference; it reads and writes nothing.
expect_rc 0 "demo --no-cache" "$exe" demo --quiet --no-cache -o "$tmp/ref"
[ ! -e "$tmp/xdg" ] && [ ! -e "$tmp/home" ] && ok || bad "--no-cache made a cache folder"
[ "$(cache_of "$tmp/ref")" = "0 0 0 False" ] && ok || bad "--no-cache: report says $(cache_of "$tmp/ref")"
[ "$(json "$tmp/ref/report.json" "sum('fit_cached' in f for f in r['faults'])")" = 0 ] && ok ||
    bad "--no-cache: faults say fit_cached"

# 2. Cold: every fault fitted and stored; warm: every model read.
expect_rc 0 "demo, cold cache" "$exe" demo --quiet --cache "$c" -o "$tmp/cold"
[ "$(cache_of "$tmp/cold")" = "0 $nfaults 0 True" ] && ok || bad "cold: $(cache_of "$tmp/cold")"
[ -f "$c/CACHEDIR.TAG" ] && ok || bad "no CACHEDIR.TAG"
[ "$(find "$c/models" -name '*.fmm' | wc -l)" = "$nfaults" ] && ok || bad "cold: not $nfaults models stored"
same_outputs cold "$tmp/cold"
same_report cold "$tmp/cold"
expect_rc 0 "demo, warm cache" "$exe" demo --quiet --cache "$c" -o "$tmp/warm"
[ "$(cache_of "$tmp/warm")" = "$nfaults 0 0 True" ] && ok || bad "warm: $(cache_of "$tmp/warm")"
[ "$(json "$tmp/warm/report.json" "sum(f.get('fit_cached') is True for f in r['faults'])")" = "$nfaults" ] &&
    ok || bad "warm: not every fault says fit_cached"
same_outputs warm "$tmp/warm"
same_report warm "$tmp/warm"
[ -z "$(find "$c" -name '*.tmp.*')" ] && ok || bad "temporary files left in the cache"

# 3. Another size reuses every model (the fit does not depend on it), and
#    meshes as a run without the cache does at that size.
expect_rc 0 "demo --size 2000, no cache" "$exe" demo --quiet --no-cache --size 2000 -o "$tmp/ref2"
expect_rc 0 "demo --size 2000, cached" "$exe" demo --quiet --cache "$c" --size 2000 -o "$tmp/size2"
[ "$(cache_of "$tmp/size2")" = "$nfaults 0 0 True" ] && ok || bad "--size 2000: $(cache_of "$tmp/size2")"
diff -r -x report.json "$tmp/ref2" "$tmp/size2" >/dev/null && ok || bad "--size 2000: outputs differ"

# 3b. The junction plan's neighbours (sheet pairs, near-duplicates) and
#     their intersection curves are kept beside the models: found and stored once, read by every later
#     run on the same models and join distance, at any size; another join
#     distance finds them again; a damaged file is rejected and found
#     again, with the same outputs.
nb_of() { json "$1/report.json" "r['fit_cache']['connect_neighbours']"; }
[ "$(nb_of "$tmp/cold")" = "found and stored" ] && ok || bad "cold neighbours: $(nb_of "$tmp/cold")"
for d in warm size2; do
    [ "$(nb_of "$tmp/$d")" = read ] && ok || bad "$d neighbours: $(nb_of "$tmp/$d")"
done
[ "$(nb_of "$tmp/ref")" = "not looked up" ] && ok || bad "--no-cache neighbours: $(nb_of "$tmp/ref")"
#     The pairs' intersection curves are kept with them, as traced (before
#     they are resampled at a spacing that follows the size): read at any
#     size, none traced again; a size whose spacing differs (700 m: 175 m
#     against 250 m) meshes as a run without the cache does.
curves_of() { json "$1/report.json" "'%d %d' % (r['fit_cache']['connect_curves_read'], r['fit_cache']['connect_curves_traced'])"; }
read cr ct <<<"$(curves_of "$tmp/cold")"
[ "$cr" = 0 ] && [ "$ct" -gt 0 ] && ok || bad "cold curves: $cr read, $ct traced"
for d in warm size2; do
    [ "$(curves_of "$tmp/$d")" = "$ct 0" ] && ok || bad "$d curves: $(curves_of "$tmp/$d"), not $ct 0"
done
expect_rc 0 "demo --size 700, no cache" "$exe" demo --quiet --no-cache --size 700 -o "$tmp/ref7"
expect_rc 0 "demo --size 700, cached" "$exe" demo --quiet --cache "$c" --size 700 -o "$tmp/size7"
[ "$(curves_of "$tmp/size7")" = "$ct 0" ] && ok || bad "--size 700 curves: $(curves_of "$tmp/size7")"
diff -r -x report.json "$tmp/ref7" "$tmp/size7" >/dev/null && ok ||
    bad "--size 700: outputs differ: $(diff -rq -x report.json "$tmp/ref7" "$tmp/size7" | head -3)"
expect_rc 0 "demo --join 800, no cache" "$exe" demo --quiet --no-cache --join 800 -o "$tmp/refj"
expect_rc 0 "demo --join 800" "$exe" demo --quiet --cache "$c" --join 800 -o "$tmp/join"
[ "$(nb_of "$tmp/join")" = "found and stored" ] && ok || bad "--join 800 neighbours: $(nb_of "$tmp/join")"
diff -r -x report.json "$tmp/refj" "$tmp/join" >/dev/null && ok || bad "--join 800: outputs differ"
nbf=($(find "$c/connect" -name '*.fmn' | sort))
[ "${#nbf[@]}" = 2 ] && ok || bad "${#nbf[@]} neighbours files, not 2"
for f in "${nbf[@]}"; do
    python3 -c "
import sys; p = sys.argv[1]; b = bytearray(open(p, 'rb').read()); b[len(b) // 2] ^= 0x10
open(p, 'wb').write(b)" "$f"
done
expect_rc 0 "demo with damaged neighbours" "$exe" demo --quiet --cache "$c" -o "$tmp/nbdamaged"
[ "$(nb_of "$tmp/nbdamaged")" = "found again over a rejected file" ] && ok ||
    bad "damaged neighbours: $(nb_of "$tmp/nbdamaged")"
same_outputs "damaged neighbours" "$tmp/nbdamaged"
expect_rc 0 "demo after damaged neighbours" "$exe" demo --quiet --cache "$c" -o "$tmp/nbmended"
[ "$(nb_of "$tmp/nbmended")" = read ] && ok || bad "mended neighbours: $(nb_of "$tmp/nbmended")"
same_outputs "mended neighbours" "$tmp/nbmended"

# 4. An option that reaches the fit (the surface must reach 3 km above
#    the top) is another model: all misses, then all hits.
expect_rc 0 "demo --top extend 3000" "$exe" demo --quiet --cache "$c" --top extend 3000 -o "$tmp/ext"
[ "$(cache_of "$tmp/ext")" = "0 $nfaults 0 True" ] && ok || bad "--top extend: $(cache_of "$tmp/ext")"
expect_rc 0 "demo --top extend 3000 again" "$exe" demo --quiet --cache "$c" --top extend 3000 -o "$tmp/ext2"
[ "$(cache_of "$tmp/ext2")" = "$nfaults 0 0 True" ] && ok || bad "--top extend again: $(cache_of "$tmp/ext2")"
diff -r -x report.json "$tmp/ext" "$tmp/ext2" >/dev/null && ok || bad "--top extend: outputs differ"

# 5. Damaged models: one truncated, one with a byte changed, one emptied;
#    each rejected, its fault fitted again (same outputs), stored anew.
models=($(find "$c/models" -name '*.fmm' | sort))
rm -rf "$c" && expect_rc 0 "demo, refill" "$exe" demo --quiet --cache "$c" -o "$tmp/refill"
models=($(find "$c/models" -name '*.fmm' | sort))
[ "${#models[@]}" = "$nfaults" ] && ok || bad "refill: ${#models[@]} models"
size=$(stat -c %s "${models[0]}")
head -c $((size / 2)) "${models[0]}" >"$tmp/half" && cat "$tmp/half" >"${models[0]}"
python3 -c "
import sys; p = sys.argv[1]; b = bytearray(open(p, 'rb').read()); b[len(b) // 3] ^= 0x40
open(p, 'wb').write(b)" "${models[1]}"
: >"${models[2]}"
expect_rc 0 "demo with damaged models" "$exe" demo --quiet --cache "$c" -o "$tmp/damaged"
[ "$(cache_of "$tmp/damaged")" = "$((nfaults - 3)) 3 3 True" ] && ok ||
    bad "damaged: $(cache_of "$tmp/damaged"), expected $((nfaults - 3)) hits, 3 misses, 3 rejected"
same_outputs damaged "$tmp/damaged"
expect_rc 0 "demo after the damage" "$exe" demo --quiet --cache "$c" -o "$tmp/mended"
[ "$(cache_of "$tmp/mended")" = "$nfaults 0 0 True" ] && ok || bad "mended: $(cache_of "$tmp/mended")"
same_outputs mended "$tmp/mended"

# 6. The default place: $XDG_CACHE_HOME/faultmesh (absolute only), else
#    $HOME/.cache/faultmesh; neither: a note, and the run goes on.
expect_rc 0 "demo, XDG_CACHE_HOME" "$exe" demo --quiet -o "$tmp/xdgrun"
[ "$(find "$tmp/xdg/faultmesh/models" -name '*.fmm' | wc -l)" = "$nfaults" ] && ok ||
    bad "no models in \$XDG_CACHE_HOME/faultmesh"
expect_rc 0 "demo, HOME" env -u XDG_CACHE_HOME "$exe" demo --quiet -o "$tmp/homerun"
[ "$(find "$tmp/home/.cache/faultmesh/models" -name '*.fmm' | wc -l)" = "$nfaults" ] && ok ||
    bad "no models in \$HOME/.cache/faultmesh"
expect_rc 0 "demo, relative XDG_CACHE_HOME" env XDG_CACHE_HOME=relative "$exe" demo --quiet -o "$tmp/relrun"
[ "$(cache_of "$tmp/relrun")" = "$nfaults 0 0 True" ] && [ ! -e relative ] && ok ||
    bad "a relative XDG_CACHE_HOME was not ignored for \$HOME/.cache"
expect_rc 0 "demo, no HOME" env -u XDG_CACHE_HOME -u HOME "$exe" demo -o "$tmp/nohome"
grep -q "note: no fit cache" "$tmp/err" && ok || bad "no note without HOME: $(cat "$tmp/err")"
[ "$(cache_of "$tmp/nohome")" = "0 0 0 False" ] && ok || bad "no HOME: $(cache_of "$tmp/nohome")"
json "$tmp/nohome/report.json" "r['fit_cache']['note']" | grep -q HOME && ok || bad "no HOME: report has no note"
same_outputs "no HOME" "$tmp/nohome"
#    a folder that cannot be made (a file in the way): a note, exit 0
: >"$tmp/afile"
expect_rc 0 "demo --cache under a file" "$exe" demo --cache "$tmp/afile/cache" -o "$tmp/blocked"
grep -q "note: no fit cache" "$tmp/err" && ok || bad "no note for a cache that cannot be made"
[ "$(cache_of "$tmp/blocked")" = "0 0 0 False" ] && ok || bad "blocked: $(cache_of "$tmp/blocked")"
same_outputs blocked "$tmp/blocked"
expect_rc 0 "demo --quiet --cache under a file" "$exe" demo --quiet --cache "$tmp/afile/cache" -o "$tmp/blocked2"
[ ! -s "$tmp/err" ] && ok || bad "--quiet still printed: $(cat "$tmp/err")"

# 7. The settings file: cache = "DIR" (from the file's folder), false.
mkdir -p "$tmp/proj"
printf 'cache = "mycache"\nquiet = true\n' >"$tmp/proj/on.toml"
expect_rc 0 "demo --config cache = DIR" "$exe" demo --config "$tmp/proj/on.toml" -o "$tmp/cfgon"
[ "$(find "$tmp/proj/mycache/models" -name '*.fmm' | wc -l)" = "$nfaults" ] && ok ||
    bad "cache = \"mycache\" not taken from the file's folder"
printf 'cache = false\nquiet = true\n' >"$tmp/proj/off.toml"
expect_rc 0 "demo --config cache = false" "$exe" demo --config "$tmp/proj/off.toml" -o "$tmp/cfgoff"
[ "$(cache_of "$tmp/cfgoff")" = "0 0 0 False" ] && ok || bad "cache = false: $(cache_of "$tmp/cfgoff")"
expect_rc 0 "--cache beside cache = false" "$exe" demo --config "$tmp/proj/off.toml" --cache "$c" -o "$tmp/cfgover"
[ "$(cache_of "$tmp/cfgover")" = "$nfaults 0 0 True" ] && ok || bad "--cache over cache = false: $(cache_of "$tmp/cfgover")"

# 8. Two runs filling one empty cache at once: both whole, same outputs,
#    every model whole (the next run reads them all), no temporary left.
rm -rf "$c"
"$exe" demo --quiet -j 1 --cache "$c" -o "$tmp/par1" & p1=$!
"$exe" demo --quiet -j 1 --cache "$c" -o "$tmp/par2" & p2=$!
wait $p1 && wait $p2 && ok || bad "concurrent runs failed"
same_outputs "concurrent 1" "$tmp/par1"
same_outputs "concurrent 2" "$tmp/par2"
[ -z "$(find "$c" -name '*.tmp.*')" ] && ok || bad "concurrent runs left temporary files"
expect_rc 0 "demo after the concurrent runs" "$exe" demo --quiet --cache "$c" -o "$tmp/after"
[ "$(cache_of "$tmp/after")" = "$nfaults 0 0 True" ] && ok || bad "after concurrent runs: $(cache_of "$tmp/after")"

echo "fit_cache_test: $pass passed, $fail failed"
[ "$fail" = 0 ] && rm -rf "$tmp"
[ "$fail" = 0 ]
