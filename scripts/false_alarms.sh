#!/usr/bin/env bash
# The false-alarm campaign: correct implementations, run for a long time under every contract
# they claim, must give no finding; every bundled buggy example must still be caught.
#
#   bash scripts/false_alarms.sh [--minutes M] [--jobs J] [--seed S] [--no-build]
#
# Each run below takes M minutes (default 10) of one job; J (default: the number of cores) run
# at a time, so the whole takes about 14 M / J minutes, then the buggy examples (at most 7 min).
# S (default: from the clock) is the first seed, each run gets its own. The runs:
#   verify: the bundled `correct` (double and float, any refusal) and `engine_no_statuses` (double
#           and float, examples/engine_contract.json: answers only, unit planes), every
#           convention and family;
#   testing: the float engine of false_alarms/ through oblique::testing (every family and place,
#           each convention, answers only), RC_PARAMS max_success per property; and, a run of
#           its own, its [0, 1] variant that forms GL's row and converts it (engines ported from
#           OpenGL);
#   fuzz driver: the same engine through oblique::fuzzing, on mutated fuzz_oblique corpus inputs;
#   consumers: the right code around the matrix (examples/consumers) through
#           oblique::testing::check_consumers, float and double, every family and convention;
#   consumers over the protocol: the same functions as a program (consumers_program) under
#           `oblique verify --consumers all`, double and float, every family and convention; and
#           an engine whose mirror pass is a proper camera (the flip in the projection), declared
#           with --mirror-design proper_camera;
#   shaders: the bundled right depth shaders (examples/shaders: GLSL, HLSL, and GLSL inverting
#           in the shader) under `oblique verify --shader` on llvmpipe, every family and convention.
# Then each buggy example under verify (must be caught: exit 1), with its time to the finding, and
# each wrong consumer (must be caught by its property), in-process and over the protocol, and each
# wrong shader (GLSL and HLSL) under verify --shader.
# Logs and a summary go to a new folder build/false-alarms/<UTC time>/ (nothing is overwritten);
# the script exits 1 on any false alarm or missed bug, 2 when a run could not be made.
set -euo pipefail
cd "$(dirname "$0")/.."

