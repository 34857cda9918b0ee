#!/bin/sh
# slow_drawing.sh OBLIQUE IMPL DIR: the correct program under slow drawing (2048 x 2048 frames,
# every answer drawn, one thread, 5 s limit, 2 s timeout). Drawing a batch takes longer than the
# timeout and runs past the time limit; the answers the program gave meanwhile wait in the pipe.
# It must pass (they were not read: a false timeout finding after 49 s) and end near its limit.
oblique=$1
impl=$2
dir=$3
rm -rf "$dir"
start=$(date +%s)
"$oblique" verify --impl "$impl" --rasterize --raster-size 2048 --raster-every 1 --time-limit 5 \
  --timeout 2 --threads 1 --seed 3 --report-dir "$dir" > "$dir.log" 2>&1
status=$?
took=$(($(date +%s) - start))
cat "$dir.log"
if [ "$status" != 0 ]; then
  echo "slow_drawing: exit $status, expected 0 (the correct program passes)"
  exit 1
fi
if [ "$took" -gt 20 ]; then
  echo "slow_drawing: took $took s for a 5 s limit"
  exit 1
fi
echo "slow_drawing: passed in $took s"
