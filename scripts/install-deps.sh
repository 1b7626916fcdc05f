#!/usr/bin/env bash
# Installs what the project needs on Debian 12 and skips whatever is already there.
# Usage: scripts/install-deps.sh            (everything: native, wasm, test data)
# Idempotent: a second run installs nothing and does not touch the network.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  # native toolchain and test framework
  g++ cmake ninja-build libgtest-dev
  # the wasm toolchain and the runtime its tests run in
  emscripten nodejs
  # the baker: ray tracing, image loading for `prt-bake probe`
  libembree-dev libtinygltf-dev libglm-dev libopenexr-dev libstb-dev
  # the baker's glossy matrices: ssyrk/sgemm rank-k updates (CBLAS header and library)
  libopenblas-dev
  # vertex and index order for cache and compression locality
  libmeshoptimizer-dev
  # JSON checks of glTF files that tinygltf does not make (header-only)
  nlohmann-json3-dev
  # the server: Boost.Beast/Asio (header-only), the encoders of its precompressed
  # variants (gzip, zstd, brotli), and XXH64 for its content-addressed URLs
  libboost-dev zlib1g-dev libzstd-dev libbrotli-dev libxxhash-dev
  # CC0 HDR environment maps (EXR) used by tests and the demo
  blender-data
  # the lightmap-atlas generator of `prt-bake --texels` for scenes without a valid UV atlas
  # (Smart UV Project, run headless; docs/transfer-textures.md)
  blender
  # a corpus of real glTF files, valid and malformed (glTF 1.0 among them), for loader tests
  assimp-testmodels
  # scale-out bakes: a single-node Slurm cluster (slurmctld, slurmd, sbatch) and its
  # authentication daemon, started without systemd by scripts/slurm-local.sh for the tests
  slurm-wlm munge
  # syscall traces: the atomic-write test checks the directory is flushed after the rename
  strace
  # headless browser for the web client's tests (driven by playwright-core from npm)
  chromium
  # the client's renderer on native OpenGL ES (prt-gpu-frames: GPU frame times without a
  # browser): EGL and GLES headers (GLVND), and Mesa's software driver for its tests here
  pkg-config libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
)

missing=()
# npm comes with the machine's Node.js where it has one; otherwise Debian's package.
command -v npm >/dev/null || packages+=(npm)
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# npm packages of a folder, from its lockfile; skipped while the lockfile is unchanged.
npm_ci() {
  local dir=$1 stamp=$1/node_modules/.prt-lockfile-sha256
  local want
  want=$(sha256sum "$dir/package-lock.json" | cut -d' ' -f1)
  if [[ -f $stamp && $(cat "$stamp") == "$want" ]]; then
    echo "install-deps: $dir/node_modules is up to date"
    return
  fi
  echo "install-deps: npm ci in $dir"
  (cd "$dir" && npm ci --ignore-scripts --no-audit --no-fund)
  echo "$want" > "$stamp"
}

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages already installed"
  npm_ci web
  exit 0
fi

sudo=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null; then
    sudo=(sudo)
  else
    echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2
    exit 1
  fi
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q
"${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
npm_ci web
