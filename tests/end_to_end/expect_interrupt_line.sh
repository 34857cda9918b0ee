#!/bin/sh
# expect_interrupt_line.sh OBLIQUE DIR IMPL [ARG...]: runs oblique verify on the correct IMPL (with
# ARGs) as a terminal's foreground command would, sends it SIGINT (a Ctrl-C) once it has judged
# cases, and requires it to die of it (exit 130) after one line that says how many were judged,
# the seed, and the command that repeats the run with that seed.
oblique=$1
dir=$2
impl=$3
shift 3
rm -rf "$dir"
mkdir -p "$dir"
env --default-signal=INT "$oblique" verify --impl "$impl" --time-limit 60 \
  --report-dir "$dir/reports" "$@" > "$dir/verify.log" 2>&1 &
verify=$!
# Interrupted once it has shown progress (a progress line comes every few seconds).
tries=0
until grep -q "oblique verify: [0-9]" "$dir/verify.log"; do
  tries=$((tries + 1))
  if [ "$tries" -gt 300 ]; then
    echo "expect_interrupt_line: no progress line in 30 s"
    kill "$verify"
    exit 1
  fi
  sleep 0.1
done
kill -s INT "$verify"
wait "$verify"
status=$?
cat "$dir/verify.log"
if [ "$status" != 130 ]; then
  echo "expect_interrupt_line: oblique verify exited with $status after SIGINT, expected 130"
  exit 1
fi
line=$(grep "interrupted after" "$dir/verify.log")
if [ -z "$line" ]; then
  echo "expect_interrupt_line: no 'interrupted after' line"
  exit 1
fi
judged=$(echo "$line" | sed -n 's/.*interrupted after \([0-9]*\) .*/\1/p')
seed=$(echo "$line" | sed -n 's/.*(seed \([0-9]*\)).*/\1/p')
if [ -z "$judged" ] || [ "$judged" -eq 0 ]; then
  echo "expect_interrupt_line: the line counts no judged case: $line"
  exit 1
fi
if [ -z "$seed" ] || ! echo "$line" | grep -q "to repeat it: .* verify .*--seed $seed"; then
  echo "expect_interrupt_line: the line lacks the seed or the command with it: $line"
  exit 1
fi
echo "SIGINT after $judged judged, seed $seed"
