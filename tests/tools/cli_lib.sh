# Shared by the command-line test scripts (sourced): pass/fail counting and
# an exit-code assertion. Needs $tmp (a scratch folder).
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
expect_rc() { # expected-rc description command...
    local want=$1 what=$2; shift 2
    "$@" >"$tmp/out" 2>"$tmp/err"; local rc=$?
    if [ "$rc" = "$want" ]; then ok; else bad "$what: exit $rc, expected $want"; cat "$tmp/err"; fi
}
# json FILE EXPR: EXPR evaluated with r the parsed FILE (report.json
# queries without jq: python3 is there wherever the tests run)
json() { python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print($2)" "$1"; }
