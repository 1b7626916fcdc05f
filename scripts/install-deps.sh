#!/usr/bin/env bash
# Installs what the project needs on Debian 12 and skips whatever is already there.
# Usage: scripts/install-deps.sh            (everything: native, wasm, test data)
# Idempotent: a second run installs nothing and does not touch the network.
set -euo pipefail

packages=(
  # native toolchain and test framework
  g++ cmake ninja-build libgtest-dev
  # the wasm toolchain and the runtime its tests run in
  emscripten nodejs
  # the baker: ray tracing, image loading for `prt-bake probe`
  libembree-dev libtinygltf-dev libglm-dev libopenexr-dev libstb-dev
  # CC0 HDR environment maps (EXR) used by tests and the demo
  blender-data
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages already installed"
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
