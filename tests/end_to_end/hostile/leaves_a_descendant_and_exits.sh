#!/bin/sh
# A fuzz target that fails at once (exit 1) but leaves a descendant holding its output for a
# minute: `oblique fuzz-report` must take the exit, not wait for the descendant.
setsid sleep 60 &
echo $! >> "$FUZZ_PIDS"
echo "crashed on $1"
exit 1
