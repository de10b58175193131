#!/usr/bin/env bash
# libFuzzer runs of the loaders of outside data (tests/fuzz/<name>_fuzz.cpp).
#   tools/fuzz.sh --list          names the fuzzers
#   tools/fuzz.sh NAME SECONDS    builds fuzz_NAME (clang, ASan + UBSan, build-fuzz/) and fuzzes
#                                 it for SECONDS from the seed corpus (test data, configs)
# Exits non-zero on a crash, a sanitizer report, an uncaught non-project exception, a leak, a
# hang (an input running over SIMS_FUZZ_TIMEOUT s, default 20) or an input needing more than
# SIMS_FUZZ_RSS_MB (default 2048) of memory; the input is saved under build-fuzz/artifacts/NAME/.
# Corpora grow in build-fuzz/corpus/NAME. Builds use SIMS_JOBS (default 2) jobs;
# SIMS_FUZZ_SKIP_BUILD=1 skips the build (to run several fuzzers in parallel after one build).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${SIMS_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}"
FUZZERS=(bvh script plan scene_plan front3d mesh_obj mesh_ply config env_state checkpoint)

usage() { echo "usage: tools/fuzz.sh --list | NAME SECONDS" >&2; exit 2; }
[ $# -ge 1 ] || usage
if [ "$1" = "--list" ]; then printf '%s\n' "${FUZZERS[@]}"; exit 0; fi
[ $# -eq 2 ] || usage
NAME="$1" SECONDS_TO_RUN="$2"
[[ " ${FUZZERS[*]} " == *" $NAME "* ]] || { echo "unknown fuzzer '$NAME' (tools/fuzz.sh --list)" >&2; exit 2; }
[[ "$SECONDS_TO_RUN" =~ ^[1-9][0-9]*$ ]] || { echo "SECONDS: a positive integer" >&2; exit 2; }
command -v clang++ >/dev/null || { echo "clang++ not found: run cmake/setup.sh" >&2; exit 2; }

if [ ! -f "$BUILD/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DSIMS_FUZZ=ON -DSIMS_BUILD_TESTS=OFF >/dev/null
fi
# SIMS_FUZZ_SKIP_BUILD=1 runs the binary as built (several fuzzers in parallel, one build).
[ -n "${SIMS_FUZZ_SKIP_BUILD:-}" ] || cmake --build "$BUILD" -j "${SIMS_JOBS:-2}" --target "fuzz_$NAME"

# Seeds: the project's own fixtures for this loader, copied once into the working corpus.
CORPUS="$BUILD/corpus/$NAME" SEEDS="$BUILD/seeds/$NAME" ART="$BUILD/artifacts/$NAME"
mkdir -p "$CORPUS" "$ART"
rm -rf "$SEEDS" && mkdir -p "$SEEDS"
seed() { for f in "$@"; do [ -f "$f" ] && cp "$f" "$SEEDS/$(echo "${f#"$ROOT"/}" | tr '/' '_')"; done; true; }
T="$ROOT/tests/testdata"
case "$NAME" in
  bvh)
    seed "$T"/motion/*.bvh
    # The CMU skeleton with its first 3 frames (the full clips are megabytes).
    for f in /usr/share/assimp/models/BVH/*.bvh; do
      [ -f "$f" ] && awk '/^Frames:/{print "Frames: 3"; next} {print} /^Frame Time:/{n=NR} n && NR>n+2{exit}' \
        "$f" >"$SEEDS/cmu_$(basename "$f")"
    done ;;
  script) seed "$ROOT"/assets/stories/*.json $(find "$ROOT/assets/scripts" -name '*.json' | sort | head -40) ;;
  plan) seed "$T"/fuzz/seeds/plan/*.json ;;
  scene_plan) seed "$T"/scene/sceneplan.json ;;
  front3d) seed "$T"/scene/front3d/3D-FRONT/house.json ;;
  mesh_obj) seed $(find "$T/scene" -name '*.obj' | sort) ;;
  mesh_ply) seed $(find "$T/scene" -name '*.ply' | sort) ;;
  config) seed $(find "$ROOT/configs" -name '*.json' -size -64k | sort) ;;
  # The harness holds valid snapshots of its environments; the seeds pick each environment
  # (byte 0) in each mode (byte 1: raw, patch at a 4-byte offset, cut).
  env_state)
    for e in 0 1 2 3 4 5; do for m in 0 1 2; do
      printf "\\x0$e\\x0$m\\x10\\x00\\x00\\x00\\xff\\xff" >"$SEEDS/env${e}_mode${m}"
    done; done ;;
  checkpoint) seed "$ROOT"/assets/policies/*/policy.pt ;;
esac
# Earlier regressions stay in the corpus.
[ -d "$T/fuzz/$NAME" ] && cp "$T/fuzz/$NAME"/* "$SEEDS/" 2>/dev/null || true

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$ROOT/cmake/lsan.supp}"
export OMP_NUM_THREADS=1
cd "$BUILD"
set +e
"$BUILD/fuzz/fuzz_$NAME" "$CORPUS" "$SEEDS" -max_total_time="$SECONDS_TO_RUN" \
  -timeout="${SIMS_FUZZ_TIMEOUT:-20}" -rss_limit_mb="${SIMS_FUZZ_RSS_MB:-2048}" \
  -artifact_prefix="$ART/" -print_final_stats=1 2>&1 | tee "$BUILD/fuzz_$NAME.log" | grep -v '^#[0-9]'
code=${PIPESTATUS[0]}
set -e
if [ "$code" -ne 0 ]; then
  echo "[fuzz] $NAME: FAILED (exit $code); input(s) in $ART/, log in $BUILD/fuzz_$NAME.log" >&2
  exit 1
fi
echo "[fuzz] $NAME: no crash, hang or leak in $SECONDS_TO_RUN s"
