#!/bin/sh
# interrupt_while_reporting.sh OBLIQUE DIR IMPL: Ctrl-C (SIGINT) to `oblique verify` on a wrong IMPL
# after its report's name is taken (the empty verify-*.md that reserves it) and before the report
# is committed (while the picture of the fault is drawn, in the process itself). It must die of the
# interrupt (exit 130), say that it was writing the report, and leave nothing: no empty report
# taking the name (the next run wrote "-2"), no staging folder. Also: a folder or a link where a
# staging folder's old, guessable name was (.oblique-staging-PID-0) is never written through.
oblique=$1
dir=$2
impl=$3
rm -rf "$dir"
mkdir -p "$dir/reports" "$dir/elsewhere"
# The old names for every pid a run may get soon: links to a folder outside.
pid_now=$$
for p in $(seq "$pid_now" $((pid_now + 200))); do
  ln -s "$dir/elsewhere" "$dir/reports/.oblique-staging-$p-0"
done
caught=0
for try in 1 2 3 4 5 6 7 8; do
  rm -f "$dir/reports"/verify-*.md "$dir/reports"/verify-*.json
  env --default-signal=INT "$oblique" verify --impl "$impl" --seed 5 --quiet \
    --report-dir "$dir/reports" > "$dir/run.log" 2>&1 &
  run=$!
  # The reservation appears empty; the committed report is never empty.
  reserved=""
  while kill -0 "$run" 2>/dev/null; do
    for f in "$dir/reports"/verify-*.md; do
      if [ -e "$f" ] && [ ! -s "$f" ]; then reserved=$f; break 2; fi
    done
  done
  if [ -z "$reserved" ]; then
    wait "$run"
    continue
  fi
  kill -s INT "$run"
  wait "$run"
  status=$?
  if [ -s "$reserved" ]; then continue; fi  # committed before the signal landed: again
  caught=1
  break
done
cat "$dir/run.log"
if [ "$caught" != 1 ]; then
  echo "interrupt_while_reporting: never interrupted between the reservation and the commit"
  exit 1
fi
if [ "$status" != 130 ]; then
  echo "interrupt_while_reporting: exit $status after SIGINT, expected 130"
  exit 1
fi
if ! grep -q "interrupted while writing a violation's report" "$dir/run.log"; then
  echo "interrupt_while_reporting: the interrupt line does not say the report was being written"
  exit 1
fi
left=$(ls -A "$dir/reports" | grep -v '^\.oblique-staging-[0-9]*-0$')
if [ -n "$left" ]; then
  echo "interrupt_while_reporting: left behind: $left"
  exit 1
fi
if [ -n "$(ls -A "$dir/elsewhere")" ]; then
  echo "interrupt_while_reporting: written through a staging link: $(ls -A "$dir/elsewhere")"
  exit 1
fi
echo "interrupt_while_reporting: exit 130, said, nothing left behind, no link followed"
