# Helpers for the CLI test scripts (sourced, not run). Expects SANDTIN and JSON_GET set, and
# runs in the scenario's work directory.

failures=0
fail() {
    echo "FAIL: $*" >&2
    failures=$((failures + 1))
}

# json FILE POINTER...: the values at JSON pointers, one per line.
json() {
    "$JSON_GET" "$@"
}

# holds WHAT AWK-CONDITION VALUES...: the condition over a, b, c (the values) must hold.
holds() {
    local what=$1 cond=$2
    shift 2
    if ! awk -v a="${1:-}" -v b="${2:-}" -v c="${3:-}" "BEGIN { exit !($cond) }"; then
        fail "$what: ($cond) does not hold for a='${1:-}' b='${2:-}' c='${3:-}'"
    fi
}

# run NAME ARGS...: runs sandtin, keeping stdout in NAME.out, stderr in NAME.err, exit code in $rc.
run() {
    local name=$1
    shift
    "$SANDTIN" "$@" >"$name.out" 2>"$name.err"
    rc=$?
}

expect_ok() {
    local name=$1
    shift
    run "$name" "$@"
    if [[ $rc -ne 0 ]]; then
        fail "$name: 'sandtin $*' exited with $rc; stderr: $(cat "$name.err")"
        return 1
    fi
    return 0
}

# expect_error NAME KEYWORD ARGS...: non-zero exit below 128 (no crash), a message on stderr
# containing KEYWORD (case-insensitive).
expect_error() {
    local name=$1 keyword=$2
    shift 2
    run "$name" "$@"
    if [[ $rc -eq 0 ]]; then
        fail "$name: 'sandtin $*' succeeded but should have failed"
    elif [[ $rc -ge 128 ]]; then
        fail "$name: 'sandtin $*' crashed (exit $rc, signal $((rc - 128)))"
    fi
    if [[ ! -s "$name.err" ]]; then
        fail "$name: no message on stderr"
    elif ! grep -qi -- "$keyword" "$name.err"; then
        fail "$name: stderr lacks '$keyword': $(cat "$name.err")"
    fi
    if grep -qi "terminate called\|Segmentation\|Aborted\|core dumped" "$name.err"; then
        fail "$name: crash message on stderr: $(cat "$name.err")"
    fi
}

check_eq() {  # check_eq WHAT ACTUAL EXPECTED
    if [[ "$2" != "$3" ]]; then fail "$1: got '$2', expected '$3'"; fi
}

finish() {  # finish SCENARIO
    if [[ $failures -ne 0 ]]; then
        echo "$failures check(s) failed in scenario $1" >&2
        exit 1
    fi
    echo "scenario $1: all checks passed"
}
