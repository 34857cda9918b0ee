#!/usr/bin/env bash
# Whether continuous fuzzing holds its pace: runs one libFuzzer target of the `fuzz` preset for
# SECONDS (default 600, loading the corpus included) on a copy of its corpus, with its dictionary
# and .options (as scripts/fuzz.sh), one process, and prints the executions per second of each
# minute after the corpus is loaded (libFuzzer's INITED) against the first minute's, and the peak
# resident memory.
#
#   bash scripts/fuzz_steadiness.sh TARGET [SECONDS]   (after: cmake --build --preset fuzz --target TARGET)
#
# The rate of a minute is the executions between libFuzzer's progress lines nearest its ends,
# over the time between them. Extra ASAN_OPTIONS in the environment apply (after the target's).
# A finding or a crash ends the run early: exit 1, the log and crash file kept in a new folder.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: fuzz_steadiness.sh TARGET [SECONDS]}
seconds=${2:-600}
binary=build/fuzz/fuzz/$target
[[ -x "$binary" ]] || { echo "fuzz_steadiness.sh: build $binary first (cmake --build --preset fuzz --target $target)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/corpus"
cp fuzz/corpus/"$target"/* "$work/corpus/" 2>/dev/null || true
source scripts/fuzz_options.sh
read_fuzz_options "$target"
start=$EPOCHREALTIME
# Each progress line stamped with the seconds since the start.
status=0
(cd "$work" && ASAN_OPTIONS="$asan_options${ASAN_OPTIONS:+:$ASAN_OPTIONS}" /usr/bin/time -f "peak_rss_kb %M" "$OLDPWD/$binary" -max_total_time="$seconds" \
    -use_value_profile=1 -dict="$OLDPWD/fuzz/$target.dict" -print_final_stats=1 \
    -artifact_prefix="$work/" ${libfuzzer_flags[@]+"${libfuzzer_flags[@]}"} corpus 2>&1) |
  while IFS= read -r line; do
    printf '%s %s\n' "$EPOCHREALTIME" "$line"
  done > "$work/log" || status=$?
if ((status != 0)); then
  # A finding (or a crash of the target) ends the run early: say so and keep what it left, never
  # a silent exit.
  kept=$(mktemp -d "${TMPDIR:-/tmp}/fuzz_steadiness.XXXXXX")
  cp -r "$work"/. "$kept"/
  echo "fuzz_steadiness.sh: $target ended with status $status before $seconds s; its log and" \
       "any crash file are kept in $kept:" >&2
  grep -v ' #[0-9]' "$kept/log" | tail -n 40 >&2
  exit 1
fi
awk -v target="$target" -v start="$start" '
  # Minutes count from the INITED line: loading the corpus is not fuzzing.
  /INITED/ && inited == "" { inited = $1 - start }
  inited != "" && / #[0-9]+/ && /exec\/s/ {
    for (i = 2; i <= NF; ++i) if ($i ~ /^#[0-9]+$/) { n = substr($i, 2) + 0; break }
    t = $1 - start - inited; times[++k] = t; runs[k] = n
  }
  /peak_rss_kb/ { peak = $NF }
  END {
    if (k < 2) { print target ": too few progress lines"; exit 1 }
    printf "%s: corpus loaded in %.0f s, then %d executions in %.0f s; peak RSS %.0f MB\n",
           target, inited, runs[k] - runs[1], times[k], peak / 1024
    first = 0
    for (m = 1; m * 60 <= times[k] + 30; ++m) {
      lo = 0; hi = 0
      for (j = 1; j <= k; ++j) { if (times[j] <= (m - 1) * 60) lo = j; if (times[j] <= m * 60) hi = j }
      if (lo == 0) lo = 1
      if (hi <= lo) continue
      rate = (runs[hi] - runs[lo]) / (times[hi] - times[lo])
      if (first == 0) first = rate
      printf "  minute %2d: %7.1f exec/s (%3.0f%% of the first minute)\n", m, rate, 100 * rate / first
    }
  }' "$work/log"
