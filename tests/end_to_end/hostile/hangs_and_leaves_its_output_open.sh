#!/bin/sh
# A fuzz target at its worst for `oblique fuzz-report`: a descendant in a session of its own
# keeps the output open for a minute, and the target itself ignores SIGTERM and hangs. The report
# must come at --timeout, and nothing of it may be left running. $1: the input; FUZZ_PIDS names
# the file where the pids go.
setsid sleep 60 &
echo $! >> "$FUZZ_PIDS"
echo $$ >> "$FUZZ_PIDS"
trap '' TERM
sleep 60
