#!/usr/bin/env bash
# The run speeds issue 65 sets targets for, measured in one run on this machine so that they
# compare as ratios (docs/accuracy-and-performance.md keeps the dated figures):
#   - verify, the matrix: requests a second against the same requests through `oblique apply`
#     over a pipe (the ceiling a verifier of that program could reach);
#   - verify --consumers all, float and double: rounds a second, on the right consumers program;
#   - verify --shader, the bundled right GLSL (view position and linear depth, every convention):
#     judged answers a second;
#   - verify --rasterize --raster-every 1: seconds per 1,000 cases.
#
#   bash scripts/speed.sh [--seconds S] [--seed N]
#
# Needs the release build (cmake --build --preset release). S (default 10) is each timed run's
# length. Prints a Markdown table and writes it, with every run's output, to a new folder
# build/speed/<UTC time>/; exits 2 when a run could not be made.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=10
seed=7
while (($#)); do
  case "$1" in
    --seconds) seconds="${2:-}"; shift $(($# > 1 ? 2 : 1)) ;;
    --seed) seed="${2:-}"; shift $(($# > 1 ? 2 : 1)) ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "speed.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$seconds" =~ ^[0-9]+$ && "$seconds" -gt 0 ]] || { echo "speed.sh: --seconds takes a positive integer" >&2; exit 2; }
[[ "$seed" =~ ^[0-9]+$ ]] || { echo "speed.sh: --seed takes a non-negative integer" >&2; exit 2; }

oblique=build/release/cli/oblique
ex=build/release/examples
for f in "$oblique" "$ex/example_correct" "$ex/example_consumers_program"; do
  [[ -x "$f" ]] || { echo "speed.sh: $f is not built (cmake --build --preset release)" >&2; exit 2; }
done
out=build/speed/$(date -u +%Y%m%dT%H%M%SZ)
if [[ -e "$out" ]]; then echo "speed.sh: $out exists; not overwriting it" >&2; exit 2; fi
mkdir -p "$out" || { echo "speed.sh: cannot create $out" >&2; exit 2; }
fail() { echo "speed.sh: $1 (its output: $2)" >&2; exit 2; }
rate() { awk -v n="$1" -v s="$2" 'BEGIN { printf "%.0f", (s > 0 ? n / s : 0) }'; }

# The matrix: verify's own figure, and the same requests (captured on their way) through apply.
cases=$((seconds * 15000))
"$oblique" verify --impl "tee $out/requests.jsonl | $oblique apply" --convention all --cases "$cases" \
  --seed "$seed" --quiet > "$out/matrix.log" 2>&1 || fail "verify of oblique apply failed" "$out/matrix.log"
verify_rate=$(sed -n 's/.* \([0-9]*\) requests per second.*/\1/p' "$out/matrix.log" | tail -1)
began=$(date +%s.%N)
"$oblique" apply < "$out/requests.jsonl" > /dev/null || true  # (refusals exit 1)
took=$(awk -v a="$began" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
apply_rate=$(rate "$(wc -l < "$out/requests.jsonl")" "$took")

# The code around the matrix, float and double: rounds over the run's own seconds.
consumers() {  # precision, program flags
  "$oblique" verify --consumers all --impl "$ex/example_consumers_program $2" --precision "$1" \
    --convention all --time-limit "$seconds" --seed "$seed" --quiet > "$out/consumers_$1.log" 2>&1 ||
    fail "verify --consumers all ($1) failed" "$out/consumers_$1.log"
  sed -n 's/.* \([0-9]*\) rounds of .*, \([0-9.]*\) s)$/\1 \2/p' "$out/consumers_$1.log" | tail -1
}
read -r rounds_f secs_f <<< "$(consumers float --float)"
read -r rounds_d secs_d <<< "$(consumers double "")"

# The bundled right GLSL shader on llvmpipe: judged answers over the run's seconds.
shader_rate=""
if "$oblique" verify --shader examples/shaders/depth_right.glsl --consumers view_position,linear_depth \
     --convention all --time-limit "$seconds" --seed "$seed" --quiet > "$out/shader.log" 2>&1; then
  read -r answers secs_s <<< "$(sed -n 's/.*no violation in \([0-9]*\) answers judged.*, \([0-9.]*\) s)$/\1 \2/p' "$out/shader.log")"
  shader_rate=$(rate "$answers" "$secs_s")
fi

# The rasterizer on every answer: 200 cases, scaled to 1,000.
raster=""
if "$oblique" verify --impl "$ex/example_correct" --rasterize --raster-every 1 --cases 200 \
     --seed "$seed" --quiet > "$out/raster.log" 2>&1; then
  raster=$(sed -n 's/.*, \([0-9.]*\) s, [0-9]* requests per second.*/\1/p' "$out/raster.log" |
           awk '{ printf "%.1f", $1 * 5 }')
fi

{
  echo "# Speeds $(date -u +%Y-%m-%dT%H:%M:%SZ), seed $seed, $seconds s runs"
  echo ""
  echo "| what | figure |"
  echo "|---|---|"
  echo "| verify, matrix (oblique apply as the program) | $verify_rate requests/s |"
  echo "| oblique apply, the same requests over a pipe | $apply_rate requests/s |"
  echo "| verify / apply | $(awk -v a="$verify_rate" -v b="$apply_rate" 'BEGIN { printf "%.0f%%", (b > 0 ? 100 * a / b : 0) }') |"
  echo "| verify --consumers all, float | $(rate "$rounds_f" "$secs_f") rounds/s |"
  echo "| verify --consumers all, double | $(rate "$rounds_d" "$secs_d") rounds/s |"
  echo "| verify --shader (right GLSL, llvmpipe) | ${shader_rate:-not run (see shader.log)} judged answers/s |"
  echo "| verify --rasterize --raster-every 1 | ${raster:-not run (see raster.log)} s per 1,000 cases |"
} | tee "$out/summary.md"
