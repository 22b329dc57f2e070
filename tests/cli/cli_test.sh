#!/usr/bin/env bash
# End-to-end tests of the sandtin CLI.
# usage: cli_test.sh /path/to/sandtin <scenario> <work-dir> /path/to/json_get
#   scenarios: roundtrip, bad_input, bench, demo, run_good, run_bad, readme_script, script_extrude
# json_get (tests/cli/json_get.cpp) reads values out of the JSON the CLI prints.
set -uo pipefail

SANDTIN=${1:?path to the sandtin binary}
SCENARIO=${2:?scenario}
WORK=${3:?work directory}
JSON_GET=${4:?path to json_get}
README=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/README.md

rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK" || exit 1

failures=0
fail() {
    echo "FAIL: $*" >&2
    failures=$((failures + 1))
}

# json FILE POINTER...: the values at JSON pointers, one per line (strings raw, the rest as
# compact JSON).
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

abs_le() {  # abs_le X Y REL: |X - Y| <= REL * |Y|
    holds "$4" "(a - b <= c * (b < 0 ? -b : b)) && (b - a <= c * (b < 0 ? -b : b))" "$1" "$2" "$3"
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

# expect_error NAME KEYWORD ARGS...: non-zero exit below 128 (no crash, no signal), a message
# on stderr containing KEYWORD (case-insensitive).
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

scenario_roundtrip() {
    # The acceptance example: new, then info.
    expect_ok new1 new --flat 10 10 --points 1000 --seed 3 -o scene.sandtin || return
    [[ -s scene.sandtin ]] || fail "new wrote no file"
    expect_ok info1 info scene.sandtin --json || return
    check_eq "info vertices" "$(json info1.out /vertices)" 1004
    check_eq "info valid" "$(json info1.out /valid)" true
    # Euler's formula for 1004 points, 4 of them on the hull: T = 2V - h - 2.
    check_eq "info triangles" "$(json info1.out /triangles)" 2002
    check_eq "info constrained_edges" "$(json info1.out /constrained_edges)" 0
    # Flat: every face judged, none steep, no slope at all (physics/face_slopes).
    check_eq "info slopes faces" "$(json info1.out /slopes/faces)" 2002
    check_eq "info slopes steep" "$(json info1.out /slopes/steep_faces)" 0
    check_eq "info slopes max ratio" "$(json info1.out /slopes/max_ratio)" 0.0
    check_eq "info slopes area" "$(json info1.out /slopes/sloped_area)" 0.0
    check_eq "info bbox" "$(json info1.out /bbox/min/0 /bbox/min/1 /bbox/max/0 /bbox/max/1 | tr '\n' ' ')" \
        "0.0 0.0 10.0 10.0 "

    # What `new --json` reports of the terrain it saved equals what `info` reads back.
    expect_ok new2 new --flat 10 10 --points 1000 --seed 3 --height 1.5 -o scene2.sandtin --json || return
    expect_ok info2 info scene2.sandtin --json || return
    for key in vertices triangles constrained_edges constraints bbox volume; do
        check_eq "new vs info $key" "$(json info2.out "/$key")" "$(json new2.out "/$key")"
    done
    check_eq "info2 vertices" "$(json info2.out /vertices)" 1004
    check_eq "info2 valid" "$(json info2.out /valid)" true
    # Flat at 1.5 m over 100 m^2: 150 m^3 (independent of the triangulation).
    abs_le "$(json info2.out /volume)" 150 1e-12 "volume of the flat terrain"

    # Same seed, same file; another seed, another file.
    expect_ok new3 new --flat 10 10 --points 1000 --seed 3 -o scene3.sandtin || return
    cmp -s scene.sandtin scene3.sandtin || fail "new is not deterministic for a seed"
    expect_ok new4 new --flat 10 10 --points 1000 --seed 4 -o scene4.sandtin || return
    cmp -s scene.sandtin scene4.sandtin && fail "different seeds gave the same file"

    # A grid: (8+1) x (6+1) vertices, 2*8*6 triangles, flat at 2 m over 4 x 3 m.
    expect_ok grid1 new --grid 4 3 8 6 --height 2 -o grid.sandtin --json || return
    expect_ok grid2 info grid.sandtin --json || return
    check_eq "grid vertices" "$(json grid2.out /vertices)" 63
    check_eq "grid triangles" "$(json grid2.out /triangles)" 96
    abs_le "$(json grid2.out /volume)" 24 1e-12 "grid volume"
    check_eq "grid valid" "$(json grid2.out /valid)" true

    # A sandbox over a flat bedrock: 2 cm of sand everywhere, and a removal bigger than the sand
    # under it digs down to the bedrock and stops there.
    expect_ok bed1 new --flat 1 1 --points 2000 --height 0.1 --sand-depth 0.02 -o bed.sandtin --json ||
        return
    check_eq "sand over bedrock" "$(json bed1.out /sand/vertices_over_bedrock)" 2004
    abs_le "$(json bed1.out /sand/min_thickness)" 0.02 1e-15 "sand thickness (thinnest)"
    abs_le "$(json bed1.out /sand/max_thickness)" 0.02 1e-15 "sand thickness (thickest)"
    printf '[{"op": "remove", "at": [0.5, 0.5], "volume": 0.001, "radius": 0.05}]\n' >dig.json
    expect_ok bed2 run dig.json -i bed.sandtin -o bed_dug.sandtin --json || return
    abs_le "$(json bed2.out /terrain/sand/min_thickness)" 0 1e-12 "sand left in the pit"
    abs_le "$(json bed2.out /terrain/bbox/min/2)" 0.08 1e-12 "the pit's floor is the bedrock"
    expect_error bed3 "--sand-depth" new --flat 1 1 --sand-depth -1 -o bad.sandtin
    [[ -e bad.sandtin ]] && fail "a refused new wrote bad.sandtin"

    # Zero points: just the rectangle.
    expect_ok rect1 new --flat 3 2 -o rect.sandtin || return
    expect_ok rect2 info rect.sandtin --json || return
    check_eq "rect vertices" "$(json rect2.out /vertices)" 4
    check_eq "rect triangles" "$(json rect2.out /triangles)" 2

    # Human-readable info.
    expect_ok info3 info scene.sandtin || return
    grep -q "vertices *1004" info3.out || fail "plain info lacks the vertex count: $(cat info3.out)"
    grep -q "valid *yes" info3.out || fail "plain info lacks 'valid yes': $(cat info3.out)"
    expect_ok help help
}

scenario_bad_input() {
    expect_ok good new --flat 10 10 --points 200 --seed 1 -o good.sandtin || return
    local size
    size=$(stat -c %s good.sandtin)

    expect_error missing "missing.sandtin" info missing.sandtin --json
    # --help on any command prints its usage on stdout and succeeds; a stray or missing
    # argument is named.
    local cmd
    for cmd in new info run import export stress haptics demo "bench erosion"; do
        # shellcheck disable=SC2086
        expect_ok "help_${cmd// /_}" $cmd --help || continue
        grep -q "^usage: sandtin ${cmd%% *}" "help_${cmd// /_}.out" ||
            fail "'$cmd --help' printed no usage: $(cat "help_${cmd// /_}.out")"
    done
    grep -q -- "--grid" help_new.out || fail "new's usage lacks --grid"
    expect_ok version --version || return
    grep -Eq "^sandtin [0-9]+\.[0-9]+\.[0-9]+ \(session format [0-9]+" version.out ||
        fail "--version printed: $(cat version.out)"
    expect_error stray "unexpected argument 'extra'" new --flat 1 1 extra -o stray.sandtin
    expect_error seed_unused "--seed applies to --flat with --points" new --flat 1 1 --seed 3 -o s.sandtin
    expect_error missing_arg "missing 1 of its 1" info
    # Heights beyond 1e9 m (the largest terrain side) would give infinite volumes and meshes.
    expect_error huge_height "--height" new --flat 1 1 --height 1e308 -o huge.sandtin
    [[ -e huge.sandtin ]] && fail "new with a height of 1e308 m wrote huge.sandtin"
    head -c $((size / 2)) good.sandtin >truncated.sandtin
    expect_error truncated "truncated" info truncated.sandtin
    head -c 20 good.sandtin >header_only.sandtin
    expect_error truncated_header "truncated" info header_only.sandtin
    : >empty.sandtin
    expect_error empty "empty.sandtin" info empty.sandtin
    printf 'this is not a terrain at all, just some text\n%.0s' {1..20} >garbage.sandtin
    expect_error garbage "not a sandtin" info garbage.sandtin
    head -c 4096 /dev/urandom >random.sandtin 2>/dev/null || dd if=/dev/urandom of=random.sandtin bs=4096 count=1 2>/dev/null
    expect_error random "not a sandtin" info random.sandtin
    # One flipped byte in the payload.
    cp good.sandtin flipped.sandtin
    printf '\xff' | dd of=flipped.sandtin bs=1 seek=$((size - 7)) conv=notrunc 2>/dev/null
    expect_error flipped "checksum" info flipped.sandtin
    expect_error directory "cannot" info .

    expect_error nan_width "nan" new --flat nan 10 -o nan.sandtin
    expect_error zero_width "positive" new --flat 0 10 -o zero.sandtin
    expect_error negative_height "positive" new --flat 10 -3 -o neg.sandtin
    expect_error inf_width "inf" new --flat inf 10 -o inf.sandtin
    expect_error negative_points "points" new --flat 10 10 --points -5 -o negpts.sandtin
    expect_error text_points "points" new --flat 10 10 --points many -o txt.sandtin
    expect_error unknown_option "--bogus" new --flat 10 10 --bogus -o bogus.sandtin
    expect_error missing_value "--flat" new --flat 10
    expect_error missing_output "-o" new --flat 10 10
    expect_error both_shapes "exactly one" new --flat 10 10 --grid 10 10 2 2 -o both.sandtin
    expect_error bad_grid "NX" new --grid 10 10 0 2 -o g.sandtin
    expect_error nan_height "height" new --flat 10 10 --height nan -o h.sandtin
    expect_error no_dir "nosuchdir" new --flat 10 10 -o nosuchdir/x.sandtin
    expect_error huge "1e9 m" new --flat 1e160 1e160 --points 100 -o huge.sandtin
    expect_error tiny "1e-9 m" new --flat 1e-200 1e-200 -o tiny.sandtin
    expect_error spaced_count "points" new --flat 10 10 --points " -1" -o spaced.sandtin
    for f in nan zero neg inf negpts txt bogus both g h huge tiny spaced; do
        [[ -e "$f.sandtin" ]] && fail "a failed 'new' left $f.sandtin behind"
    done
    expect_error unknown_command "frobnicate" frobnicate
    expect_error no_arguments "usage"
    expect_error info_no_file "usage" info
    expect_error bench_unknown "unknown benchmark .nosuchbench. (available: tin, groove, import, history, water, erosion, gpu, haptics)" bench nosuchbench
    expect_error demo_extra "usage" demo extra-argument
    # The good file is still fine after all that.
    expect_ok good_info info good.sandtin --json && check_eq "good valid" "$(json good_info.out /valid)" true
}

scenario_bench() {
    expect_ok bench bench tin --quick || return
    # A smoke test of the driver: the sections exist and hold numbers; timings are not judged.
    json bench.out /insert/0/sandtin_ms /insert/0/cgal_ms /locate/path_with_hint_ns \
        /remove/us_per_removal /constraints/sandtin_ms_per_ring_median >/dev/null ||
        fail "bench output lacks insert/locate/remove/constraints figures: $(head -c 400 bench.out)"
    check_eq "bench quick flag" "$(json bench.out /quick)" true
    holds "bench removals" "a > 0" "$(json bench.out /remove/removed)"
    holds "bench constraint rings" "a > 0 && b > 0" "$(json bench.out /constraints/rings)" \
        "$(json bench.out /constraints/constrained_edges_after)"
    expect_ok bench_json bench tin --quick --json || return
    check_eq "bench --json" "$(json bench_json.out /bench)" tin
    # Run time against error: both slope rules and the projection on the TIN and the grid, CSV
    # and SVG written. Each method has 8 runs (TIN then grid, for the cone, the half cone, the
    # quarter cone and the step): 0-7 the edge rule's, 8-15 the face rule's, 16-23 the
    # projection's. The face rule and the projection rest with no face steeper than repose on
    # both discretisations, the edge rule's TIN cone with most of its slopes steeper.
    expect_ok bench_erosion bench erosion --quick --out erosion_out || return
    [[ -s erosion_out/erosion.csv && -s erosion_out/erosion.svg ]] ||
        fail "bench erosion wrote no CSV or SVG"
    for k in 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23; do
        holds "bench erosion face rule or projection run $k" "a == 0 && b <= 1.001" \
            "$(json bench_erosion.out /runs/$k/steep_share_of_slopes)" \
            "$(json bench_erosion.out /runs/$k/max_face_ratio)"
    done
    check_eq "bench erosion run 9" "$(json bench_erosion.out /runs/9/method)" grid-face
    check_eq "bench erosion run 16" "$(json bench_erosion.out /runs/16/method)" tin-proj
    check_eq "bench erosion run 20" "$(json bench_erosion.out /runs/20/scene)" quarter-cone
    # The projected cones, whole, half and quarter (runs 16-21): within 2 % of the analytic
    # cone's height on average inside 1.2 R, their toes within 20 % of its radius at this
    # coarse level (r_S 4 cm, 32² cells; measured about 1 % and 13 %).
    # Their toe bias is a mean of the offsets whose largest magnitude is toe_error, so it
    # cannot exceed it; the step (runs 22, 23) has no toe.
    for k in 16 17 18 19 20 21; do
        holds "bench erosion projected cone $k" "a < 0.02 * c && b < 0.2" \
            "$(json bench_erosion.out /runs/$k/pile_mean_error_m)" \
            "$(json bench_erosion.out /runs/$k/toe_error)" \
            "$(json bench_erosion.out /runs/$k/pile_height_m)"
        holds "bench erosion projected cone $k toe bias" "a == a + 0 && a <= b && -a <= b" \
            "$(json bench_erosion.out /runs/$k/toe_bias)" \
            "$(json bench_erosion.out /runs/$k/toe_error)"
    done
    check_eq "bench erosion step toe bias" "$(json bench_erosion.out /runs/22/toe_bias)" null
    # A subset of the table: one scene, one rule, no throughput tables.
    expect_ok bench_erosion_cone bench erosion --quick --scenes cone --rules face --no-throughput ||
        return
    check_eq "bench erosion subset" "$(json bench_erosion_cone.out /runs/1/method)" grid-face
    holds "bench erosion subset size" "a == 2" \
        "$(json bench_erosion_cone.out /runs | tr -cd '{' | wc -c)"
    expect_error bench_erosion_scene \
        "--scenes: 'hill' is not one of cone, half-cone, quarter-cone, step, dunes" \
        bench erosion --scenes hill
    expect_error bench_erosion_rule "--rules: 'vertex' is not one of edge, face, projection" \
        bench erosion --rules vertex
    holds "bench erosion edge rule TIN cone" "a > 0.1" \
        "$(json bench_erosion.out /runs/0/steep_share_of_slopes)"
    # The groove with a shipped tool instead of the seeds' circle: the λ digs a valid groove.
    expect_ok bench_lambda bench groove --quick --tool lambda --json || return
    check_eq "bench groove tool" "$(json bench_lambda.out /tool/asset)" lambda
    check_eq "bench groove λ valid" "$(json bench_lambda.out /by_size/1/valid)" true
    holds "bench groove λ stamps" "a > 0 && b > 0" "$(json bench_lambda.out /by_size/1/stamps)" \
        "$(json bench_lambda.out /by_size/1/per_stamp_median_ms)"
    # The same groove eroding after every stamp: its walls stand steeper than the angle of
    # repose, so the relaxation must move sand, and the terrain must stay valid.
    check_eq "bench groove λ eroded valid" "$(json bench_lambda.out /by_size/1/with_erosion/valid)" true
    # It visits sand that moves: heights change (the share of visits that change one is what
    # the groove's active set holds).
    holds "bench groove λ erosion" "a > 0 && b > 0 && c > 0" \
        "$(json bench_lambda.out /by_size/1/with_erosion/erosion_vertex_updates)" \
        "$(json bench_lambda.out /by_size/1/with_erosion/erosion_ms)" \
        "$(json bench_lambda.out /by_size/1/with_erosion/relax_heights_changed_per_update)"
    # Locality: the 10⁴-point groove's density on a tenth of the area (side sqrt(0.1) m, a
    # stroke of 0.8 of its diagonal, 0.358 m: 36 stamps 1 cm apart), and the 10³-point
    # groove's on a 10 m square (10⁵ points, 11.3 m: 1 132 stamps). Both valid.
    for size in smaller larger; do
        check_eq "bench groove λ $size terrain valid" \
            "$(json bench_lambda.out /locality/${size}_terrain/valid)" true
    done
    holds "bench groove λ smaller terrain" "a == 1000 && b >= 35 && b <= 37 && c > 0" \
        "$(json bench_lambda.out /locality/smaller_terrain/points)" \
        "$(json bench_lambda.out /locality/smaller_terrain/stamps)" \
        "$(json bench_lambda.out /locality/smaller_terrain/per_stamp_ratio)"
    holds "bench groove λ larger terrain" "a == 100000 && b >= 1130 && b <= 1134 && c > 0" \
        "$(json bench_lambda.out /locality/larger_terrain/points)" \
        "$(json bench_lambda.out /locality/larger_terrain/stamps)" \
        "$(json bench_lambda.out /locality/larger_terrain/per_stamp_ratio)"
    # Eroded to rest after the stroke: it rests, stays valid, and the settle margin (the
    # default) rests in fewer iterations than the seeds' rule, whose slopes creep.
    check_eq "bench groove λ to rest" "$(json bench_lambda.out /by_size/1/to_rest/at_rest)" true
    check_eq "bench groove λ to rest valid" "$(json bench_lambda.out /by_size/1/to_rest/valid)" true
    check_eq "bench groove λ seeds' rule at rest" \
        "$(json bench_lambda.out /by_size/1/to_rest/seeds_rule/at_rest)" true
    holds "bench groove λ to rest iterations" "a > 0 && a < b" \
        "$(json bench_lambda.out /by_size/1/to_rest/iterations)" \
        "$(json bench_lambda.out /by_size/1/to_rest/seeds_rule/iterations)"
    holds "bench groove λ target" "a == 100" "$(json bench_lambda.out /by_size/1/to_rest/target_ms)"
    # Restoring from a snapshot rebuilds every vertex (the four corners come on top).
    holds "bench tin restore" "a == 10000 && b == 10004 && c > 0" \
        "$(json bench_json.out /restore/0/points)" "$(json bench_json.out /restore/0/vertices)" \
        "$(json bench_json.out /restore/0/restore_cpu_ms_median)"
    expect_error bench_bad_tool "nosuchtool" bench groove --quick --tool nosuchtool
    expect_error bench_tool_elsewhere "--tool applies to 'bench groove' only" bench tin --tool lambda
}

scenario_bench_water() {
    # The water schemes against SWASHES's analytic solutions (quick: two spacings of the dam
    # breaks, one of Thacker's bowl). The finite volumes meet the tests' 5 % at 4 cm on both
    # dam breaks; the pipes, without momentum, are further off on each; the lake at rest stays
    # still; the rain rows hold timings (not judged).
    expect_ok bench_water bench water --quick --json || return
    check_eq "bench water name" "$(json bench_water.out /bench)" water
    check_eq "bench water quick" "$(json bench_water.out /quick)" true
    for k in 0 1; do
        holds "bench water dam break $k" "a < 0.05 && b > a" \
            "$(json bench_water.out /dam_breaks/$k/schemes/finite_volume_order2/levels/1/l1)" \
            "$(json bench_water.out /dam_breaks/$k/schemes/pipes/levels/1/l1)"
    done
    check_eq "bench water Ritter" "$(json bench_water.out /dam_breaks/0/case)" ritter
    holds "bench water Thacker" "a < 0.2 && a < b" \
        "$(json bench_water.out /thacker/schemes/finite_volume_order2/levels/0/l1)" \
        "$(json bench_water.out /thacker/schemes/finite_volume_order1/levels/0/l1)"
    holds "bench water lake at rest" "a <= 1e-10" \
        "$(json bench_water.out /lake_at_rest/largest_speed_m_per_s)"
    holds "bench water rain" "a > 0 && b > 0" \
        "$(json bench_water.out /rain_on_a_slope/0/pipes/step_ms_median)" \
        "$(json bench_water.out /rain_on_a_slope/0/finite_volume_order2/step_ms_median)"
    # Throughput rows: the CPU's always, the GPU's wherever a Vulkan device exists (timings
    # are not judged; their presence and sense are).
    holds "bench water CPU throughput" "a > 0 && b >= 20000" \
        "$(json bench_water.out /throughput/0/cpu/vertex_steps_per_s)" \
        "$(json bench_water.out /throughput/0/vertices)"
    holds "bench water 2-thread CPU throughput" "a > 0 && b == 2" \
        "$(json bench_water.out /throughput/0/cpu_2_threads/vertex_steps_per_s)" \
        "$(json bench_water.out /throughput/0/cpu_2_threads/threads)"
}

scenario_demo() {
    expect_ok demo demo --json || return
    check_eq "demo valid" "$(json demo.out /valid)" true
    holds "demo stamps" "a > 0" "$(json demo.out /stamps)"
    holds "demo constrained edges" "a > 0" "$(json demo.out /constrained_edges)"
    # Volume accounting: the terrain changed by exactly what the steps reported (the stroke
    # digs, the pour adds, erosion conserves), recomputed from scratch by `describe_terrain`.
    local expected
    expected=$(awk -v a="$(json demo.out /volume_before)" -v b="$(json demo.out /volume_reported)" \
        'BEGIN { printf "%.15g", a + b }')
    abs_le "$(json demo.out /volume)" "$expected" 1e-9 "demo volume accounted for"
    # The stroke dug: the reported change is negative and larger than the pour.
    holds "demo dug" "a < 0" "$(json demo.out /steps/0/volume_change)"
    # The result is saved, by default in the current directory, and the JSON says where.
    check_eq "demo file" "$(json demo.out /file)" sandtin-demo.sandtin
    expect_ok demo_info info sandtin-demo.sandtin --json || return
    check_eq "demo result valid" "$(json demo_info.out /valid)" true
    check_eq "demo result vertices" "$(json demo_info.out /vertices)" "$(json demo.out /vertices)"

    # Without --json: a short summary for a person, not a JSON document.
    expect_ok demo_plain demo -o "my demo.sandtin" || return
    grep -q "sandtin demo" demo_plain.out || fail "plain demo output lacks its title"
    if "$JSON_GET" demo_plain.out /valid >/dev/null 2>&1 || grep -q '^{' demo_plain.out; then
        fail "plain demo output is JSON: $(head -c 300 demo_plain.out)"
    fi
    holds "plain demo is short" "a <= 15" "$(wc -l <demo_plain.out)"
    grep -q "^  vertices  *$(json demo.out /vertices)$" demo_plain.out ||
        fail "plain demo lacks the vertex count: $(cat demo_plain.out)"
    grep -q "relief" demo_plain.out || fail "plain demo lacks the relief: $(cat demo_plain.out)"
    grep -q "^wrote my demo.sandtin$" demo_plain.out ||
        fail "plain demo does not say where it wrote: $(cat demo_plain.out)"
    [[ -s "my demo.sandtin" ]] || fail "demo -o wrote no file"
    # The command that opens the result: the editor beside this sandtin, the path quoted.
    local editor
    editor="$(dirname "$(dirname "$SANDTIN")")/app/sandtin-editor"
    local command
    command=$(grep -A1 "^open it in the editor:" demo_plain.out | tail -n 1 | sed 's/^  //')
    if [[ -x "$editor" ]]; then
        check_eq "editor command" "$command" "$editor 'my demo.sandtin'"
    else
        check_eq "editor command" "$command" "sandtin-editor 'my demo.sandtin'"
    fi
    [[ -s demo_plain.err ]] && fail "plain demo wrote to a piped stderr: $(cat demo_plain.err)"
    expect_error demo_bad_out "sandtin export" demo -o demo.png
}

# "extrude" on a stamp or stroke is shorthand for the tool's field: both spellings leave the same
# terrain, unlike no extrusion; given in both places, they must agree.
scenario_script_extrude() {
    local where
    for where in op tool none; do
        local tool='{"asset": "circle"}' op_field=''
        [[ $where == tool ]] && tool='{"asset": "circle", "extrude": true}'
        [[ $where == op ]] && op_field='"extrude": true,'
        cat >"extrude_$where.json" <<END_OF_SCRIPT
{"version": 1,
 "terrain": {"size": [1, 1], "points": 2000, "seed": 7, "height": 0.1},
 "operations": [
   {"op": "stroke", "tool": $tool, $op_field "path": [[0.3, 0.5], [0.7, 0.5]], "depth": 0.01},
   {"op": "stamp", "tool": $tool, $op_field "at": [0.5, 0.3], "depth": 0.01}]}
END_OF_SCRIPT
        expect_ok "run_$where" run "extrude_$where.json" -o "$where.sandtin" --json || return
    done
    cmp -s op.sandtin tool.sandtin || fail "extrude on the op and in the tool left other terrains"
    check_eq "same volume" "$(json run_op.out /terrain/volume)" "$(json run_tool.out /terrain/volume)"
    # Extrusion pushes the dug sand into a ridge: the volume stays, where a plain dig loses it.
    holds "extrusion kept the sand" "a > b" "$(json run_op.out /terrain/volume)"         "$(json run_none.out /terrain/volume)"
    holds "the ridge got sand" "a > 0" "$(json run_op.out /steps/0/deposited_volume)"

    cat >contradiction.json <<'END_OF_SCRIPT'
{"version": 1, "terrain": {"points": 100},
 "operations": [
   {"op": "stroke", "tool": {"asset": "circle", "extrude": false}, "extrude": true,
    "path": [[0.3, 0.5], [0.7, 0.5]], "depth": 0.01}]}
END_OF_SCRIPT
    expect_error contradiction "tool.extrude" run contradiction.json -o c.sandtin
    grep -q "contradiction.json:3: operation 1 (stroke): field 'extrude' is true" contradiction.err ||
        fail "the contradiction is not named by line and field: $(cat contradiction.err)"
    [[ -e c.sandtin ]] && fail "a contradictory script wrote a terrain"
    cat >width.json <<'END_OF_SCRIPT'
[{"op": "stamp", "tool": {"asset": "circle"}, "extrude": true, "extrusion_width": 0.02,
  "at": [0.5, 0.5]}]
END_OF_SCRIPT
    expect_error width "field 'extrusion_width' is a field of the tool" run width.json -o w.sandtin
}

# sandtin run: a good script in both forms, from a script terrain and from an input session.
# Oracles: the lines of the operations counted in the script text; a pour of V m^3 on flat sand
# of height H over a W x L m rectangle leaves W L H + V exactly, whatever the triangulation.
# The face rule from a script: a poured pile at rest has no triangle steeper than repose, as
# `info` measures it face by face; the same pile under the edge rule has many.
scenario_face_rule() {
    # face_jacobi: the face rule under the Jacobi schedule, on two threads.
    for rule in face edge face_jacobi; do
        settings="\"rule\": \"$rule\""
        if [[ $rule == face_jacobi ]]; then
            settings='"rule": "face", "schedule": "jacobi", "threads": 2'
        fi
        cat >"$rule.json" <<END_OF_SCRIPT
{"version": 1,
 "terrain": {"size": [1, 1], "points": 3000, "seed": 3},
 "settings": {$settings},
 "operations": [
   {"op": "pour", "at": [0.5, 0.5], "volume": 1e-3, "radius": 0.02},
   {"op": "erode", "until_rest": true}]}
END_OF_SCRIPT
        expect_ok "run_$rule" run "$rule.json" -o "$rule.sandtin" --json || return
        check_eq "$rule rule at rest" "$(json "run_$rule.out" /steps/1/at_rest)" true
        abs_le "$(json "run_$rule.out" /terrain/volume)" 1e-3 1e-15 "$rule rule volume"
        expect_ok "info_$rule" info "$rule.sandtin" --json || return
    done
    check_eq "face rule: steep faces" "$(json info_face.out /slopes/steep_faces)" 0
    holds "face rule: steepest face" "a <= 1.001" "$(json info_face.out /slopes/max_ratio)"
    check_eq "face rule, Jacobi: steep faces" "$(json info_face_jacobi.out /slopes/steep_faces)" 0
    holds "face rule, Jacobi: steepest face" "a <= 1.001" \
        "$(json info_face_jacobi.out /slopes/max_ratio)"
    holds "edge rule: steep faces" "a > 10" "$(json info_edge.out /slopes/steep_faces)"
    # The default is the face rule: a script that names no rule rests with no steep face.
    sed 's/"settings": {"rule": "face"},/"settings": {},/' face.json >default.json
    grep -q '"settings": {},' default.json || fail "could not write the default-rule script"
    expect_ok run_default run default.json -o default.sandtin --json || return
    expect_ok info_default info default.sandtin --json || return
    check_eq "default rule: steep faces" "$(json info_default.out /slopes/steep_faces)" 0
    sed 's/"rule": "face"/"rule": "faces"/' face.json >bad.json
    expect_error bad_rule "'rule' is 'faces'; expected one of: edge, face" run bad.json -o bad.sandtin
}

scenario_run_good() {
    cat >good.json <<'END_OF_SCRIPT'
{
  "version": 1,
  "terrain": {"size": [1, 1], "points": 2000, "seed": 5, "height": 0.1},
  "settings": {"simplify_tolerance": 0.0005},
  "operations": [
    {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.5, 0.5], "depth": 0.02},
    {"op": "stroke", "tool": {"asset": "box", "extrude": false},
     "path": [[0.2, 0.2], [0.4, 0.6], [0.8, 0.7]],
     "curve": true, "spacing": 0.01, "depth": 0.01},
    {"op": "stamp", "tool": {"asset": "lambda"}, "at": [0.7, 0.3], "angle": 0.5, "bottom": 0.05},
    {"op": "pour", "at": [0.3, 0.8], "volume": 1e-5, "radius": 0.03},
    {"op": "brush", "kind": "raise", "at": [0.7, 0.3], "radius": 0.05, "strength": 0.002},
    {"op": "simplify"}
  ]
}
END_OF_SCRIPT
    expect_ok run1 run good.json -o out.sandtin --json || return
    [[ -s out.sandtin ]] || fail "run wrote no file"
    check_eq "run steps" "$(json run1.out /steps/0/op /steps/1/op /steps/5/op | tr '\n' ' ')" \
        "stamp stroke simplify "
    check_eq "run step lines" \
        "$(json run1.out /steps/0/line /steps/1/line /steps/3/line | tr '\n' ' ')" "6 7 11 "
    check_eq "run valid" "$(json run1.out /terrain/valid)" true
    holds "stroke stamps" "a >= 50" "$(json run1.out /steps/1/stamps_applied)"
    expect_ok info1 info out.sandtin --json || return
    check_eq "info valid after run" "$(json info1.out /valid)" true
    check_eq "info vertices = run vertices" "$(json info1.out /vertices)" \
        "$(json run1.out /terrain/vertices)"
    # Only the pour (1e-5 m^3) and the raise brush (at most 0.002 * pi * 0.05^2) add sand; the
    # stamps and the stroke (no extrusion) only dig.
    holds "the run dug" "a < 0.1 + 1e-5 + 0.002 * 3.1416 * 0.0025" "$(json info1.out /volume)"
    # Plain output; the same script gives the same terrain.
    expect_ok run2 run good.json -o out2.sandtin || return
    grep -q "ran 6 operations" run2.out || fail "plain run output: $(cat run2.out)"
    cmp -s out.sandtin out2.sandtin || fail "the same script gave two different terrains"

    # A pour adds exactly its volume: 1 x 1 x 0.1 + 0.001.
    cat >pour.json <<'END_OF_SCRIPT'
{"terrain": {"points": 500, "seed": 2, "height": 0.1},
 "operations": [{"op": "pour", "at": [0.5, 0.5], "volume": 0.001, "radius": 0.05}]}
END_OF_SCRIPT
    expect_ok pour1 run pour.json -o pour.sandtin --json || return
    abs_le "$(json pour1.out /terrain/volume)" 0.101 1e-12 "volume after the pour"
    abs_le "$(json pour1.out /volume_before)" 0.1 1e-12 "volume before the pour"

    # From an input session (-i), which stays as it was: 2 x 1 x 0.2 + 0.002.
    expect_ok new1 new --flat 2 1 --points 1000 --seed 3 --height 0.2 -o in.sandtin || return
    cp in.sandtin in.orig
    cat >pour2.json <<'END_OF_SCRIPT'
[
  {"op": "pour", "path": [[0.5, 0.5], [1.5, 0.5]], "volume": 0.002, "radius": 0.04}
]
END_OF_SCRIPT
    expect_ok pour2 run pour2.json -i in.sandtin -o from_in.sandtin --json || return
    abs_le "$(json pour2.out /terrain/volume)" 0.402 1e-12 "volume after pouring on the input"
    cmp -s in.sandtin in.orig || fail "run changed its input file"
    expect_ok info2 info from_in.sandtin --json || return
    check_eq "input run valid" "$(json info2.out /valid)" true
    abs_le "$(json info2.out /volume)" 0.402 1e-12 "saved volume"

    # A tool bigger than the terrain, extruding: the sand it pushes has nowhere to go. The run
    # succeeds, and says on stderr, naming the line, how much left the terrain; a good run
    # says nothing there.
    grep -q "warning" run2.err && fail "a run with nothing to warn of warned: $(cat run2.err)"
    cat >lost.json <<'END_OF_SCRIPT'
{"terrain": {"points": 500, "seed": 2, "height": 0.1},
 "operations": [
   {"op": "stamp", "tool": {"radius": 5, "control_points": 64, "extrude": true},
    "at": [0.5, 0.5], "bottom": 0.08}]}
END_OF_SCRIPT
    expect_ok lost1 run lost.json -o lost.sandtin || return
    grep -q "warning: lost.json:3: operation 1 (stamp): extrusion had nowhere to put 0.02 m" \
        lost1.err || fail "no warning of the lost extrusion: $(cat lost1.err)"

    # Neither -i nor a terrain: a usage error and no file.
    printf '[{"op": "simplify"}]\n' >noterrain.json
    expect_error noterrain "terrain" run noterrain.json -o noterrain.sandtin
    [[ -e noterrain.sandtin ]] && fail "a failed run left noterrain.sandtin behind"
    return 0
}

# Bad scripts: a message naming the line and the field, a non-zero exit, the input session
# byte-identical and no output file.
scenario_run_bad() {
    expect_ok new1 new --flat 1 1 --points 500 --seed 4 --height 0.1 -o in.sandtin || return
    cp in.sandtin in.orig
    local ok='  {"op": "pour", "at": [0.5, 0.5], "volume": 1e-5},'
    {
        echo "["
        for _ in 1 2 3 4 5; do echo "$ok"; done
        echo '  {"op": "pour", "at": [0.5, 0.5], "volume": 1e-5, "radius": -0.02}'
        echo "]"
    } >radius.json
    {
        echo "["
        echo "$ok"
        echo '  {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.5, 0.5], "depht": 0.01}'
        echo "]"
    } >field.json
    printf '[\n%s\n  {"op": "dig", "at": [0.5, 0.5]}\n]\n' "$ok" >op.json
    printf '[\n%s\n%s\n  {"op": "pour" "at": [0.5, 0.5]}\n]\n' "$ok" "$ok" >syntax.json
    printf '[\n  {"op": "stamp", "tool": {"asset": "nope"}, "at": [0.5, 0.5]}\n]\n' >asset.json

    local spec name keyword line
    for spec in "radius:radius:7" "field:depht:3" "op:dig:3" "syntax:JSON:4" "asset:asset:2"; do
        IFS=: read -r name keyword line <<<"$spec"
        expect_error "bad_$name" "$keyword" run "$name.json" -i in.sandtin -o "out_$name.sandtin"
        grep -q "$name.json:$line:" "bad_$name.err" ||
            fail "bad_$name: stderr does not name line $line: $(cat "bad_$name.err")"
        [[ -e "out_$name.sandtin" ]] && fail "bad_$name: a failed run created out_$name.sandtin"
        cmp -s in.sandtin in.orig || fail "bad_$name: the input session changed"
    done
    # Even when the output is the input itself.
    expect_error bad_inplace "radius" run radius.json -i in.sandtin -o in.sandtin
    cmp -s in.sandtin in.orig || fail "a bad script run in place changed the input"
    # A missing script, a missing input, no output given.
    expect_error missing_script "missing.json" run missing.json -i in.sandtin -o out_missing.sandtin
    [[ -e out_missing.sandtin ]] && fail "a run without its script created its output"
    printf '[{"op": "simplify"}]\n' >fine.json
    expect_error missing_input "nosuch.sandtin" run fine.json -i nosuch.sandtin -o out_noin.sandtin
    [[ -e out_noin.sandtin ]] && fail "a run without its input created its output"
    expect_error no_output "-o" run fine.json -i in.sandtin
    cmp -s in.sandtin in.orig || fail "the input session changed"
    # The script is not an output: not as -o, not through a link, not as a save op's path
    # (named with its line, before any work). The script stays as it was.
    cp fine.json fine.orig
    ln -sf fine.json fine_link.sandtin
    expect_error script_as_output ".json" run fine.json -i in.sandtin -o fine.json
    expect_error script_via_link "the script being run" run fine.json -i in.sandtin -o fine_link.sandtin
    # Nor is any name that says mesh, map or heightmap.
    expect_error session_as_png "name it .sandtin" new --flat 1 1 -o looks_like.png
    [[ -e looks_like.png ]] && fail "new wrote a session named looks_like.png"
    printf '[\n  {"op": "simplify"},\n  {"op": "save", "path": "self.json"}\n]\n' >self.json
    cp self.json self.orig
    expect_error script_saved_over "self.json:3:" run self.json -i in.sandtin -o out_self.sandtin
    [[ -e out_self.sandtin ]] && fail "a script saving over itself created the output"
    cmp -s fine.json fine.orig || fail "-o naming the script changed it"
    cmp -s self.json self.orig || fail "a save op naming the script changed it"
    printf '[\n  {"op": "simplify"},\n  {"op": "save", "path": "nodir/cp.sandtin"}\n]\n' >nodir.json
    expect_error save_nowhere "nodir.json:3:" run nodir.json -i in.sandtin -o out_nodir.sandtin
    [[ -e out_nodir.sandtin ]] && fail "a checkpoint that cannot be written still ran the script"
    # A pipe in the output's place is refused, and stays a pipe.
    mkfifo pipe.sandtin
    expect_error pipe_output "named pipe" run fine.json -i in.sandtin -o pipe.sandtin
    [[ -p pipe.sandtin ]] || fail "the pipe at the output was replaced"
    cmp -s in.sandtin in.orig || fail "the input session changed"
    return 0
}

# The example script in README.md ("Scripts") runs as the README says: its foot stroke digs a
# groove, its pour adds exactly its volume, and its save op writes next to the script. Without a
# depth the same stroke changes nothing on flat sand, as the README says too.
scenario_readme_script() {
    awk '/To cut a groove, give a depth:/ { want = 1; next }
         want && /^```json$/ { inside = 1; next }
         inside && /^```$/ { exit }
         inside { print }' "$README" >readme.json
    [[ -s readme.json ]] || { fail "no example script after 'To cut a groove' in $README"; return; }
    expect_ok readme run readme.json -o readme.sandtin --json || return
    check_eq "README script ops" "$(json readme.out /steps/0/op /steps/1/op /steps/3/op | tr '\n' ' ')" \
        "stroke pour save "
    check_eq "README script valid" "$(json readme.out /terrain/valid)" true
    # The stroke's own account of what it dug. The foot (assets/tools/foot.obj) is 0.26 m long
    # and 0.1 m wide, so it sweeps at most 0.86 x 0.1 m along the 0.6 m path, and it digs at
    # most 1 cm deep: below 8.6e-4 m^3. It must dig more than 0.1 mm over that box.
    holds "the README stroke dug" "a > 8.6e-6 && a < 8.6e-4" \
        "$(json readme.out /steps/0/displaced_volume)"
    abs_le "$(json readme.out /steps/1/volume_change)" 0.0005 1e-12 "the README pour"
    [[ -s groove.sandtin ]] || fail "the README script's save op wrote no groove.sandtin"
    expect_ok readme_info info groove.sandtin --json || return
    check_eq "saved checkpoint valid" "$(json readme_info.out /valid)" true

    sed 's/, "depth": 0.01//' readme.json >nodepth.json
    grep -q '"depth"' nodepth.json && { fail "could not take the depth out of the script"; return; }
    expect_ok nodepth run nodepth.json -o nodepth.sandtin --json || return
    check_eq "a stroke without depth on flat sand" "$(json nodepth.out /steps/0/displaced_volume)" 0.0
    return 0
}

case "$SCENARIO" in
    roundtrip) scenario_roundtrip ;;
    bad_input) scenario_bad_input ;;
    bench) scenario_bench ;;
    bench_water) scenario_bench_water ;;
    demo) scenario_demo ;;
    run_good) scenario_run_good ;;
    face_rule) scenario_face_rule ;;
    run_bad) scenario_run_bad ;;
    readme_script) scenario_readme_script ;;
    script_extrude) scenario_script_extrude ;;
    *)
        echo "unknown scenario $SCENARIO" >&2
        exit 2
        ;;
esac

if [[ $failures -ne 0 ]]; then
    echo "$failures check(s) failed in scenario $SCENARIO" >&2
    exit 1
fi
echo "scenario $SCENARIO: all checks passed"
