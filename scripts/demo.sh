#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled default scene:
# `oblique check examples/scenes/lake.json` (a camera over a lake, its reflection and refraction
# passes). Another scene: bash scripts/demo.sh examples/scenes/wall_mirror_reversed_z.json
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release > /dev/null
cmake --build --preset release --target oblique > /dev/null
./build/release/cli/oblique check "${1:-examples/scenes/lake.json}"
