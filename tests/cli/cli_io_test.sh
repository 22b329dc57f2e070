#!/usr/bin/env bash
# End-to-end tests of `sandtin import`, `sandtin export` and `sandtin bench import`.
# usage: cli_io_test.sh /path/to/sandtin <scenario> <work-dir> /path/to/json_get <data-dir> \
#          /path/to/session_metadata
#   scenarios: import, export, import_bad, export_bad, bench_import
set -uo pipefail

SANDTIN=${1:?path to the sandtin binary}
SCENARIO=${2:?scenario}
WORK=${3:?work directory}
JSON_GET=${4:?path to json_get}
DATA=${5:?test data directory}
SESSION_METADATA=${6:?path to session_metadata}
TILE="$DATA/bay-hills-terrain-rgb.png"

rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK" || exit 1
# shellcheck source=cli_lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/cli_lib.sh"

scenario_import() {
    expect_ok imp10 import "$TILE" --max-error 10 -o bay10.sandtin --json || return
    holds "points at 10 m (delatin: 190)" "a <= 190 && a >= 4" "$(json imp10.out /points)"
    holds "max error at 10 m" "a <= 10" "$(json imp10.out /max_error)"
    check_eq "format" "$(json imp10.out /format)" terrain-rgb
    check_eq "raster" "$(json imp10.out /raster/width /raster/height | tr '\n' ' ')" "512 512 "
    check_eq "reached" "$(json imp10.out /reached_error)" true
    holds "rmsd" "a > 0 && a < b" "$(json imp10.out /rmsd)" "$(json imp10.out /max_error)"
    # The session holds what the import reported.
    expect_ok info10 info bay10.sandtin --json || return
    check_eq "info vertices" "$(json info10.out /vertices)" "$(json imp10.out /points)"
    check_eq "info triangles" "$(json info10.out /triangles)" "$(json imp10.out /triangles)"
    check_eq "info valid" "$(json info10.out /valid)" true
    check_eq "bbox" "$(json info10.out /bbox/max/0 /bbox/max/1 | tr '\n' ' ')" "511.0 511.0 "

    # Point limit, pixel size and z-scale.
    expect_ok imp_n import "$TILE" --max-error 0.2 --max-points 300 --pixel-size 2 \
        --z-scale 0.5 -o n.sandtin --json || return
    check_eq "point limit" "$(json imp_n.out /points)" 300
    check_eq "not reached" "$(json imp_n.out /reached_error)" false
    expect_ok info_n info n.sandtin --json || return
    check_eq "pixel size" "$(json info_n.out /bbox/max/0)" 1022.0
    holds "z-scale halves heights" "a < 130" "$(json info_n.out /bbox/max/2)"

    # An ASCII grid with a no-data hole, and plain output.
    {
        echo "ncols 6"; echo "nrows 5"; echo "xllcorner 100"; echo "yllcorner 200"
        echo "cellsize 2"; echo "NODATA_value -9999"
        echo "1 2 3 4 5 6"; echo "2 3 4 5 6 7"; echo "3 4 -9999 6 7 8"
        echo "4 5 6 7 8 9"; echo "5 6 7 8 9 10"
    } >grid.asc
    expect_ok asc import grid.asc --max-error 0 -o grid.sandtin --json || return
    check_eq "asc no-data" "$(json asc.out /raster/nodata_samples)" 1
    check_eq "asc georeference" "$(json asc.out /georeference/west)" 101.0
    holds "asc exact" "a <= 1e-9" "$(json asc.out /max_error)"
    expect_ok asc_plain import grid.asc --max-error 0.5 -o grid2.sandtin || return
    grep -q "points" asc_plain.out || fail "plain import output lacks points"
}

