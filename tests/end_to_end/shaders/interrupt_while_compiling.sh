#!/bin/sh
# interrupt_while_compiling.sh COMMAND [ARG...]: SIGTERM to COMMAND (verify, check or a user's test
# binary) while glslang preprocesses a macro bomb for it. It must die of the signal (exit 143), say
# what it stopped (the interrupt line: "interrupted while preprocessing FILE"), and leave no glslang
# running (it once exited 143 saying nothing, glslangValidator still spinning) nor any of its files.
log=$(mktemp)
TMPDIR=$(mktemp -d)  # glslang's files go here: nothing may be left in it
export TMPDIR
trap 'rm -f "$log"; rm -rf "$TMPDIR"' EXIT
"$@" > "$log" 2>&1 &
run=$!
tool=""
tries=0
while [ -z "$tool" ]; do
  tries=$((tries + 1))
  if [ "$tries" -gt 300 ] || ! kill -0 "$run" 2>/dev/null; then
    cat "$log"
    echo "interrupt_while_compiling: glslang never ran"
    kill "$run" 2>/dev/null
    exit 1
  fi
  tool=$(pgrep -P "$run" -f glslangValidator | head -n 1)
  [ -n "$tool" ] || sleep 0.05
done
sleep 0.3
kill -s TERM "$run"
wait "$run"
status=$?
cat "$log"
sleep 0.2
state=$(ps -o stat= -p "$tool" 2>/dev/null)
if [ -n "$state" ] && [ "${state#Z}" = "$state" ]; then
  kill -9 "$tool"
  echo "interrupt_while_compiling: glslang ($tool) outlived the interrupted run"
  exit 1
fi
if [ "$status" != 143 ]; then
  echo "interrupt_while_compiling: exit $status after SIGTERM, expected 143"
  exit 1
fi
if ! grep -Eq "interrupted while (preprocessing|compiling) .*macro_bomb.glsl .*; nothing was judged" "$log"; then
  echo "interrupt_while_compiling: no interrupt line naming the shader"
  exit 1
fi
if [ -n "$(ls -A "$TMPDIR")" ]; then
  echo "interrupt_while_compiling: left in TMPDIR: $(ls -A "$TMPDIR")"
  exit 1
fi
echo "interrupt_while_compiling: exit 143, said, glslang ended, nothing left behind"
