#!/usr/bin/env bash
# Installs every Debian package oblique needs, skipping what is already present.
# Usage: bash scripts/setup.sh [--fuzz]   (--fuzz adds clang-14 and its sanitizer runtimes)
set -euo pipefail

packages=(cmake g++ make pkgconf libeigen3-dev nlohmann-json3-dev libcli11-dev libgtest-dev
          libgmock-dev librapidcheck-dev libgmp-dev libbenchmark-dev gnuplot-nox time
          libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri glslang-tools
          spirv-cross libpng-dev chromium)
if [[ "${1:-}" == "--fuzz" ]]; then
  packages+=(clang-14 libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