minutes=10
jobs=$(nproc)
seed=$(date +%s)
build=1
while (($#)); do
  case "$1" in
    --minutes) minutes="${2:-}"; shift $(($# > 1 ? 2 : 1)) ;;
    --seed) seed="${2:-}"; shift $(($# > 1 ? 2 : 1)) ;;
    --jobs) jobs="${2:-}"; shift $(($# > 1 ? 2 : 1)) ;;
    --no-build) build=0; shift ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    *) echo "false_alarms.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$minutes" =~ ^[0-9]+$ && "$minutes" -gt 0 ]] || { echo "false_alarms.sh: --minutes takes a positive integer" >&2; exit 2; }
[[ "$jobs" =~ ^[0-9]+$ && "$jobs" -gt 0 ]] || { echo "false_alarms.sh: --jobs takes a positive integer" >&2; exit 2; }
[[ "$seed" =~ ^[0-9]+$ ]] || { echo "false_alarms.sh: --seed takes a non-negative integer" >&2; exit 2; }

if ((build)); then
  bash scripts/setup.sh
  cmake --preset release > /dev/null
  cmake --build --preset release --target oblique example_correct example_engine_no_statuses \
    example_camera_space_signs example_zero_one_factor_on_gl example_no_camera_guard \
    example_sign_by_division example_ignores_shift example_two_bugs example_ignores_m11_sign \
    float_engine_property_test float_engine_fuzz_replay example_consumers_right \
    example_consumers_wrong example_consumers_program > /dev/null
fi
bin=build/release
oblique=$bin/cli/oblique
ex=$bin/examples
for f in "$oblique" "$ex/example_correct" "$ex/example_engine_no_statuses" \
         "$bin/false_alarms/float_engine_property_test" "$bin/false_alarms/float_engine_fuzz_replay" \
         "$ex/example_consumers_right" "$ex/example_consumers_wrong" \
         "$ex/example_consumers_program"; do
  [[ -x "$f" ]] || { echo "false_alarms.sh: $f is not built (run without --no-build)" >&2; exit 2; }
done

out=build/false-alarms/$(date -u +%Y%m%dT%H%M%SZ)
if [[ -e "$out" ]]; then echo "false_alarms.sh: $out exists; not overwriting it" >&2; exit 2; fi
mkdir -p "$out" || { echo "false_alarms.sh: cannot create $out" >&2; exit 2; }
summary="$out/summary.md"
: > "$summary" || { echo "false_alarms.sh: cannot write $summary" >&2; exit 2; }
say() { echo "$*" | tee -a "$summary"; }

# name | kind | implementation | arguments
runs=(
  "correct, double, any refusal|verify|$ex/example_correct|--convention all"
  "correct, float, any refusal|verify|$ex/example_correct --float|--precision float --convention all"
  "engine_no_statuses, double, contract file|verify|$ex/example_engine_no_statuses|--contract examples/engine_contract.json"
  "engine_no_statuses, float, contract file|verify|$ex/example_engine_no_statuses --float|--precision float --contract examples/engine_contract.json"
  "float engine, oblique::testing|testing||FloatEngine.glHasEveryProperty:FloatEngine.zeroOneHasEveryProperty:FloatEngine.reversedZHasEveryProperty"
  "float engine making [0, 1] through GL's row, oblique::testing|testing||FloatEngine.zeroOneThroughGlHasEveryProperty"
  "float engine, fuzz driver|fuzzing||"
  "right consumers, oblique::testing|consumers||"
  "right consumers, verify, double|consumers_verify|$ex/example_consumers_program|--convention all"
  "right consumers, verify, float|consumers_verify|$ex/example_consumers_program --float|--precision float --convention all"
  "proper-camera mirror engine, verify, double|consumers_verify|$ex/example_consumers_program --wrong mirror_by_reflected_look_at|--convention all --mirror-design proper_camera"
  "right shader, GLSL, verify --shader|shader_verify|examples/shaders/depth_right.glsl|--consumers view_position,linear_depth --convention all"
  "right shader, HLSL, verify --shader|shader_verify|examples/shaders/depth_right.hlsl|--consumers view_position,linear_depth --convention all"
  "right shader, GLSL inverse() in the shader, verify --shader|shader_verify|examples/shaders/depth_right_inverse_in_shader.glsl|--consumers view_position --convention all"
)
secs=$((minutes * 60))

# One run, in the background: its log, and its figures in run<n>.figures (judged, left out, rc).
run_one() {
  # A figure's grep that finds nothing (no line left out, a finding) is not an error here.
  set +e +o pipefail
  local n=$1 kind=$2 impl=$3 args=$4 s=$5
  local log="$out/run$n.log" rc=0 judged=0 left=0
  case "$kind" in
    verify)
      # shellcheck disable=SC2086
      "$oblique" verify --impl "$impl" $args --seed "$s" --time-limit "$secs" \
        --report-dir "$out/reports$n" > "$log" 2>&1 || rc=$?
      judged=$(sed -n 's/^oblique verify: \([0-9]*\) cases, no violation.*/\1/p' "$log" | tail -1)
      left=$(sed -n 's/^  left out by the contract: //p' "$log" | grep -o '[0-9]* drawn' |
             awk '{s += $1} END {print s + 0}')
      ;;
    testing)
      # RapidCheck runs each property to max_success; the six properties of one convention's test
      # draw the same cases (one seed), so a case counts once, by its near_is_clip_plane run. About
      # 3,000 cases per second per job (all six properties) set max_success from the time, shared
      # by the tests the filter (`args`) selects.
      local tests
      tests=$("$bin/false_alarms/float_engine_property_test" --gtest_list_tests --gtest_filter="$args" |
              grep -c '^  ')
      RC_PARAMS="max_success=$((secs * 3000 / (tests > 0 ? tests : 1))) seed=$s" \
        OBLIQUE_REPORT_DIR="$out/reports$n" \
        "$bin/false_alarms/float_engine_property_test" --gtest_filter="$args" > "$log" 2>&1 || rc=$?
      # "passed N" counts the cases left out too, which its line names in parentheses ("(left
      # out: why N, why N)"): judged is the rest.
      local passed
      passed=$(grep -o '^near_is_clip_plane: OK, passed [0-9]* tests' "$log" |
               awk '{s += $4} END {print s + 0}')
      left=$(sed -n 's/^near_is_clip_plane: OK, passed [0-9]* tests (left out: \(.*\))$/\1/p' "$log" |
               grep -o '[0-9][0-9]*\(,\|$\)' | tr -d ',' | awk '{s += $1} END {print s + 0}')
      judged=$((passed - left))
      ;;
    fuzzing)
      # Inputs for the time, at about 60,000 per second per job (each decoded for the three
      # conventions' functions; those without the perspective shape are not given to them).
      "$bin/false_alarms/float_engine_fuzz_replay" --random "$((secs * 60000))" --seed "$s" \
        fuzz/corpus/fuzz_oblique > "$log" 2>&1 || rc=$?
      judged=$(sed -n 's/^oblique: \([0-9]*\) inputs judged.*/\1/p' "$log" | tail -1)
      left=$(sed -n 's/^oblique: [0-9]* inputs judged//p' "$log" | grep -o '[0-9]* left out' |
             grep -o '[0-9]*' | awk '{s += $1} END {print s + 0}')
      ;;
    consumers)
      # Nine properties, each its own cases, in float then double. RapidCheck stops at a count,
      # not a time, and the cases' cost varies by an order between properties and precisions, so
      # the run is rounds at successive seeds until the time is spent: each round's max_success
      # is scaled from the last round's pace to take about a minute, never below 300 (a round
      # must draw every family of every property to pass the coverage gate: a round of 28 cases
      # failed it), and the first finding ends it. No round starts in the last 20 s.
      local chunk=300 round=0 began=$SECONDS took
      : > "$log"
      while ((rc == 0 && SECONDS - began < secs - 20)); do
        took=$SECONDS
        echo "# round $round: max_success=$chunk seed=$((s + 1000 * round))" >> "$log"
        RC_PARAMS="max_success=$chunk seed=$((s + 1000 * round))" \
          OBLIQUE_REPORT_DIR="$out/reports$n" \
          "$ex/example_consumers_right" --gtest_filter='RightConsumers.*' >> "$log" 2>&1 || rc=$?
        took=$((SECONDS - took))
        chunk=$((chunk * 60 / (took > 0 ? took : 1)))
        ((chunk < 300)) && chunk=300
        round=$((round + 1))
      done
      # As above: "passed N" less what each line says it left out.
      local passed
      passed=$(grep -o '^[a-z_]*: OK, passed [0-9]* tests' "$log" | awk '{s += $4} END {print s + 0}')
      left=$(sed -n 's/^[a-z_]*: OK, passed [0-9]* tests (left out: \(.*\))$/\1/p' "$log" |
               grep -o '[0-9][0-9]*\(,\|$\)' | tr -d ',' | awk '{s += $1} END {print s + 0}')
      judged=$((passed - left))
      ;;
    consumers_verify|shader_verify)
      # shellcheck disable=SC2086
      if [[ "$kind" == shader_verify ]]; then
        "$oblique" verify --shader "$impl" $args --seed "$s" --time-limit "$secs" \
          --quiet --report-dir "$out/reports$n" > "$log" 2>&1 || rc=$?
      else
        "$oblique" verify --consumers all --impl "$impl" $args --seed "$s" --time-limit "$secs" \
          --quiet --report-dir "$out/reports$n" > "$log" 2>&1 || rc=$?
      fi
      judged=$(sed -n 's/^oblique verify: no violation in \([0-9]*\) answers judged.*/\1/p' "$log")
      left=$(sed -n 's/^  left out: //p' "$log" | grep -o '[0-9][0-9]*\(,\|$\)' | tr -d ',' |
             awk '{s += $1} END {print s + 0}')
      ;;
  esac
  echo "${judged:-0} ${left:-0} $rc" > "$out/run$n.figures"
}

