#!/usr/bin/env bash
# Installs what is missing, builds, and runs `oblique apply` on the bundled example requests.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release > /dev/null
cmake --build --preset release --target oblique > /dev/null
status=0
./build/release/cli/oblique apply < examples/requests.jsonl || status=$?
# Exit 1 only says some request got a non-ok status, which the example shows on purpose.
if [[ $status -gt 1 ]]; then exit "$status"; fi
