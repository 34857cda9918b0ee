#!/bin/sh
# edited_consumer_report.sh OBLIQUE DIR PROGRAM: a consumer finding's report, edited so that its
# case has no oblique matrix (the plane made all zeros), then replayed: nothing can be judged, so
# the replay must say so and exit 2 (it printed "the round holds (none judged)" and exited 0).
oblique=$1
dir=$2
program=$3
rm -rf "$dir"
mkdir -p "$dir"
"$oblique" verify --quiet --seed 7 --consumers culling_planes --convention zero_one \
  --impl "$program --wrong gl_planes_on_any_matrix" --report-dir "$dir" > "$dir/run.log" 2>&1
status=$?
if [ "$status" != 1 ]; then
  cat "$dir/run.log"
  echo "edited_consumer_report: the wrong program's run exited with $status, expected 1"
  exit 1
fi
report=$(ls "$dir"/verify-consumer-*.json | head -n 1)
sed -E 's/"plane": *\[[^]]*\]/"plane": [0, 0, 0, 0]/' "$report" > "$dir/edited.json"
if cmp -s "$report" "$dir/edited.json"; then
  echo "edited_consumer_report: $report has no \"plane\" to edit"
  exit 1
fi
"$oblique" verify --replay "$dir/edited.json" --impl "$program" > "$dir/replay.log" 2>&1
status=$?
cat "$dir/replay.log"
if [ "$status" != 2 ]; then
  echo "edited_consumer_report: the edited report's replay exited with $status, expected 2"
  exit 1
fi
if ! grep -q "judged nothing" "$dir/replay.log"; then
  echo "edited_consumer_report: the replay does not say that nothing was judged"
  exit 1
fi
echo "edited_consumer_report: exit 2, nothing judged said"