# Ctrl-C (or SIGTERM): the runs under way are stopped; what they wrote stays in $out.
kill_tree() {
  local child
  for child in $(pgrep -P "$1"); do kill_tree "$child"; done
  kill "$1" 2> /dev/null || true
}
stop() {
  trap - INT TERM
  for job in $(jobs -p); do kill_tree "$job"; done
  wait
  echo "false_alarms.sh: interrupted; the logs so far are in $out" >&2
  exit 130
}
trap stop INT TERM

say "# False-alarm campaign $(date -u +%Y-%m-%dT%H:%M:%SZ)"
say ""
say "$minutes min per run, $jobs at a time, first seed $seed, logs in $out."
say ""
n=0
for r in "${runs[@]}"; do
  IFS='|' read -r name kind impl args <<< "$r"
  n=$((n + 1))
  while (($(jobs -rp | wc -l) >= jobs)); do wait -n || true; done
  echo "started: $name (seed $((seed + n)))" >&2
  run_one "$n" "$kind" "$impl" "$args" "$((seed + n))" &
done
wait
say "| run | seed | judged cases | left out | findings |"
say "|---|---|---|---|---|"
total=0
failures=0
n=0
for r in "${runs[@]}"; do
  IFS='|' read -r name kind impl args <<< "$r"
  n=$((n + 1))
  read -r judged left rc < "$out/run$n.figures" || { judged=0; left=0; rc=2; }
  findings=0
  if ((rc != 0)); then
    findings="exit $rc: see run$n.log"
    failures=$((failures + 1))
  fi
  total=$((total + judged))
  say "| $name | $((seed + n)) | $judged | $left | $findings |"
