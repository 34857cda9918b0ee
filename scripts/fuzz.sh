#!/usr/bin/env bash
# Continuous fuzzing on one machine.
#
#   bash scripts/fuzz.sh [--time SECONDS] [--jobs N] [--impl NAME] [TARGET ...]
#
# Builds the `fuzz` preset (clang-14, libFuzzer, ASan + UBSan), then for each target (default:
# every fuzz/fuzz_*.cpp) runs libFuzzer for SECONDS (default 600) with -fork=N (default: cores)
# over a working copy of fuzz/corpus/TARGET, with its dictionary and -use_value_profile=1,
# printing libFuzzer's progress lines (executions per second, coverage). Afterwards it merges
# the new inputs into fuzz/corpus/TARGET (scripts/fuzz_merge.sh: minimised with -merge=1, never
# losing what an old input covered, swapped in only when the merge succeeded), minimises each crash,
# de-duplicates crashes by their violation message, and for each new one writes a report to
# reports/fuzz/ and a regression input to fuzz/regressions/TARGET/ (which CTest replays).
# --impl NAME fuzzes another implementation (OBLIQUE_IMPL, e.g. a planted mutant) instead.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/fuzz_options.sh

seconds=600
jobs=$(nproc)
impl=""
targets=()
while (($#)); do
  case "$1" in
    --time) seconds="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --impl) impl="$2"; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) targets+=("$1"); shift ;;
  esac
done
if ((${#targets[@]} == 0)); then
  for f in fuzz/fuzz_*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi

bash scripts/setup.sh --fuzz
cmake --preset fuzz > /dev/null
cmake --build --preset fuzz --target "${targets[@]}" $(printf '%s_replay ' "${targets[@]}") > /dev/null
[[ -n "$impl" ]] && export OBLIQUE_IMPL="$impl"

work=build/fuzz/work
mkdir -p "$work" reports/fuzz
# Ctrl-C (or SIGTERM) stops the whole run with exit 130. The fuzzing itself is interrupted
# (libFuzzer exits normally on SIGINT, so the flag is what tells the script); a merge under way
# leaves the corpus as it was (scripts/fuzz_merge.sh); crashes already kept stay kept.
interrupted=0
stop() {
  echo "fuzz.sh: interrupted; the checked-in corpus is as it was before this target's merge" >&2
  exit 130
}
trap 'interrupted=1' INT TERM
merge_failed=0
for target in "${targets[@]}"; do
  binary="build/fuzz/fuzz/$target"
  corpus="$work/$target/corpus"
  crashes="$work/$target/crashes"
  rm -rf "$work/$target" && mkdir -p "$corpus" "$crashes"
  cp fuzz/corpus/"$target"/* "$corpus"/ 2>/dev/null || true
  echo "== $target: ${seconds}s, $jobs jobs${impl:+, implementation $impl}"
  before=$(ls "$corpus" | wc -l)
  # fuzz/TARGET.options (OSS-Fuzz's format: sections "[libfuzzer]", "[asan]", ... of
  # "name = value" lines): [libfuzzer] adds flags (e.g. fuzz_protocol's max_len, so long lines are
  # explored), [asan] goes to ASAN_OPTIONS after what the user set there (the user's wins).
  read_fuzz_options "$target"
  set +e
  (cd "$crashes" && ASAN_OPTIONS="$asan_options${ASAN_OPTIONS:+:$ASAN_OPTIONS}" \
      "../../../../../$binary" -fork="$jobs" -ignore_crashes=1 -max_total_time="$seconds" \
      -use_value_profile=1 -dict="../../../../../fuzz/$target.dict" -print_final_stats=1 \
      ${libfuzzer_flags[@]+"${libfuzzer_flags[@]}"} "../corpus") 2>&1 | tee "$work/$target/log" | grep -E --line-buffered "exec/s|cov:|crash|deadly|ERROR" | \
      awk 'NR % 20 == 1 || /crash|deadly|ERROR/'
  set -e
  ((interrupted)) && stop
  # Merge what was found back into the checked-in corpus (scripts/fuzz_merge.sh: replaced only
  # by a merge that succeeded and is not empty, no covering input lost). Without OBLIQUE_IMPL:
  # the merge keeps what covers the default implementations, so a run on one implementation does
  # not drop the inputs that reach the others.
  if ! env -u OBLIQUE_IMPL bash scripts/fuzz_merge.sh "$binary" "fuzz/corpus/$target" "$corpus" \
      "$work/$target/merge.log"; then
    ((interrupted)) && stop
    echo "the merge failed: fuzz/corpus/$target kept as it was; the new inputs stay in $corpus"
    merge_failed=1
  fi
  ((interrupted)) && stop
  grep -E "exec/s" "$work/$target/log" | tail -n 1 | sed 's/^/last progress: /' || true
  # Crashes: minimise, de-duplicate by message, report, keep as regression input.
  declare -A seen=()
  for crash in "$crashes"/crash-* "$crashes"/leak-* "$crashes"/timeout-*; do
    ((interrupted)) && stop
    [[ -e "$crash" ]] || continue
    minimized="$crash.min"
    "$binary" -minimize_crash=1 -runs=2000 -exact_artifact_path="$minimized" "$crash" > /dev/null 2>&1 || true
    [[ -s "$minimized" ]] || minimized="$crash"
    message=$(OBLIQUE_FUZZ_DESCRIBE=1 "build/fuzz/fuzz/${target}_replay" "$minimized" 2>&1 | \
              grep -E "violated|ERROR|runtime error" | head -n 1 || true)
    key=$(printf '%s' "$message" | sha1sum | cut -c1-12)
    [[ -n "${seen[$key]:-}" ]] && continue
    seen[$key]=1
    # Named by content, so a new input with a known message never overwrites a kept one.
    name="crash-$(sha1sum < "$minimized" | cut -c1-12)"
    cp "$minimized" "fuzz/regressions/$target/$name"
    report="reports/fuzz/$target-$name.md"
    {
      echo "# $target: ${message:-crash}"
      echo
      echo "Implementation: ${impl:-the core}. Found by \`scripts/fuzz.sh\` on $(date -u +%F)."
      echo
      echo "## Decoded input"
      echo
      echo '```'
      OBLIQUE_FUZZ_DESCRIBE=1 "build/fuzz/fuzz/${target}_replay" "$minimized" 2>&1 | grep -v "^replay" | head -n 30 || true
      echo '```'
      echo
      echo "## Replay"
      echo
      echo '```sh'
      echo "${impl:+OBLIQUE_IMPL=$impl }build/release/fuzz/${target}_replay fuzz/regressions/$target/$name"
      echo "${impl:+OBLIQUE_IMPL=$impl }build/fuzz/fuzz/$target fuzz/regressions/$target/$name"
      echo '```'
    } > "$report"
    echo "new crash: $message"
    echo "  report: $report"
    echo "  regression input: fuzz/regressions/$target/$name"
  done
  unset seen
done
if ((merge_failed)); then
  echo "fuzz.sh: a corpus merge failed (see above)" >&2
  exit 1
fi
