#!/usr/bin/env bash
# The engine idioms' campaign (examples/shaders/engines/idioms.txt, docs/shaders.md): each right
# function at fresh seeds for M minutes through `oblique verify --shader` and for M minutes
# through OBLIQUE_SHADER_TEST (example_engine_idioms, RapidCheck rounds at successive seeds),
# and once through `oblique check --shader` on the bundled scene with a reconstruction consumer:
# no finding allowed. Then each wrong twin under verify at a fresh seed: it must be caught and
# named by what its answers show; the seconds to the finding (compiling included) are listed.
#
#   bash scripts/shader_idioms.sh [--minutes M] [--jobs J] [--seed S]
#
# Needs the release build (cmake --build --preset release). Logs and a summary go to a new folder
# build/shader-idioms/<UTC time>/; exits 1 on a false alarm or a missed twin, 2 when a run could
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
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "shader_idioms.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$minutes" =~ ^[0-9]+$ && "$minutes" -gt 0 ]] || { echo "shader_idioms.sh: --minutes takes a positive integer" >&2; exit 2; }
[[ "$jobs" =~ ^[0-9]+$ && "$jobs" -gt 0 ]] || { echo "shader_idioms.sh: --jobs takes a positive integer" >&2; exit 2; }
[[ "$seed" =~ ^[0-9]+$ ]] || { echo "shader_idioms.sh: --seed takes a non-negative integer" >&2; exit 2; }

oblique=build/release/cli/oblique
macro=build/release/examples/example_engine_idioms
for f in "$oblique" "$macro"; do
  [[ -x "$f" ]] || { echo "shader_idioms.sh: $f is not built (cmake --build --preset release)" >&2; exit 2; }
done
idioms=examples/shaders/engines
scene=examples/scenes/portal_room_consumers.json
out=build/shader-idioms/$(date -u +%Y%m%dT%H%M%SZ)
if [[ -e "$out" ]]; then echo "shader_idioms.sh: $out exists; not overwriting it" >&2; exit 2; fi
mkdir -p "$out" || { echo "shader_idioms.sh: cannot create $out" >&2; exit 2; }
summary="$out/summary.md"
say() { echo "$*" | tee -a "$summary"; }
secs=$((minutes * 60))

mapfile -t lines < <(grep -E '^[a-z]' "$idioms/idioms.txt")

# The flags of an idiom's claims: kind, conventions, families, the way v runs.
claims() {
  local kind=$1 conventions=$2 families=$3 v=$4 vectors=$5
  echo "--consumers $kind --precision float --convention $conventions${families:+ --families $families}${v:+ --uv-v $v}${vectors:+ --vectors $vectors}"
}

# One right idiom, one way in, in the background: its log and "judged rc" in <n>.figures.
run_right() {
  set +e +o pipefail
  local n=$1 way=$2 name=$3 file=$4 kind=$5 conventions=$6 families=$7 v=$8 vectors=$9 s=${10}
  local log="$out/$n.$way.log" rc=0 judged=0
  case "$way" in
    verify)
      # shellcheck disable=SC2046
      "$oblique" verify $(claims "$kind" "$conventions" "$families" "$v" "$vectors") --shader "$idioms/$file" \
        --seed "$s" --time-limit "$secs" --quiet --report-dir "$out/reports$n" > "$log" 2>&1 || rc=$?
      judged=$(sed -n 's/^oblique verify: no violation in \([0-9]*\) answers judged.*/\1/p' "$log")
      ;;
    macro)
      # RapidCheck stops at a count: rounds at successive seeds until the time is spent.
      local round=0 began=$SECONDS
      : > "$log"
      while ((rc == 0 && SECONDS - began < secs - 10)); do
        RC_PARAMS="max_success=2000 seed=$((s + 1000 * round))" OBLIQUE_REPORT_DIR="$out/reports$n" \
          "$macro" --gtest_filter="RightIdioms.$name" >> "$log" 2>&1 || rc=$?
        round=$((round + 1))
      done
      judged=$(grep -o '^[a-z_]*: OK, passed [0-9]* tests' "$log" | awk '{s += $4} END {print s + 0}')
      ;;
    check)
      "$oblique" check "$scene" ${v:+--uv-v "$v"} ${vectors:+--vectors "$vectors"} --shader "$idioms/$file:$kind" > "$log" 2>&1 || rc=$?
      judged=$(sed -n 's/.*reconstruction ok (\([0-9]*\) judged).*/\1/p' "$log" | awk '{s += $1} END {print s + 0}')
      ;;
  esac
  echo "${judged:-0} $rc" > "$out/$n.$way.figures"
}

say "# Engine idioms' campaign $(date -u +%Y-%m-%dT%H:%M:%SZ)"
say ""
say "$minutes min per idiom per way (verify, OBLIQUE_SHADER_TEST), $jobs at a time, first seed $seed, logs in $out."
say ""
n=0
for line in "${lines[@]}"; do
  IFS='|' read -r name file kind conventions families v vectors shows <<< "$line"
  n=$((n + 1))
  for way in verify macro check; do
    while (($(jobs -rp | wc -l) >= jobs)); do wait -n || true; done
    run_right "$n" "$way" "$name" "$file" "$kind" "$conventions" "$families" "$v" "$vectors" \
      "$((seed + n))" &
  done
done
wait
say "| idiom | verify: judged | OBLIQUE_SHADER_TEST: judged | check: judged | findings |"
say "|---|---|---|---|---|"
failures=0
n=0
for line in "${lines[@]}"; do
  IFS='|' read -r name file kind conventions families v vectors shows <<< "$line"
  n=$((n + 1))
  row="| $name"
  findings=""
  for way in verify macro check; do
    read -r judged rc < "$out/$n.$way.figures" || { judged=0; rc=2; }
    row="$row | $judged"
    if ((rc != 0)); then findings="$findings $way exit $rc (see $n.$way.log)"; fi
  done
  [[ -n "$findings" ]] && failures=$((failures + 1))
  say "$row | ${findings:-0} |"
done
say ""
say "Wrong twins (verify --shader, fresh seed): each must be caught and named."
say ""
say "| idiom | caught (the round of the finding) | seconds (compiling included) | named |"
say "|---|---|---|---|"
missed=0
n=0
for line in "${lines[@]}"; do
  IFS='|' read -r name file kind conventions families v vectors shows <<< "$line"
  n=$((n + 1))
  wrong=${file%.*}_wrong.${file##*.}
  log="$out/$n.wrong.log"
  start=$(date +%s.%N)
  rc=0
  # shellcheck disable=SC2046
  "$oblique" verify $(claims "$kind" "$conventions" "$families" "$v" "$vectors") --shader "$idioms/$wrong" \
    --seed "$((seed + 100 + n))" --time-limit 60 --report-dir "$out/wrong$n" > "$log" 2>&1 || rc=$?
  elapsed=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.1f", b - a}')
  if ((rc == 1)) && grep -Eq "likely cause: .*$shows" "$log"; then
    named=$(grep -Eo "likely cause: [a-z_]+" "$log" | head -1 | cut -d' ' -f3-)
    [[ "$named" == no ]] && named="no known mistake; what the answers show"
    round=$(grep -Eo "violated in round [0-9]+" "$log" | head -1 | grep -Eo "[0-9]+$")
    say "| $name | yes, round ${round:-?} | $elapsed | $named |"
  else
    say "| $name | NO (exit $rc, or not named: $shows) | $elapsed | |"
    missed=$((missed + 1))
  fi
done
say ""
say "False alarms: $failures idioms; wrong twins missed or unnamed: $missed."
((failures == 0 && missed == 0))