scenario_export() {
    expect_ok imp import "$TILE" --max-error 5 -o bay.sandtin --json || return
    local points triangles
    points=$(json imp.out /points)
    triangles=$(json imp.out /triangles)
    for ext in obj ply stl gltf glb; do
        expect_ok "exp_$ext" export bay.sandtin -o "bay.$ext" --json || continue
        check_eq "$ext vertices" "$(json "exp_$ext.out" /vertices)" "$points"
        check_eq "$ext triangles" "$(json "exp_$ext.out" /triangles)" "$triangles"
        [[ -s "bay.$ext" ]] || fail "$ext: no file"
    done
    [[ -s bay.mtl && -s bay_albedo.png && -s bay_normal.png ]] || fail "obj companions missing"
    # Solid base for printing, in millimetres.
    expect_ok solid export bay.sandtin -o solid.stl --base 20 --units mm --json || return
    holds "solid adds walls and bottom" "a > b" "$(json solid.out /triangles)" "$triangles"
    check_eq "solid bottom in mm" "$(json solid.out /bbox/max/0)" 511000.0
    # Height map: the import grid by default, and it re-imports.
    expect_ok hpng export bay.sandtin -o h.png --json || return
    check_eq "height map size" "$(json hpng.out /map/width /map/height | tr '\n' ' ')" "512 512 "
    expect_ok reimp import h.png --max-error 5 -o re.sandtin --json || return
    check_eq "re-import size" "$(json reimp.out /raster/width)" 512
    check_eq "re-import cell" "$(json reimp.out /raster/cell_size)" 1.0
    expect_ok hexr export bay.sandtin -o h.exr --json || return
    expect_ok reexr import h.exr --max-error 5 -o re2.sandtin --json || return
    check_eq "exr re-import size" "$(json reexr.out /raster/width)" 512
    expect_ok nmap export bay.sandtin -o n.png --map normal --size 256 --json || return
    check_eq "normal map" "$(json nmap.out /format)" normal-png
    expect_ok amap export bay.sandtin -o a.png --map albedo --size 64 || return
    # Simplify on export.
    expect_ok simp export bay.sandtin -o s.ply --max-error 20 --json || return
    holds "simplified" "a < b" "$(json simp.out /vertices)" "$points"
    holds "simplified error" "a <= 20" "$(json simp.out /simplified/max_error)"
    expect_ok plain export bay.sandtin -o p.obj --no-textures --up z || return
    grep -q "wrote p.obj" plain.out || fail "plain export output lacks the file"
    [[ -e p_albedo.png ]] && fail "--no-textures still wrote textures"
    check_eq "unedited: the import grid" "$(json hpng.out /default_sampling/grid)" "the import grid"

    # Edits between the import grid's samples: a 0.5 m pit on a flat 2 m grid. The default map
    # and the default simplification raster must sample finely enough to keep it.
    {
        printf 'ncols 21\nnrows 21\nxllcorner 0\nyllcorner 0\ncellsize 2\n'
        for _ in $(seq 21); do printf '5 %.0s' $(seq 21); printf '\n'; done
    } >flat2m.asc
    expect_ok imp_flat import flat2m.asc --max-error 0 -o flat2m.sandtin || return
    printf '[{"op": "stamp", "tool": {"contour": "circle", "radius": 0.6, "profile": "flat"},
      "at": [21, 19], "depth": 0.5}]\n' >pit.json
    expect_ok pit run pit.json -i flat2m.sandtin -o pit.sandtin || return
    expect_ok pit_png export pit.sandtin -o pit.png --json || return
    check_eq "edited: a finer grid" "$(json pit_png.out /default_sampling/grid)" \
        "finer than the import grid, which edits have left"
    expect_ok pit_back import pit.png --max-error 0.01 -o pit_back.sandtin || return
    expect_ok pit_info info pit_back.sandtin --json || return
    holds "the pit survives export and import" "a < 4.6" "$(json pit_info.out /bbox/min/2)"
    expect_ok pit_ply export pit.sandtin -o pit.ply --max-error 0.01 --json || return
    holds "the simplified mesh keeps the pit" "a > 4" "$(json pit_ply.out /vertices)"
    # The georeference survives export and re-import, of a height PNG and of an EXR.
    printf 'ncols 3\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 2\n1 2 3\n2 3 4\n3 4 5\n' >geo.asc
    expect_ok geo_imp import geo.asc --max-error 0 -o geo.sandtin || return
    for ext in png exr; do
        expect_ok "geo_$ext" export geo.sandtin -o "geo.$ext" || return
        expect_ok "geo_back_$ext" import "geo.$ext" --max-error 0 -o "geo_$ext.sandtin" --json || return
        check_eq "$ext georeference" \
            "$(json "geo_back_$ext.out" /georeference/west /georeference/south | tr '\n' ' ')" "1001.0 2001.0 "
    done
    expect_ok pit_note export pit.sandtin -o pit2.png || return
    grep -q "note: edits put vertices between the samples" pit_note.out ||
        fail "no note on the finer sampling: $(cat pit_note.out)"
    return 0
}

