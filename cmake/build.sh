#!/usr/bin/env bash
# Configures and builds SIMS-C++ into build/ (Release, Ninja, ccache), then prepares the
# data the apps and tests use (converted npm vocabularies, synthetic motion clips) when the
# corresponding tools exist. Extra arguments go to the CMake configure step.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${SIMS_BUILD_DIR:-$ROOT/build}"
JOBS="${SIMS_JOBS:-2}"
cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$BUILD" -j "$JOBS"
# Setup-time data conversion (idempotent, skipped when already done).
if [ -x "$BUILD/bin/prepare_assets" ]; then "$BUILD/bin/prepare_assets"; fi
if [ -x "$BUILD/bin/make_synthetic_motions" ]; then "$BUILD/bin/make_synthetic_motions"; fi
