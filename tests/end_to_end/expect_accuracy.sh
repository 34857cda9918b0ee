#!/bin/sh
# expect_accuracy.sh OBLIQUE DIR IMPL [VERIFY ARG...]: `oblique verify --impl IMPL --accuracy DIR`
# must hold and write the profile: the implementation's row beside the core's three methods, the
# charts' scripts, and a worst answer whose replay command, pasted from accuracy.md, holds and
# measures the same error again.
oblique=$1
dir=$2
impl=$3
shift 3
rm -rf "$dir" "$dir.reports"
mkdir -p "$dir.reports"  # made here: verify then neither makes nor removes it or its parent
# Its own report folder: two of these run at once under ctest -j, and the default ./oblique-reports
# was one both probed (one run's probe removed the folder the other had just found).
out=$("$oblique" verify --impl "$impl" --accuracy "$dir" --report-dir "$dir.reports" "$@" 2>&1) || {
  printf '%s\n' "$out"
  echo "expect_accuracy.sh: the run did not hold"
  exit 1
}
printf '%s\n' "$out" | tail -n 3
printf '%s\n' "$out" | grep -Eq "^accuracy: [1-9][0-9]* answers profiled, worst [0-9.]+ bits lost: " || {
  echo "expect_accuracy.sh: no profile line"
  exit 1
}
for row in "| core closed_form |" "| core general |" "| core accurate |" "round trip over the pipe"; do
  grep -qF -- "$row" "$dir/accuracy.md" || {
    echo "expect_accuracy.sh: accuracy.md lacks \"$row\""
    exit 1
  }
done
for file in accuracy.csv accuracy.gp stiffness.gp worst-1.json; do
  [ -s "$dir/$file" ] || {
    echo "expect_accuracy.sh: no $file"
    exit 1
  }
done
# The first worst answer's replay, as the report prints it (the line after its "```sh").
replay=$(awk '/^1\. /{found=1} found && /```sh/{getline; sub(/^ +/, ""); print; exit}' "$dir/accuracy.md")
[ -n "$replay" ] || {
  echo "expect_accuracy.sh: accuracy.md has no replay command"
  exit 1
}
again=$(sh -c "$replay" 2>&1) || {
  printf '%s\n' "$again"
  echo "expect_accuracy.sh: the replay ($replay) did not hold"
  exit 1
}
printf '%s\n' "$again"
# The error measured again equals the recorded one (the first entry's ulps, to 0.1).
now=$(printf '%s\n' "$again" | sed -n 's/.*row 3 against the exact answer: \([0-9.e+]*\),.*/\1/p')
recorded=$(sed -n 's/.*"ulps": \[\([^],]*\).*/\1/p' "$dir/worst-1.json")
[ -n "$now" ] && awk -v a="$now" -v b="$recorded" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 0.05 + 1e-12 * b) }' || {
  echo "expect_accuracy.sh: the replay measured $now ulps, the profile recorded $recorded"
  exit 1
}
