#!/bin/sh
# edited_raster_report.sh OBLIQUE DIR PROGRAM: a raster report whose frame is edited (a depth
# buffer it was never drawn into, a frame of 100,000 x 100,000 pixels) is refused in words, exit 2,
# before anything is drawn: it was drawn into a fixed24 buffer in silence, and at any size.
oblique=$1
dir=$2
program=$3
rm -rf "$dir"
mkdir -p "$dir"
report() {  # report BUFFER SIZE: a raster report of the identity camera and a plane in view
  cat > "$dir/edited.json" <<JSON
{"type": "raster", "convention": "gl", "buffer": $1, "size": $2, "seed": 5,
 "projection": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1.2, -2.2, 0, 0, -1, 0],
 "plane": [0, 0, -1, -3],
 "request": "{\"projection\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1.2, -2.2, 0, 0, -1, 0], \"plane\": [0, 0, -1, -3]}"}
JSON
}
expect_refused() {  # expect_refused WHAT MESSAGE
  "$oblique" verify --replay "$dir/edited.json" --impl "$program" > "$dir/replay.log" 2>&1
  status=$?
  cat "$dir/replay.log"
  if [ "$status" != 2 ] || ! grep -q "$2" "$dir/replay.log"; then
    echo "edited_raster_report: $1: exit $status, expected 2 and \"$2\""
    exit 1
  fi
}
report '"float64"' 256
expect_refused "an unknown buffer" '"buffer" is not a depth buffer (fixed24 or float32)'
report 7 256
expect_refused "a buffer that is no name" '"buffer" is not a depth buffer'
report '"fixed24"' 100000
expect_refused "a frame too large" '"size" must be a whole number of pixels within \[16, 4096\]'
report '"fixed24"' 2.5
expect_refused "a fractional frame" '"size" must be a whole number'
# The same report unedited is read: drawn (exit 0), or exit 3 where no rasterizer can judge.
report '"fixed24"' 256
"$oblique" verify --replay "$dir/edited.json" --impl "$program" > "$dir/replay.log" 2>&1
status=$?
cat "$dir/replay.log"
if [ "$status" != 0 ] && [ "$status" != 3 ]; then
  echo "edited_raster_report: the unedited report's replay exited $status, expected 0 or 3"
  exit 1
fi
echo "edited_raster_report: each edited frame refused in words, the unedited one read"
