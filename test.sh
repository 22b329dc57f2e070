#!/usr/bin/env bash
# Installs what is missing, builds sandtin, and runs the whole test suite:
#   1. Release build, every ctest (GPU on lavapipe, the editor under Xvfb, 5 x 3 000-operation
#      stress sessions);
#   2. AddressSanitizer + UndefinedBehaviorSanitizer (clang) over the engine rooms' tests, and
#      libFuzzer on the session loader, every importer, the script parser and the haptic packet
#      decoder, SANDTIN_FUZZ_SECONDS (default 5) each, from the same build;
#   3. ThreadSanitizer over the threaded parts (haptics loop, multithreaded Jacobi, the
#      autosave writer).
# Arguments are passed to the first ctest (e.g. ./test.sh -L tin). SANDTIN_TEST_PASSES picks
# passes (default "release asan tsan fuzz").
set -euo pipefail
cd "$(dirname "$0")"

scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
passes=${SANDTIN_TEST_PASSES:-release asan tsan fuzz}
has_pass() { [[ " $passes " == *" $1 "* ]]; }
# The checking builds (sanitizers, fuzzing) compile at -O1 with line tables only, as the
# sanitizers' documentation recommends: half the compile time of -O2 -g (tin.cpp under ASan:
# 46 s against 90 s), readable stack traces, and the same tests pass in the same time.
checking_flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG")
section() { printf '\n=== %s (%s)\n' "$1" "$(date +%T)"; }

if has_pass release; then
  section "release build and the whole suite"
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
  cmake --build build -j"$jobs"
  ctest --test-dir build --output-on-failure -j"$jobs" "$@"
fi

# The engine rooms under ASan+UBSan, and the libFuzzer targets, in one clang build: the fuzz
# configuration already compiles every library with ASan and UBSan, so the tests and the
# fuzzers share one compile of the engine (a separate GCC ASan tree cost CI eight minutes).
# GPU, editor and CLI tests stay in the release pass: their drivers (lavapipe, the X server)
# are not ours to sanitize. Long sessions are the release pass's job too; here the short tests
# cover the same code (the half and quarter cones and the two-triangle pile, 59 s and 33 s under
# ASan, run the relaxation and the r_S splits that the Jacobi two-triangle pile runs in 4 s).
# The threaded Jacobi schedule's bit-for-bit comparisons (2 x 12 s here) run under ThreadSanitizer
# below; the 10^5-vertex one-and-two-threads determinism check (19 s here, 63 s under TSan) runs
# in the release pass only, its threaded code reaching ThreadSanitizer through the schedule
# tests and AddressSanitizer through Determinism.JacobiOnOneAndTwoThreads; the long groove eroded to rest (27 s) repeats
# the relaxation and splits of the shorter erode tests; a script's projected pour (20 s here)
# repeats the projection that ReposeProjection.* runs under AddressSanitizer. The water's long
# runs (the lake at rest's 10^4 steps, 30 s here; the script's eroding streams, 38 and 28 s)
# repeat the steps and the sediment code that the shorter water tests run here, and a stroke's
# volume (28 s) the extrusion that the border stamp's conservation test runs. Under 12 s each
# but repeating what others run here: both schemes carrying water between two script ops (the
# kept water's shorter tests), sand on steep rock (the point pour's projection), three strokes
# (the thousand-stamp stroke), the banded letter and star (the polygon tests' other shapes).
# The collapsing cone settled with and without vertices on its bends (101 s here, 6 s in the
# release pass) repeats the fitting and the projection that the script's fit_bends erode runs
# here (51 s).
engine_tests=(sandtin_tin_tests sandtin_io_tests sandtin_geom_tests sandtin_tools_tests
  sandtin_terrain_io_tests sandtin_physics_tests sandtin_stress_tests sandtin_haptics_core_tests
  sandtin_history_tests sandtin_water_tests)
fuzzers=(fuzz_session fuzz_script fuzz_udp_packet fuzz_png fuzz_esri_ascii fuzz_exr fuzz_geotiff)
if has_pass asan || has_pass fuzz; then
  section "clang: AddressSanitizer + UndefinedBehaviorSanitizer, then libFuzzer"
  targets=()
  has_pass asan && targets+=("${engine_tests[@]}")
  has_pass fuzz && targets+=("${fuzzers[@]}")
  CC=clang-14 CXX=clang++-14 cmake -S . -B build-clang-asan -G Ninja "${checking_flags[@]}" \
    -DSANDTIN_FUZZ=ON -DSANDTIN_FUZZ_SECONDS="${SANDTIN_FUZZ_SECONDS:-5}"
  cmake --build build-clang-asan -j"$jobs" --target "${targets[@]}"
  if has_pass asan; then
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --test-dir build-clang-asan --output-on-failure -j"$jobs" \
      -L '^(tin|io|geom|tools|terrain_io|physics|stress|tsan|history|water)$' \
      -E '^(stress\.session_seed_|LongStroke\.|Conservation\.|AnalyticPile\.(AgainstAWall|TwoTriangleFlatTerrainGrows)|Jacobi\.OneAndTwoThreads|JacobiSchedule\.(OneThreadMatchesItsDefinitionBitForBit|TwoThreadsMatch)|ErodeScript\.AGrooveErodedWithARelocationRadius|Script\.AnErodeThatProjectsFirst|SettleFittedToKinks\.PutsACollapsingCone|ShallowWater\.(Ritters|Stokers|Thackers|ALakeAtRest)|ScriptWater\.(WaterThatErodes|SandTheWaterLaysDown)|ScriptWaterKept\.TheWaterOneOperation|Extrusion\.StrokeConservesVolume|ReposeProjection\.SandOnSteepRock|Stroke\.(CutsTheRequestedDepth|AClickPutsItsRidge|ARakeStroke)|PolygonInclusion\.BandedLetterAndStar)'
  fi
  if has_pass fuzz; then
    ctest --test-dir build-clang-asan --output-on-failure -j"$jobs" -L '^fuzz$'
  fi
fi

if has_pass tsan; then
  section "ThreadSanitizer"
  cmake -S . -B build-tsan -G Ninja "${checking_flags[@]}" -DSANDTIN_TSAN=ON
  cmake --build build-tsan -j"$jobs" --target sandtin_haptics_core_tests sandtin_physics_tests \
    sandtin_io_tests
  export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
  # The haptics core (label tsan), then the multithreaded Jacobi (its one-thread comparisons
  # have nothing to race and took TSan 70 s), the thread pool and the autosave writer, each
  # test in its own process so that both cores are busy (run one after another in a single
  # process, they left a core idle for about a minute). The determinism sessions (tests/stress) run the same
  # thread pool through a whole session; they run in the release and ASan passes, and are not
  # built here (their binary alone cost the TSan pass about half a minute).
  ctest --test-dir build-tsan --output-on-failure -j"$jobs" -L '^tsan$'
  ctest --test-dir build-tsan --output-on-failure -j"$jobs" \
    -R '^(Jacobi|Randomisation|ThreadPool)\.|^JacobiSchedule\.TwoThreads|^Autosave\.Writer' \
    -E '^Jacobi\.OneAndTwoThreadsAreBitwiseIdentical$'
  unset TSAN_OPTIONS
fi

section "all passes done"
