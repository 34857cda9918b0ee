#!/bin/sh
# A protocol mistake for the count check's tests: runs the program given with its arguments, and
# once its input is closed writes one line more, if it was asked any consumer request ("kind").
# Every answer it gave is right; only the count of lines is wrong.
asked=$(mktemp) || exit 3
trap 'rm -f "$asked"' EXIT
tee "$asked" | "$@"
if grep -q '"kind"' "$asked"; then
  echo '{"status": "ok"}'
fi
