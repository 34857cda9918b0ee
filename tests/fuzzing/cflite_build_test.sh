#!/bin/bash
# Runs .clusterfuzzlite/build.sh as ClusterFuzzLite's builder would (OSS-Fuzz's variables, clang,
# AddressSanitizer, libFuzzer) on this machine, then checks that every fuzz target, its
# dictionary and its seed corpus zip landed in $OUT. Usage: cflite_build_test.sh SOURCE CLANG CLANGXX
set -euo pipefail
source_dir="$1"
export CC="$2" CXX="$3"
scratch="$(mktemp -d "${TMPDIR:-/tmp}/oblique-cflite.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
export OUT="$scratch/out" WORK="$scratch/work" SRC="$scratch/src"
mkdir -p "$OUT" "$WORK" "$SRC"
export CFLAGS="-O1 -fno-omit-frame-pointer -gline-tables-only -fsanitize=address -fsanitize-address-use-after-scope -fsanitize=fuzzer-no-link"
export CXXFLAGS="$CFLAGS"
export LIB_FUZZING_ENGINE="-fsanitize=fuzzer"
bash "$source_dir/.clusterfuzzlite/build.sh"
status=0
for source in "$source_dir"/fuzz/fuzz_*.cpp; do
  target="$(basename "$source" .cpp)"
  for file in "$target" "$target.dict" "${target}_seed_corpus.zip"; do
    if [[ ! -s "$OUT/$file" ]]; then
      echo "missing from \$OUT: $file"
      status=1
    fi
  done
  if [[ -x "$OUT/$target" ]]; then
    # The fuzzer runs: a few seconds on its seed corpus, no crash.
    mkdir -p "$scratch/corpus/$target"
    (cd "$scratch/corpus/$target" && python3 -m zipfile -e "$OUT/${target}_seed_corpus.zip" .)
    if ! "$OUT/$target" -runs=200 "$scratch/corpus/$target" > "$scratch/$target.log" 2>&1; then
      tail -30 "$scratch/$target.log"
      echo "$target failed on its seed corpus"
      status=1
    fi
  else
    echo "not executable: \$OUT/$target"
    status=1
  fi
done
ls -l "$OUT"
[[ $status -eq 0 ]] && echo "ClusterFuzzLite build: every fuzzer, dictionary and seed corpus in \$OUT"
exit $status