scenario_import_bad() {
    : >empty.png
    expect_error empty "empty" import empty.png --max-error 1 -o x.sandtin
    head -c 5000 "$TILE" >truncated.png
    expect_error truncated "PNG" import truncated.png --max-error 1 -o x.sandtin
    echo "not a picture" >text.png
    expect_error text "not a heightmap" import text.png --max-error 1 -o x.sandtin
    expect_error missing "missing.png" import missing.png --max-error 1 -o x.sandtin
    printf 'ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 nan 6\n' >nan.asc
    expect_error nan "not finite" import nan.asc --max-error 1 -o x.sandtin
    expect_ok nan_ok import nan.asc --max-error 1 --nonfinite-as-nodata -o ok.sandtin --json
    printf 'ncols 3\nrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n' >hdr.asc
    expect_error header "'rows' is not an ESRI ASCII grid header key" import hdr.asc --max-error 1 -o x.sandtin
    printf 'ncols 0\nnrows 0\nxllcorner 0\nyllcorner 0\ncellsize 1\n' >zero.asc
    expect_error zero "empty" import zero.asc --max-error 1 -o x.sandtin
    expect_error too_big "exceeds the limit of 100 x 100" import "$TILE" --max-error 1 --max-size 100 100 -o x.sandtin
    expect_error no_error "--max-error" import "$TILE" -o x.sandtin
    expect_error neg_error "max-error" import "$TILE" --max-error -1 -o x.sandtin
    expect_error nan_error "not a finite number" import "$TILE" --max-error nan -o x.sandtin
    expect_error few_points "at least 4" import "$TILE" --max-error 1 --max-points 3 -o x.sandtin
    expect_error bad_pixel "pixel-size" import "$TILE" --max-error 1 --pixel-size 0 -o x.sandtin
    expect_error bad_encoding "encoding" import "$TILE" --max-error 1 --encoding jpeg -o x.sandtin
    expect_error gray_forced "grayscale" import "$TILE" --max-error 1 --encoding gray -o x.sandtin
    expect_error no_output "-o" import "$TILE" --max-error 1
    expect_error no_dir "nosuchdir" import "$TILE" --max-error 1 -o nosuchdir/x.sandtin
    [[ -e x.sandtin ]] && fail "a failed import left x.sandtin behind"
    expect_error tiny_pixels "nan.asc (with its pixel size" import nan.asc --max-error 1 --nonfinite-as-nodata --pixel-size 1e-12 -o x.sandtin
    expect_error encoding_asc "applies to PNG heightmaps" import nan.asc --max-error 1 --encoding gray -o x.sandtin
    expect_error huge_offset "--z-offset" import "$TILE" --max-error 1 --z-offset 1e308 -o x.sandtin
    # The heightmap is not an output: importing over itself would destroy it.
    printf 'ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n5 6\n7 8\n' >self.asc
    cp self.asc self.orig
    ln -sf self.asc self_link.sandtin
    expect_error over_itself "the heightmap being imported" import self.asc --max-error 0.1 -o self_link.sandtin
    cmp -s self.asc self.orig || fail "importing a heightmap over itself changed it"
    return 0
}

