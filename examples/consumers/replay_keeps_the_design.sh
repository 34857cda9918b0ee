#!/bin/sh
# replay_keeps_the_design.sh OBLIQUE PROGRAM DIR: a consumer report records the mirror design the
# run declared, and its replay judges by that design. The right program's mirror (the default,
# reflected_view design) is caught under a declared proper_camera; replaying the report with no
# --mirror-design on the command line must catch it again (exit 1), not judge it by the default
# design and pass.
oblique=$1
program=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir"
"$oblique" verify --quiet --seed 7 --report-dir "$dir/reports" --consumers mirror_view \
  --cases 200 --mirror-design proper_camera --impl "$program" > "$dir/run.log" 2>&1
status=$?
cat "$dir/run.log"
if [ "$status" != 1 ]; then
  echo "replay_keeps_the_design: the run exited $status, expected 1 (caught)"
  exit 1
fi
report=$(ls "$dir"/reports/verify-consumer-mirror_view*.json 2>/dev/null | head -n 1)
if [ -z "$report" ] || ! grep -q '"mirror_design": "proper_camera"' "$report"; then
  echo "replay_keeps_the_design: no report recording the design: $report"
  exit 1
fi
"$oblique" verify --replay "$report" --impl "$program"
status=$?
if [ "$status" != 1 ]; then
  echo "replay_keeps_the_design: the replay exited $status, expected 1 (the declared design)"
  exit 1
fi
echo "replay_keeps_the_design: caught again by the recorded design"
