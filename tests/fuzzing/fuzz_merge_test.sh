#!/usr/bin/env bash
# CTest (label fuzz): scripts/fuzz_merge.sh against stub fuzzers that fail, produce nothing, are
# interrupted mid-merge, or succeed. Whatever the merge does, no input of the corpus may be lost.
#
#   bash tests/fuzzing/fuzz_merge_test.sh SOURCE_DIR
set -uo pipefail
source_dir="$1"
merge="$source_dir/scripts/fuzz_merge.sh"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# A corpus of three inputs, and a directory of two new ones.
setup() {
  rm -rf "$scratch/work" && mkdir -p "$scratch/work/corpus" "$scratch/work/new"
  printf 'alpha' > "$scratch/work/corpus/a"
  printf 'beta' > "$scratch/work/corpus/b"
  printf 'gamma' > "$scratch/work/corpus/c"
  printf 'delta' > "$scratch/work/new/d"
  printf 'epsilon' > "$scratch/work/new/e"
  (cd "$scratch/work/corpus" && sha1sum a b c) > "$scratch/expected"
}

corpus_unchanged() {
  local what="$1"
  if ! (cd "$scratch/work/corpus" 2> /dev/null && sha1sum -c --quiet "$scratch/expected"); then
    fail "$what: the corpus lost or changed an input"
  fi
  local n
  n=$(find "$scratch/work/corpus" -maxdepth 1 -type f | wc -l)
  ((n == 3)) || fail "$what: the corpus holds $n inputs, not 3"
  if compgen -G "$scratch/work/.corpus.*" > /dev/null; then
    fail "$what: a temporary directory was left beside the corpus: $(ls -a "$scratch/work")"
  fi
}

stub() {
  local name="$1" body="$2"
  printf '#!/usr/bin/env bash\n%s\n' "$body" > "$scratch/$name"
  chmod +x "$scratch/$name"
  echo "$scratch/$name"
}

run_merge() {
  bash "$merge" "$1" "$scratch/work/corpus" "$scratch/work/new" "$scratch/work/merge.log" \
    > "$scratch/out" 2>&1
}

# 1. A merge that fails after writing part of its output (e.g. an unwritable TMPDIR).
setup
fuzzer=$(stub failing '[[ "$1" == -merge=1 ]] && printf x > "$2/partial"; exit 1')
run_merge "$fuzzer" && fail "failing merge: exit 0"
corpus_unchanged "failing merge"

# 2. A merge that exits 0 but writes nothing.
setup
fuzzer=$(stub empty 'exit 0')
run_merge "$fuzzer" && fail "empty merge: exit 0"
corpus_unchanged "empty merge"

# 3. A merge interrupted by Ctrl-C: the stub writes one input, then SIGINTs the merge script (as
#    the terminal does to the whole process group) and exits as libFuzzer does on SIGINT.
setup
fuzzer=$(stub interrupted 'cp "$3"/a "$2"/ ; kill -INT "$PPID"; sleep 0.2; exit 72')
run_merge "$fuzzer"
status=$?
((status == 130)) || fail "interrupted merge: exit $status, not 130"
corpus_unchanged "interrupted merge"

# 4. SIGTERM on the second merge pass, after the first one succeeded.
setup
fuzzer=$(stub terminated 'if (($# == 4)); then cp "$3"/* "$4"/* "$2"/; exit 0; fi
kill -TERM "$PPID"; sleep 0.2; exit 1')
run_merge "$fuzzer"
status=$?
((status == 130)) || fail "terminated merge: exit $status, not 130"
corpus_unchanged "terminated merge"

# 5. A merge that succeeds: the first pass keeps b, c and the new inputs (as if a's features were
#    covered by them) but misses nothing; the second pass finds a's feature missing and adds it.
#    The corpus is replaced, and every old input is still there.
setup
fuzzer=$(stub succeeding 'if (($# == 4)); then cp "$3"/b "$3"/c "$4"/* "$2"/; exit 0; fi
[[ -e "$2/a" ]] || cp "$3"/a "$2"/; exit 0')
if ! run_merge "$fuzzer"; then
  fail "succeeding merge: non-zero exit: $(cat "$scratch/out")"
fi
for f in a b c d e; do
  [[ -f "$scratch/work/corpus/$f" ]] || fail "succeeding merge: $f missing from the new corpus"
done
(cd "$scratch/work/corpus" && sha1sum -c --quiet "$scratch/expected") ||
  fail "succeeding merge: an old input changed"
grep -q "corpus: 3 -> 5 inputs" "$scratch/out" || fail "succeeding merge: no count line"

if ((failures > 0)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "fuzz_merge: every case kept the corpus"
