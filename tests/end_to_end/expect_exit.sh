#!/bin/sh
# expect_exit.sh EXIT REGEX COMMAND [ARG...]: runs COMMAND and requires its exit status to be EXIT
# and its output (standard output and error together) to match the extended regex REGEX.
expected=$1
pattern=$2
shift 2
output=$("$@" 2>&1)
status=$?
printf '%s\n' "$output"
if [ "$status" != "$expected" ]; then
  echo "expect_exit.sh: exit status $status, expected $expected"
  exit 1
fi
if ! printf '%s\n' "$output" | grep -Eq -- "$pattern"; then
  echo "expect_exit.sh: the output does not match: $pattern"
  exit 1
fi
