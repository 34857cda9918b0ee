#!/usr/bin/env bash
# Installs what is missing, builds the release preset and runs every test (unit, properties, fuzz
# replay, verify examples, scenes, benchmark smoke run).
# Extra arguments go to ctest, e.g.: bash scripts/test.sh -L properties
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release
cmake --build --preset release
ctest --preset release "$@"
