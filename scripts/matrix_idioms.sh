#!/usr/bin/env bash
# The engine matrix idioms' campaign (examples/engine_matrices/idioms.txt, docs/engines.md): each
# right function at fresh seeds for M minutes every way in: `oblique verify` over the protocol
# (the program puts the matrix in the idiom's storage), the property test in its own storage
# (example_engine_matrices_test, RapidCheck rounds at successive seeds) and the fuzz driver on
# mutated corpus inputs (example_engine_matrices_fuzz_replay): no finding allowed. The
# Direct3D-style engine's wall mirror through `oblique check` (right: pass; its mirror-path bug:
# caught). Then each wrong twin under verify at a fresh seed: caught and named as idioms.txt says;
# the seconds to the report are listed.
#
#   bash scripts/matrix_idioms.sh [--minutes M] [--jobs J] [--seed S]
#
# Needs the release build (cmake --build --preset release). Logs and a summary go to a new folder
# build/matrix-idioms/<UTC time>/; exits 1 on a false alarm or a missed twin, 2 when a run could
# not be made.
set -euo pipefail
cd "$(dirname "$0")/.."

minutes=10
jobs=$(nproc)
seed=$(date +%s)
while (($#)); do
  case "$1" in
    --minutes) minutes="${2:-}"; shift $(($# > 1 ? 2 : 1)) ;;
    --seed) seed="${2:-}"; shift $(($# > 1 ? 2 : 1)) ;;
    --jobs) jobs="${2:-}"; shift $(($# > 1 ? 2 : 1)) ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "matrix_idioms.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$minutes" =~ ^[0-9]+$ && "$minutes" -gt 0 ]] || { echo "matrix_idioms.sh: --minutes takes a positive integer" >&2; exit 2; }
[[ "$jobs" =~ ^[0-9]+$ && "$jobs" -gt 0 ]] || { echo "matrix_idioms.sh: --jobs takes a positive integer" >&2; exit 2; }
[[ "$seed" =~ ^[0-9]+$ ]] || { echo "matrix_idioms.sh: --seed takes a non-negative integer" >&2; exit 2; }

oblique=build/release/cli/oblique
ex=build/release/examples
program=$ex/example_engine_matrices
test=$ex/example_engine_matrices_test
fuzz=$ex/example_engine_matrices_fuzz_replay
for f in "$oblique" "$program" "$test" "$fuzz"; do
  [[ -x "$f" ]] || { echo "matrix_idioms.sh: $f is not built (cmake --build --preset release)" >&2; exit 2; }
done
idioms=examples/engine_matrices/idioms.txt
scene=examples/scenes/d3d_wall_mirror.json
out=build/matrix-idioms/$(date -u +%Y%m%dT%H%M%SZ)
if [[ -e "$out" ]]; then echo "matrix_idioms.sh: $out exists; not overwriting it" >&2; exit 2; fi
mkdir -p "$out" || { echo "matrix_idioms.sh: cannot create $out" >&2; exit 2; }
summary="$out/summary.md"
say() { echo "$*" | tee -a "$summary"; }
secs=$((minutes * 60))

mapfile -t lines < <(grep -E '^[a-z]' "$idioms")

# The flags of an idiom's claims: the engine preset narrowed to its convention and families, float.
claims() {
  echo "--preset engine --precision float --convention $1 --families $2"
}

# One right idiom, one way in, in the background: its log and "judged rc" in <n>.<way>.figures.
run_right() {
  set +e +o pipefail
  local n=$1 way=$2 name=$3 convention=$4 families=$5 s=$6
  local log="$out/$n.$way.log" rc=0 judged=0
  case "$way" in
    verify)
      # shellcheck disable=SC2046
      "$oblique" verify $(claims "$convention" "$families") --impl "$program $name" \
        --seed "$s" --time-limit "$secs" \
        --quiet --report-dir "$out/reports$n" > "$log" 2>&1 || rc=$?
      judged=$(sed -n 's/^oblique verify: \([0-9]*\) cases, no violation.*/\1/p' "$log" | tail -1)
      ;;
    property)
      # RapidCheck stops at a count: rounds at successive seeds until the time is spent; a case
      # counts once, by its near_is_clip_plane run.
      local round=0 began=$SECONDS
      : > "$log"
      while ((rc == 0 && SECONDS - began < secs - 10)); do
        RC_PARAMS="max_success=20000 seed=$((s + 1000 * round))" OBLIQUE_REPORT_DIR="$out/reports$n" \
          "$test" --gtest_filter="RightMatrices.$name" >> "$log" 2>&1 || rc=$?
        round=$((round + 1))
      done
      # "passed N" counts the cases left out too (said in its parentheses): judged is the rest.
      local run left
      run=$(grep -o '^near_is_clip_plane: OK, passed [0-9]* tests' "$log" | awk '{s += $4} END {print s + 0}')
      left=$(sed -n 's/^near_is_clip_plane: OK, passed [0-9]* tests (left out: \(.*\))$/\1/p' "$log" |
             grep -o '[0-9][0-9]*\(,\|$\)' | tr -d ',' | awk '{s += $1} END {print s + 0}')
      judged=$((run - left))
      ;;
    fuzz)
      # Mutated corpus inputs in rounds of 200,000 until the time is spent.
      local round=0 began=$SECONDS
      : > "$log"
      while ((rc == 0 && SECONDS - began < secs - 10)); do
        OBLIQUE_IDIOM=$name "$fuzz" --random 200000 --seed "$((s + 1000 * round))" \
          fuzz/corpus/fuzz_oblique >> "$log" 2>&1 || rc=$?
        round=$((round + 1))
      done
      judged=$(sed -n 's/^oblique: \([0-9]*\) inputs judged.*/\1/p' "$log" | awk '{s += $1} END {print s + 0}')
      ;;
  esac
  echo "${judged:-0} $rc" > "$out/$n.$way.figures"
}

say "# Engine matrix idioms' campaign $(date -u +%Y-%m-%dT%H:%M:%SZ)"
say ""
say "$minutes min per idiom per way (verify, property test, fuzz driver), $jobs at a time, first seed $seed, logs in $out."
say ""
n=0
for line in "${lines[@]}"; do
  IFS='|' read -r name storage convention families names_twin <<< "$line"
  n=$((n + 1))
  for way in verify property fuzz; do
    while (($(jobs -rp | wc -l) >= jobs)); do wait -n || true; done
    run_right "$n" "$way" "$name" "$convention" "$families" "$((seed + n))" &
  done
done
wait
say "| idiom | storage | convention | verify: judged | property test: judged | fuzz driver: judged | findings |"
say "|---|---|---|---|---|---|---|"
failures=0
n=0
for line in "${lines[@]}"; do
  IFS='|' read -r name storage convention families names_twin <<< "$line"
  n=$((n + 1))
  row="| $name | $storage | $convention"
  findings=""
  for way in verify property fuzz; do
    read -r judged rc < "$out/$n.$way.figures" || { judged=0; rc=2; }
    row="$row | $judged"
    if ((rc != 0)); then findings="$findings $way exit $rc (see $n.$way.log)"; fi
  done
  [[ -n "$findings" ]] && failures=$((failures + 1))
  say "$row | ${findings:-0} |"
done
say ""
say "The Direct3D-style engine's wall mirror (oblique check $scene):"
say ""
say "| function | --layout | expected | exit | mirror line |"
say "|---|---|---|---|---|"
k=0
for triple in "d3d_mirror_pass|row_major|0" "d3d_mirror_pass_wrong|row_major|1" \
              "d3d_mirror_pass --as-stored|row_vectors|0" "d3d_mirror_pass_wrong --as-stored|row_vectors|1"; do
  IFS='|' read -r function layout expected <<< "$triple"
  k=$((k + 1))
  log="$out/check_$k.log"
  rc=0
  "$oblique" check "$scene" --consumers none --precision float --layout "$layout" \
    --impl "$program $function" > "$log" 2>&1 || rc=$?
  line=$(grep -E "wall mirror: " "$log" | tail -1)
  say "| $function | $layout | $expected | $rc | ${line:-see log} |"
  ((rc == expected)) || failures=$((failures + 1))
done
say ""
say "Wrong twins (verify, fresh seed): each must be caught and named."
say ""
say "| idiom | caught | seconds (shrinking and diagnosis included) | likely cause |"
say "|---|---|---|---|"
missed=0
n=0
for line in "${lines[@]}"; do
  IFS='|' read -r name storage convention families names_twin <<< "$line"
  n=$((n + 1))
  log="$out/$n.wrong.log"
  start=$(date +%s.%N)
  rc=0
  # shellcheck disable=SC2046
  "$oblique" verify $(claims "$convention" "$families") --impl "$program ${name}_wrong" \
    --seed "$((seed + 100 + n))" \
    --time-limit 60 --report-dir "$out/wrong$n" > "$log" 2>&1 || rc=$?
  elapsed=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.2f", b - a}')
  if ((rc == 1)) && grep -Eq "likely cause.*$names_twin" "$log"; then
    named=$(grep -Eo "likely cause[^:]*: [^(;]*" "$log" | head -1 | sed 's/^likely cause[^:]*: //')
    say "| $name | yes | $elapsed | $named |"
  else
    say "| $name | NO (exit $rc, or not named: $names_twin) | $elapsed | |"
    missed=$((missed + 1))
  fi
done
say ""
say "False alarms: $failures; wrong twins missed or unnamed: $missed."
((failures == 0 && missed == 0))
