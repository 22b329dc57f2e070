#!/usr/bin/env bash
# Progress lines of the long commands (editor/cli/progress_line.hpp): drawn on stderr when it
# is a terminal, here a pseudo-terminal from util-linux's `script`, and absent when stderr is
# piped, so --json consumers and logs never see them.
# usage: cli_progress_test.sh /path/to/sandtin <scenario> <work-dir> /path/to/json_get <data-dir>
#   scenarios: progress_import, progress_export, progress_run, progress_stress, progress_bench
set -uo pipefail

SANDTIN=${1:?path to the sandtin binary}
SCENARIO=${2:?scenario}
WORK=${3:?work directory}
JSON_GET=${4:?path to json_get}
DATA=${5:?test data directory}
TILE="$DATA/bay-hills-terrain-rgb.png"

rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK" || exit 1
# shellcheck source=cli_lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/cli_lib.sh"

# on_terminal NAME ARGS...: runs sandtin with stderr on a pseudo-terminal and stdout in
# NAME.out; what the terminal received goes to NAME.tty, the exit code to $rc.
on_terminal() {
    local name=$1
    shift
    local command
    command="$(printf '%q ' "$SANDTIN" "$@") >$(printf '%q' "$name.out")"
    script -q -e -c "$command" /dev/null </dev/null >"$name.tty"
    rc=$?
    if [[ $rc -ne 0 ]]; then
        fail "$name: 'sandtin $*' on a terminal exited with $rc: $(cat -v "$name.tty")"
        return 1
    fi
}

# expect_progress NAME: NAME.tty holds a progress line redrawn in place whose percentages never
# fall and end at 100 with "done", with the elapsed time and an estimate of the time left,
# ended by a newline.
expect_progress() {
    local name=$1
    local shown
    shown=$(cat -v "$name.tty")
    local percents
    percents=$(tr '\r' '\n' <"$name.tty" | grep -o '[0-9]\+%' | tr -d '%' | tr '\n' ' ')
    if [[ -z "$percents" ]]; then
        fail "$name: no progress on the terminal: $shown"
        return
    fi
    if ! awk -v list="$percents" 'BEGIN {
            n = split(list, p, " ");
            for (i = 2; i <= n; ++i) if (p[i] + 0 < p[i - 1] + 0) exit 1;
            exit !(p[n] == 100) }'; then
        fail "$name: the percentages do not rise to 100: $percents"
    fi
    grep -q 'elapsed [0-9]' "$name.tty" || fail "$name: no elapsed time: $shown"
    grep -q 'left' "$name.tty" || fail "$name: no estimate of the time left: $shown"
    # Redrawn in place: every drawing starts with a carriage return; the last line ends.
    [[ "$(head -c 1 "$name.tty" | od -An -tx1 | tr -d ' ')" == 0d ]] ||
        fail "$name: the line does not start with a carriage return: $shown"
    [[ "$(tail -c 1 "$name.tty" | od -An -tx1 | tr -d ' ')" == 0a ]] ||
        fail "$name: the line is not ended: $shown"
    # The last drawing says the work is done. (Which stages show in between depends on the
    # machine's speed, as the line is redrawn at most every 100 ms: the engine's stages are
    # tested in tests/io/progress_test.cpp.)
    grep -q ': done  100%' "$name.tty" || fail "$name: the last drawing does not say done: $shown"
}

# expect_silent_when_piped NAME ARGS...: the same command with stderr piped writes nothing there.
expect_silent_when_piped() {
    local name=$1
    shift
    expect_ok "$name" "$@" || return
    if [[ -s "$name.err" ]]; then
        fail "$name: stderr is not a terminal, yet it received: $(cat -v "$name.err")"
    fi
}

scenario_progress_import() {
    on_terminal imp import "$TILE" --max-error 0.5 -o tty.sandtin --json || return
    expect_progress imp
    grep -q '^.import bay-hills-terrain-rgb.png ' imp.tty || fail "the line does not say what it imports"
    # stdout stays a clean JSON document.
    holds "points on a terminal" "a > 4" "$(json imp.out /points)"
    expect_silent_when_piped imp_pipe import "$TILE" --max-error 0.5 -o pipe.sandtin --json
    check_eq "same points piped" "$(json imp_pipe.out /points)" "$(json imp.out /points)"
}

scenario_progress_export() {
    expect_ok imp import "$TILE" --max-error 2 -o bay.sandtin || return
    on_terminal exp export bay.sandtin -o tty.glb --size 256 || return
    expect_progress exp
    grep -q '^.export tty.glb ' exp.tty || fail "the line does not say what it exports"
    expect_silent_when_piped exp_pipe export bay.sandtin -o pipe.glb --size 256
    cmp -s tty.glb pipe.glb || fail "the export on a terminal wrote other bytes than piped"
}

scenario_progress_run() {
    cat >script.json <<'END_OF_SCRIPT'
{"version": 1,
 "terrain": {"size": [1, 1], "points": 3000, "seed": 3, "height": 0.1},
 "operations": [
   {"op": "stroke", "tool": {"asset": "circle"}, "path": [[0.2, 0.5], [0.8, 0.5]],
    "spacing": 0.01, "depth": 0.01, "erode": true},
   {"op": "pour", "at": [0.5, 0.3], "volume": 1e-4, "radius": 0.03},
   {"op": "erode", "iterations": 20}]}
END_OF_SCRIPT
    on_terminal run run script.json -o tty.sandtin --json || return
    expect_progress run
    grep -q '^.run script.json ' run.tty || fail "the line does not say what it runs"
    check_eq "run valid on a terminal" "$(json run.out /terrain/valid)" true
    expect_silent_when_piped run_pipe run script.json -o pipe.sandtin --json
    check_eq "same volume piped" "$(json run_pipe.out /terrain/volume)" \
        "$(json run.out /terrain/volume)"
}

scenario_progress_stress() {
    on_terminal stress stress --ops 60 --points 500 --seed 4 || return
    expect_progress stress
    grep -q '^.stress seed 4 ' stress.tty || fail "the line does not name the session"
    # Without --json it printed "1000 operations" lines on stderr before; now nothing piped.
    expect_silent_when_piped stress_pipe stress --ops 60 --points 500 --seed 4
}

scenario_progress_bench() {
    on_terminal bench bench history --quick || return
    expect_progress bench
    grep -q '^.bench history ' bench.tty || fail "the line does not name the benchmark"
    check_eq "bench on a terminal" "$(json bench.out /benchmark)" history
    expect_silent_when_piped bench_pipe bench history --quick
    # The drivers in tests/bench report through the same line (their stages and fractions are
    # checked in tests/bench/bench_progress_test.cpp).
    on_terminal bench_tin bench tin --quick || return
    expect_progress bench_tin
    grep -q '^.bench tin ' bench_tin.tty || fail "the line does not name the tin benchmark"
    check_eq "bench tin on a terminal" "$(json bench_tin.out /bench)" tin
    expect_silent_when_piped bench_tin_pipe bench tin --quick
}

command -v script >/dev/null || {
    echo "util-linux's script is missing (scripts/install-deps.sh installs bsdutils)" >&2
    exit 1
}
case "$SCENARIO" in
    progress_import) scenario_progress_import ;;
    progress_export) scenario_progress_export ;;
    progress_run) scenario_progress_run ;;
    progress_stress) scenario_progress_stress ;;
    progress_bench) scenario_progress_bench ;;
    *)
        echo "unknown scenario $SCENARIO" >&2
        exit 2
        ;;
esac
finish "$SCENARIO"
