#!/bin/sh
# concurrent_reports.sh OBLIQUE DIR IMPL: two `oblique verify` runs on the same wrong IMPL, at the
# same time, into one --report-dir. Each must keep its own report: two different names printed,
# two files there (a name picked before the pictures and renamed into place afterwards was
# printed by both, and one report replaced the other).
oblique=$1
dir=$2
impl=$3
rm -rf "$dir"
mkdir -p "$dir/reports"
for run in 1 2; do
  "$oblique" verify --impl "$impl" --seed 5 --quiet --report-dir "$dir/reports" \
    > "$dir/run$run.log" 2>&1 &
done
wait
cat "$dir/run1.log" "$dir/run2.log"
one=$(grep -o 'report: [^ ]*\.md' "$dir/run1.log" | head -n 1)
two=$(grep -o 'report: [^ ]*\.md' "$dir/run2.log" | head -n 1)
if [ -z "$one" ] || [ -z "$two" ]; then
  echo "concurrent_reports: a run printed no report"
  exit 1
fi
if [ "$one" = "$two" ]; then
  echo "concurrent_reports: both runs printed $one"
  exit 1
fi
for report in "${one#report: }" "${two#report: }"; do
  if [ ! -s "$report" ]; then
    echo "concurrent_reports: $report is missing or empty"
    exit 1
  fi
done
echo "concurrent_reports: two reports kept: ${one#report: } and ${two#report: }"
