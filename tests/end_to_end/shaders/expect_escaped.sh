#!/bin/sh
# expect_escaped.sh WAY OBLIQUE-OR-BINARY SCENE: a shader path holding terminal escapes (ESC [2J,
# which clears the screen, and a window-title sequence) named to verify, check or a user's test
# binary. The message that echoes the path must show them escaped (\x1B), never as raw bytes.
way=$1
bin=$2
scene=$3
esc=$(printf '\033')
bel=$(printf '\007')
path="/nonexistent/${esc}[2J${esc}]0;owned${bel}.glsl"
case $way in
  verify) output=$("$bin" verify --consumers view_position --shader "$path" --time-limit 1 2>&1) ;;
  check) output=$("$bin" check "$scene" --shader "$path:view_position" 2>&1) ;;
  test_macro) output=$(OBLIQUE_TRIED_SHADER="$path:view_position" "$bin" 2>&1) ;;
esac
if printf '%s' "$output" | grep -q "$esc"; then
  echo "expect_escaped: the output holds a raw ESC:"
  printf '%s\n' "$output" | od -c | head -n 20
  exit 1
fi
if ! printf '%s' "$output" | grep -qF 'cannot read the shader /nonexistent/\x1B[2J\x1B]0;owned\x07.glsl'; then
  printf '%s\n' "$output"
  echo "expect_escaped: the path is not shown escaped"
  exit 1
fi
printf '%s\n' "$output"
echo "expect_escaped: $way shows the path escaped"
