#!/bin/sh
# asks_for_a_gpu.sh OBLIQUE IMPL DIR: `verify --rasterize --device gpu`. Where EGL offers only
# llvmpipe, the user who asked for a GPU is told so (exit 3, "no GPU is reachable"), never given
# llvmpipe in silence; where a GPU answers, the run draws on it (exit 0, not llvmpipe).
oblique=$1
impl=$2
dir=$3
rm -rf "$dir"
output=$("$oblique" verify --impl "$impl" --rasterize --device gpu --cases 50 --seed 1 \
  --report-dir "$dir" 2>&1)
status=$?
printf '%s\n' "$output"
case "$status:$output" in
  3:*"no GPU is reachable"*) echo "asks_for_a_gpu: refused, saying why" ;;
  3:*"no EGL"*) echo "asks_for_a_gpu: no EGL here (skipped)" ;;
  0:*llvmpipe*) echo "asks_for_a_gpu: asked for a GPU, drew on llvmpipe in silence"; exit 1 ;;
  0:*) echo "asks_for_a_gpu: drew on a GPU" ;;
  *) echo "asks_for_a_gpu: exit $status, expected 3 (no GPU) or 0 (a GPU)"; exit 1 ;;
esac