scenario_export_bad() {
    expect_ok new new --flat 10 10 --points 50 -o s.sandtin || return
    expect_error ext "unknown output type" export s.sandtin -o s.fbx
    expect_error map "unknown map" export s.sandtin -o s.png --map curvature
    expect_error map_obj "--map applies" export s.sandtin -o s.obj --map normal
    expect_error gltf_z "Y-up" export s.sandtin -o s.glb --up z
    expect_error up "--up" export s.sandtin -o s.obj --up x
    expect_error units "unit" export s.sandtin -o s.obj --units furlong
    expect_error both "at most one" export s.sandtin -o s.stl --base 1 --skirt 1
    expect_error depth "positive" export s.sandtin -o s.stl --base -1
    expect_error map_base "meshes" export s.sandtin -o s.png --base 1
    expect_error size "--size" export s.sandtin -o s.png --size 1
    expect_error missing "missing.sandtin" export missing.sandtin -o s.obj
    echo "garbage" >g.sandtin
    expect_error garbage "not a sandtin" export g.sandtin -o s.obj
    expect_error no_dir "nosuchdir" export s.sandtin -o nosuchdir/s.stl
    # Options the output would ignore are errors.
    expect_error size_and_cell "at most one of --cell-size and --size" export s.sandtin -o a.png --size 64 --cell-size 2
    expect_error units_map "--units applies to meshes" export s.sandtin -o a.png --units km
    expect_error cell_stl "--cell-size applies to" export s.sandtin -o a.stl --cell-size 1
    expect_error textures_ply "--no-textures applies to" export s.sandtin -o a.ply --no-textures
    expect_error faceted_height "--faceted applies to" export s.sandtin -o a.png --faceted
    expect_ok cell_stl_simplified export s.sandtin -o b.stl --cell-size 1 --max-error 0.01 || return
    [[ -e a.png || -e a.stl || -e a.ply ]] && fail "a refused export wrote a file"
    # --cell-size spaces the texels of normal and albedo maps too (10 m / 0.4 m = 25 texels).
    for map in normal albedo; do
        expect_ok "cell_$map" export s.sandtin -o "c_$map.png" --map "$map" --cell-size 0.4 --json ||
            return
        check_eq "$map map width at --cell-size 0.4" "$(json "cell_$map.out" /map/width)" 25
        check_eq "$map map texel at --cell-size 0.4" "$(json "cell_$map.out" /map/cell_size)" 0.4
    done
    # A tiny cell is named as given, not rounded to 0.000000.
    expect_error tiny_cell "cell size of 1e-07 m" export s.sandtin -o tiny.png --cell-size 1e-7
    # Its companions' names are bare words in the OBJ and MTL: a space would split them.
    expect_ok spaced export s.sandtin -o "my scene.obj" || return
    grep -qx "mtllib my_scene.mtl" "my scene.obj" || fail "mtllib line: $(grep mtllib "my scene.obj")"
    grep -qx "map_Kd my_scene_albedo.png" my_scene.mtl || fail "map_Kd line: $(grep map_Kd my_scene.mtl)"
    [[ -s my_scene_albedo.png && -s my_scene_normal.png ]] || fail "textures named with spaces"
    # An OBJ's four files are one save: a folder where its normal map goes leaves none of them.
    mkdir -p objset/m_normal.png
    expect_error obj_set "m_normal.png" export s.sandtin -o objset/m.obj
    check_eq "files left by a failed OBJ export" "$(ls objset)" "m_normal.png"
    # Coordinates beyond 32-bit floats are an error, not infinities in the file.
    expect_error huge_base "32-bit floats" export s.sandtin -o huge.stl --base 1e40
    [[ -e huge.stl ]] && fail "an export beyond float range wrote huge.stl"
    # A map's cell size defaults to the one the terrain was imported with. When the session's
    # metadata holds one no map can use, that is bad data in the file (exit 1, naming it), not
    # a usage error (exit 2); an explicit --size still exports.
    printf 'ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n0 1 2\n1 2 3\n2 3 4\n' >g.asc
    expect_ok imp_g import g.asc --max-error 0 -o g.sandtin || return
    "$SESSION_METADATA" g.sandtin tiny.sandtin /import/raster/cell_size 1e-300 ||
        fail "session_metadata could not write tiny.sandtin"
    expect_error tiny_meta "tiny.sandtin: the import cell size in the session's metadata" \
        export tiny.sandtin -o tiny_meta.png
    check_eq "exit code for bad session data" "$rc" 1
    grep -q -- "--cell-size or --size" tiny_meta.err || fail "no way out named: $(cat tiny_meta.err)"
    expect_ok tiny_meta_sized export tiny.sandtin -o tiny_meta.png --size 8 || return
    # A scene's own material colours (the editor's Materials panel writes them into its
    # metadata) reach the albedo map and the OBJ material; before, exports used fixed colours.
    "$SESSION_METADATA" g.sandtin red.sandtin /materials \
        '[{"name": "red_sand", "colour": [0.6, 0.05, 0.0]}]' ||
        fail "session_metadata could not write red.sandtin"
    expect_ok red_map export red.sandtin -o red.png --map albedo --size 8 || return
    expect_ok plain_map export g.sandtin -o plain.png --map albedo --size 8 || return
    cmp -s red.png plain.png && fail "the recoloured scene exported the preset colours"
    expect_ok red_obj export red.sandtin -o red.obj || return
    grep -q "^Kd 0.6" red.mtl || fail "MTL colour of the recoloured scene: $(grep Kd red.mtl)"
    return 0
}

scenario_bench_import() {
    # A smoke test of the driver (delatin is left out: its timing is not judged here).
    SANDTIN_DELATIN_DIR=/nonexistent expect_ok bench bench import --quick --json || return
    check_eq "bench name" "$(json bench.out /bench)" import
    holds "10 m points" "a <= 190" "$(json bench.out /sandtin/0/points)"
    holds "0.2 m points" "a <= 16257" "$(json bench.out /sandtin/2/points)"
    check_eq "0.2 m bound" "$(json bench.out /sandtin/2/bound_met)" true
    check_eq "delatin skipped" "$(json bench.out /delatin/available)" false
    check_eq "rough tile" "$(json bench.out /rough_tiles/0/tile)" fbm-256
    check_eq "rough tile bound" "$(json bench.out /rough_tiles/0/sandtin/0/bound_met)" true
    holds "rough tile relief (m)" "a > 1000" "$(json bench.out /rough_tiles/0/raster/relief_m)"
}

case "$SCENARIO" in
    import) scenario_import ;;
    export) scenario_export ;;
    import_bad) scenario_import_bad ;;
    export_bad) scenario_export_bad ;;
    bench_import) scenario_bench_import ;;
    *)
        echo "unknown scenario $SCENARIO" >&2
        exit 2
        ;;
esac
finish "$SCENARIO"
