#!/bin/sh
# fuzz_report_ends_what_it_started.sh OBLIQUE DIR: `oblique fuzz-report` on targets that hang while
# ignoring SIGTERM, or that exit at once leaving a descendant that holds their output open. Each
# report must come in about --timeout (not when the descendant lets go), and none of the targets'
# processes may outlive it.
oblique=$1
dir=$2
here=$(dirname "$0")
rm -rf "$dir"
mkdir -p "$dir/inputs"
echo x > "$dir/inputs/crash-1"
export FUZZ_PIDS="$dir/pids"
: > "$FUZZ_PIDS"
fail() {
  echo "fuzz_report_ends_what_it_started: $1"
  xargs kill -9 < "$FUZZ_PIDS" 2>/dev/null
  exit 1
}
run() {  # TARGET TIMEOUT LONGEST EXPECTED-KEY
  start=$(date +%s)
  "$oblique" fuzz-report --target "sh $here/$1" --timeout "$2" --report-dir "$dir/reports-$1" \
    "$dir/inputs" > "$dir/$1.log" 2>&1
  status=$?
  took=$(($(date +%s) - start))
  cat "$dir/$1.log"
  [ "$status" = 1 ] || fail "$1: exit $status, expected 1 (a finding)"
  [ "$took" -le "$3" ] || fail "$1: took $took s, at most $3 expected"
  grep -q "$4" "$dir/$1.log" || fail "$1: no finding '$4' in its output"
}
run hangs_and_leaves_its_output_open.sh 2 12 timeout
run leaves_a_descendant_and_exits.sh 30 10 "exit status 1"
sleep 0.2
for pid in $(cat "$FUZZ_PIDS"); do
  state=$(ps -o stat= -p "$pid" 2>/dev/null)
  if [ -n "$state" ] && [ "${state#Z}" = "$state" ]; then fail "process $pid outlived fuzz-report"; fi
done
echo "fuzz_report_ends_what_it_started: both reports in time, nothing left running"
