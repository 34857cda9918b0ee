#!/bin/sh
# expect_reports_keyed_by_executable.sh WRONG RIGHT DIR: two test executables with the same test
# name run into one reports folder, the failing one first: the passing one moves none of the
# failing one's report to earlier/ (with reports keyed by test alone it did).
wrong=$1
right=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir"
fail() {
  echo "expect_reports_keyed_by_executable: $1"
  ls -R "$dir"
  exit 1
}
OBLIQUE_REPORT_DIR="$dir" "$wrong" > "$dir/wrong.log" 2>&1 && fail "the wrong function passed"
report=$(ls "$dir"/*.md 2>/dev/null | head -1)
[ -n "$report" ] || fail "the failing executable wrote no report"
case "$(basename "$report")" in
  "$(basename "$wrong").SameNames.oneTestInTwoExecutables."*) ;;
  *) fail "the report $(basename "$report") is not named by its executable and test" ;;
esac
OBLIQUE_REPORT_DIR="$dir" "$right" > "$dir/right.log" 2>&1 || fail "the right function failed: $(cat "$dir/right.log")"
[ -e "$report" ] || fail "the passing executable moved the failing one's report $(basename "$report")"
[ ! -d "$dir/earlier" ] || fail "something was moved to earlier/"
echo "expect_reports_keyed_by_executable: $(basename "$report") kept beside the passing run"
