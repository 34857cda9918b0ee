#!/usr/bin/env bash
# The corpus merge of scripts/fuzz.sh, on its own so CTest can run it against stub fuzzers.
#
#   bash scripts/fuzz_merge.sh FUZZER CORPUS NEW_INPUTS [LOG]
#
# Policy: the checked-in CORPUS is replaced only by a merge that succeeded and is not empty, and
# a merge never loses what an input of CORPUS covered:
#   1. FUZZER -merge=1 minimises CORPUS + NEW_INPUTS into a new directory beside CORPUS (libFuzzer
#      keeps, smallest first, every input that adds a coverage feature);
#   2. FUZZER -merge=1 then offers every old input of CORPUS to that new set again: an old input
#      with a feature the new set lacks is added back (normally none is);
#   3. only when both merges exited 0 and the new set is not empty is it swapped in, with two
#      renames while SIGINT and SIGTERM are held off; the old set is removed only after that.
# A failed, empty or interrupted merge leaves CORPUS as it was (the new directory is removed) and
# exits non-zero: 1 for a failed or empty merge, 130 for SIGINT or SIGTERM.
set -euo pipefail

if (($# < 3)); then
  sed -n '4p' "$0" >&2
  exit 2
fi
fuzzer="$1"
corpus="${2%/}"
new_inputs="${3%/}"
log="${4:-/dev/null}"

if [[ ! -d "$corpus" ]]; then
  echo "fuzz_merge: no corpus directory $corpus" >&2
  exit 2
fi
parent=$(dirname "$corpus")
merged=$(mktemp -d "$parent/.$(basename "$corpus").merging.XXXXXX")
retired="$parent/.$(basename "$corpus").retired.$$"

cleanup() {
  # The new set is ours to remove; the corpus is put back if a swap was cut short.
  if [[ ! -d "$corpus" && -d "$retired" ]]; then mv "$retired" "$corpus"; fi
  rm -rf "$merged"
}
interrupted() {
  trap '' INT TERM
  cleanup
  echo "fuzz_merge: interrupted; $corpus left as it was" >&2
  exit 130
}
trap interrupted INT TERM

count() { find "$1" -maxdepth 1 -type f | wc -l; }
before=$(count "$corpus")

status=0
"$fuzzer" -merge=1 "$merged" "$corpus" "$new_inputs" > "$log" 2>&1 || status=$?
if ((status == 0)); then
  "$fuzzer" -merge=1 "$merged" "$corpus" >> "$log" 2>&1 || status=$?
fi
if ((status != 0)); then
  cleanup
  echo "fuzz_merge: the merge failed (exit $status, log: $log); $corpus left as it was" >&2
  exit 1
fi
after=$(count "$merged")
if ((after == 0)); then
  cleanup
  echo "fuzz_merge: the merge produced no inputs (log: $log); $corpus left as it was" >&2
  exit 1
fi

# The swap: SIGINT and SIGTERM are ignored by the shell and by mv until the new set is in place.
trap '' INT TERM
chmod --reference="$corpus" "$merged" 2> /dev/null || chmod 755 "$merged"
mv "$corpus" "$retired"
mv "$merged" "$corpus"
rm -rf "$retired"
trap - INT TERM
echo "corpus: $before -> $after inputs"
