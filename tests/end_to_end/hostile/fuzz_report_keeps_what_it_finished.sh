#!/bin/sh
# fuzz_report_keeps_what_it_finished.sh OBLIQUE DIR: `oblique fuzz-report` over four inputs whose
# target fails at once on three and hangs on the last (the largest, run last); a Ctrl-C while it
# hangs ends the run with exit 130, one line that says how far it got, where the reports of the
# inputs it finished are and the command that goes on with the rest; those reports are written.
oblique=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir/inputs"
printf 'a' > "$dir/inputs/crash-1"
printf 'bb' > "$dir/inputs/crash-2"
printf 'ccc' > "$dir/inputs/crash-3"
printf 'hang hang hang' > "$dir/inputs/hang-4"
cat > "$dir/target.sh" <<'TARGET'
case "$1" in
  *hang*) : > "$(dirname "$1")/../hanging"; exec sleep 60 ;;
  *) echo "target: failed on $1"; exit 1 ;;
esac
TARGET
fail() {
  echo "fuzz_report_keeps_what_it_finished: $1"
  exit 1
}
env --default-signal=INT "$oblique" fuzz-report --target "sh $dir/target.sh" --timeout 60 \
  --report-dir "$dir/reports" "$dir/inputs" > "$dir/out.log" 2> "$dir/err.log" &
run=$!
tries=0
until [ -e "$dir/hanging" ]; do
  tries=$((tries + 1))
  [ "$tries" -le 300 ] || { kill "$run"; fail "the last input never ran"; }
  sleep 0.1
done
kill -s INT "$run"
wait "$run"
status=$?
cat "$dir/out.log" "$dir/err.log"
[ "$status" = 130 ] || fail "exit $status after SIGINT, expected 130"
line=$(grep "interrupted after" "$dir/err.log")
echo "$line" | grep -q "interrupted after 3 of 4 inputs; their reports: $dir/reports/fuzz-index.md; 1 not run; to go on with them: .* fuzz-report --target .*hang-4" ||
  fail "the interrupted line does not say how far it got and how to go on: $line"
grep -q "Interrupted" "$dir/reports/fuzz-index.md" || fail "the index does not say it was interrupted"
grep -q "hang-4" "$dir/reports/fuzz-index.md" || fail "the index does not name the input not run"
reports=$(ls "$dir/reports"/fuzz-*.md | grep -vc fuzz-index)
[ "$reports" -ge 1 ] || fail "no report of the inputs that ran"
echo "fuzz_report_keeps_what_it_finished: interrupted after 3 of 4, $reports report(s) kept"