done
say ""
say "Judged in all: $total cases, $failures runs with findings."
say ""
say "Buggy examples (verify, default contract, 60 s each): each must be caught."
say ""
say "| example | caught | seconds (with shrinking) | finding |"
say "|---|---|---|---|"
missed=0
for bug in camera_space_signs zero_one_factor_on_gl no_camera_guard sign_by_division two_bugs \
           ignores_m11_sign; do
  log="$out/bug_$bug.log"
  start=$(date +%s.%N)
  rc=0
  "$oblique" verify --impl "$ex/example_$bug" --seed "$seed" --time-limit 60 \
    --report-dir "$out/bug_reports_$bug" > "$log" 2>&1 || rc=$?
  elapsed=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.1f", b - a}')
  kind=$(sed -n 's/^oblique verify: \([a-z_0-9]*\) violated after \([0-9]*\) cases.*/\1 after \2 cases/p' "$log" | head -1)
  if ((rc == 1)); then
    say "| $bug | yes | $elapsed | ${kind:-see log} |"
  else
    say "| $bug | NO (exit $rc) | $elapsed | |"
    missed=$((missed + 1))
  fi
done
# ignores_shift shows on the stereo_shift family only.
log="$out/bug_ignores_shift.log"
rc=0
"$oblique" verify --impl "$ex/example_ignores_shift" --families stereo_shift --seed "$seed" \
  --time-limit 60 --report-dir "$out/bug_reports_ignores_shift" > "$log" 2>&1 || rc=$?
kind=$(sed -n 's/^oblique verify: \([a-z_0-9]*\) violated after \([0-9]*\) cases.*/\1 after \2 cases/p' "$log" | head -1)
if ((rc == 1)); then say "| ignores_shift (stereo_shift) | yes | | ${kind:-see log} |"; else
  say "| ignores_shift (stereo_shift) | NO (exit $rc) | | |"; missed=$((missed + 1)); fi
