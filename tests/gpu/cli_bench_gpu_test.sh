#!/usr/bin/env bash
# `sandtin bench gpu --quick --json` end to end: the JSON carries the device, CPU and GPU
# throughput, per-kernel times and the upload bytes per stamp (< 1 % of the mirror).
# Exit 77 (ctest SKIP) only when the machine has no Vulkan device at all.
# usage: cli_bench_gpu_test.sh /path/to/sandtin /path/to/json_get <work-dir>
set -uo pipefail
SANDTIN=${1:?sandtin}
JSON_GET=${2:?json_get}
WORK=${3:?work dir}
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK" || exit 1

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

if ! "$SANDTIN" bench gpu --quick --json > bench.json 2> bench.err; then
    if grep -q "no Vulkan device" bench.err; then
        echo "SKIP: $(cat bench.err)"
        exit 77
    fi
    fail "bench gpu failed: $(cat bench.err)"
    exit 1
fi

value() { "$JSON_GET" bench.json "$1"; }
positive() {
    local v
    v=$(value "$1") || { fail "missing $1"; return; }
    awk -v x="$v" 'BEGIN { exit !(x > 0) }' || fail "$1 = $v is not positive"
}
[[ -n "$(value /device_name)" ]] || fail "no device name"
positive /relaxation/0/cpu_jacobi_1_thread_updates_per_s
positive /relaxation/0/cpu_jacobi_2_threads_updates_per_s
positive /relaxation/0/gpu_updates_per_s
positive /relaxation/0/vertices
positive /upload/stamp_upload_bytes_median
# The bench relaxes under the default slope rule, the face rule: its outflow kernel.
value /relaxation/0/gpu_kernel_ms_per_iteration/talus_face_outflow > /dev/null ||
    fail "no per-kernel time for talus_face_outflow"
frac=$(value /upload/stamp_upload_fraction) || fail "no upload fraction"
awk -v x="$frac" 'BEGIN { exit !(x > 0 && x < 0.01) }' || fail "stamp upload fraction $frac"

# A bad option is a usage error, not a crash.
if "$SANDTIN" bench gpu --frobnicate > /dev/null 2> bad.err; then
    fail "an unknown option was accepted"
fi
grep -q -- "--frobnicate" bad.err || fail "the error does not name the option: $(cat bad.err)"

[[ $failures -eq 0 ]] && echo "cli bench gpu: ok"
exit $((failures > 0))
