#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled default scene:
# `oblique check examples/scenes/lake.json` (a camera over a lake, its reflection and refraction
# passes), with its pictures in build/demo-picture/ (the view across the water first) and the
# scene in 3D (build/demo-picture/scene.html, one file to open in a browser). Another scene:
# bash scripts/demo.sh examples/scenes/hall_of_mirrors.json
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release > /dev/null
cmake --build --preset release --target oblique > /dev/null
# The table, then the paths of the pictures (a side and a top view of the scene and its passes)
# and of the page (the scene in 3D, the check beside it).
./build/release/cli/oblique check "${1:-examples/scenes/lake.json}" --plot build/demo-picture