say ""
say "Wrong consumers (oblique::testing, seed $seed): each must be caught by its property."
say ""
say "| test | caught by | seconds |"
say "|---|---|---|"
for pair in reconstructsWithOriginal:view_position linearisesWithNearFar:linear_depth \
            glPlanesOnAnyMatrix:culling_near_is_c planesOfTranspose:culling_keeps_visible \
            planeWithoutTranslation:plane_on_surface planeFlippedForMirrors:plane_kept_side \
            mirrorByReflectedLookAt:mirror_view portalWithoutTurn:portal_view \
            cornersOfObliqueMatrix:corners_contain_kept; do
  test=${pair%%:*}
  property=${pair#*:}
  log="$out/wrong_$test.log"
  start=$(date +%s.%N)
  rc=0
  RC_PARAMS="seed=$seed" OBLIQUE_REPORT_DIR="$out/wrong_reports_$test" \
    "$ex/example_consumers_wrong" --gtest_filter="WrongConsumers.$test" > "$log" 2>&1 || rc=$?
  elapsed=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.2f", b - a}')
  if ((rc != 0)) && grep -q "violates $property violated" "$log"; then
    say "| $test | $property | $elapsed |"
  else
    say "| $test | NOT CAUGHT by $property (exit $rc) | $elapsed |"
    missed=$((missed + 1))
  fi
done
say ""
say "Wrong consumers over the protocol (verify --consumers, seed $seed): each must be caught."
say ""
say "| mistake | caught by | seconds |"
say "|---|---|---|"
for triple in reconstructs_with_original:view_position:view_position \
              linearises_with_near_far:linear_depth:linear_depth \
              gl_planes_on_any_matrix:culling_planes:culling_near_is_c \
              planes_of_transpose:culling_planes:culling_ \
              plane_without_translation:camera_plane:plane_on_surface \
              plane_flipped_for_mirrors:camera_plane:plane_kept_side \
              mirror_by_reflected_look_at:mirror_view:mirror_view \
              portal_without_turn:portal_view:portal_view \
              corners_of_oblique_matrix:corners:corners_contain_kept; do
  IFS=':' read -r mistake kind property <<< "$triple"
  log="$out/wrong_verify_$mistake.log"
  start=$(date +%s.%N)
  rc=0
  "$oblique" verify --consumers "$kind" --impl "$ex/example_consumers_program --wrong $mistake" \
    --convention all --seed "$seed" --time-limit 60 --quiet \
    --report-dir "$out/wrong_verify_reports_$mistake" > "$log" 2>&1 || rc=$?
  elapsed=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.2f", b - a}')
  caught=$(sed -n 's/^oblique verify: violated: \([a-z_]*\) violated.*/\1/p' "$log" | head -1)
  if ((rc == 1)) && [[ "$caught" == "$property"* ]]; then
    say "| $mistake | $caught | $elapsed |"
  else
    say "| $mistake | NOT CAUGHT by $property (exit $rc) | $elapsed |"
    missed=$((missed + 1))
  fi
done
say ""
say "Wrong shaders (verify --shader, seed $seed): each must be caught and named."
say ""
say "| shader | caught by | likely cause | seconds |"
say "|---|---|---|---|"
for quad in camera_matrix_view_position:view_position:reconstructs_with_original \
            zparams_linear_depth:linear_depth:linearises_with_near_far \
            opengl_ndc_view_position:view_position:ndc_depth_of_other_convention \
            reversed_as_forward_view_position:view_position:reads_reversed_as_forward; do
  IFS=':' read -r function kind cause <<< "$quad"
  for language in glsl hlsl; do
    log="$out/wrong_shader_${language}_$function.log"
    start=$(date +%s.%N)
    rc=0
    "$oblique" verify --consumers "$kind" --shader "examples/shaders/depth_wrong.$language:$function" \
      --convention all --seed "$seed" --time-limit 60 --quiet \
      --report-dir "$out/wrong_shader_reports_${language}_$function" > "$log" 2>&1 || rc=$?
    elapsed=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.2f", b - a}')
    caught=$(sed -n 's/^oblique verify: violated: \([a-z_]*\) violated.*/\1/p' "$log" | head -1)
    named=$(grep -o "likely cause: $cause" "$log" | head -1)
    if ((rc == 1)) && [[ "$caught" == "$kind" && -n "$named" ]]; then
      say "| $language $function | $caught | $cause | $elapsed |"
    else
      say "| $language $function | NOT CAUGHT by $kind and named $cause (exit $rc) | - | $elapsed |"
      missed=$((missed + 1))
    fi
  done
done
say ""
say "Summary: $total judged cases, $failures false-alarm runs, $missed buggy examples missed."
if ((failures > 0 || missed > 0)); then exit 1; fi
