#!/usr/bin/env bash
# `sandtin run --physics cpu|gpu`: the same script (stamps + erosion, Jacobi schedule) gives the
# same terrain on both (volume, vertex count, relaxation work), and a bad choice is a usage
# error. Exit 77 (ctest SKIP) only when the machine has no Vulkan device at all.
# usage: cli_physics_gpu_test.sh /path/to/sandtin /path/to/json_get <work-dir>
set -uo pipefail
SANDTIN=${1:?sandtin}
JSON_GET=${2:?json_get}
WORK=${3:?work dir}
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK" || exit 1

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

cat > erode.json <<'END_OF_SCRIPT'
{
  "version": 1,
  "terrain": {"size": [1, 1], "points": 8000, "seed": 5, "height": 0.1},
  "settings": {"schedule": "jacobi", "simplify": false},
  "operations": [
    {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.5, 0.5], "depth": 0.05},
    {"op": "erode", "iterations": 150},
    {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.3, 0.6], "depth": 0.04},
    {"op": "erode", "until_rest": true, "max_iterations": 400}
  ]
}
END_OF_SCRIPT

"$SANDTIN" run erode.json -o cpu.sandtin --physics cpu --json > cpu.json 2> cpu.err ||
    fail "cpu run failed: $(cat cpu.err)"
if ! "$SANDTIN" run erode.json -o gpu.sandtin --physics gpu --json > gpu.json 2> gpu.err; then
    if grep -q "no Vulkan device" gpu.err; then
        echo "SKIP: $(cat gpu.err)"
        exit 77
    fi
    fail "gpu run failed: $(cat gpu.err)"
    exit 1
fi
get() { "$JSON_GET" "$1" "$2"; }
[[ "$(get gpu.json /physics)" == gpu ]] || fail "the report does not say gpu"
[[ -n "$(get gpu.json /device)" ]] || fail "the report does not name the device"
[[ "$(get gpu.json /terrain/valid)" == true ]] || fail "gpu terrain invalid"
[[ "$(get cpu.json /terrain/vertices)" == "$(get gpu.json /terrain/vertices)" ]] ||
    fail "vertex counts differ"
vc=$(get cpu.json /terrain/volume) && vg=$(get gpu.json /terrain/volume) ||
    fail "no volumes in the reports"
awk -v a="$vc" -v b="$vg" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-6 * a) }' ||
    fail "volumes differ: cpu $vc gpu $vg"
uc=$(get cpu.json /steps/1/vertex_updates) && ug=$(get gpu.json /steps/1/vertex_updates)
awk -v a="$uc" -v b="$ug" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a > 0 && d <= 0.02 * a) }' ||
    fail "relaxation work differs: cpu $uc gpu $ug"

if "$SANDTIN" run erode.json -o bad.sandtin --physics tpu > /dev/null 2> bad.err; then
    fail "--physics tpu was accepted"
fi
grep -q "cpu or gpu" bad.err || fail "the error does not name the choices: $(cat bad.err)"

[[ $failures -eq 0 ]] && echo "cli physics gpu: ok"
exit $((failures > 0))
