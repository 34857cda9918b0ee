#!/bin/bash -eu
# ClusterFuzzLite / OSS-Fuzz build. Honours $CC $CXX $CFLAGS $CXXFLAGS $LIB_FUZZING_ENGINE $OUT:
# the sanitizer flags come in CXXFLAGS, the engine in LIB_FUZZING_ENGINE. Writes each fuzz target,
# its dictionary and its seed corpus (zip) to $OUT.
root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ -d "${SRC:-}/oblique" ]]; then root="$SRC/oblique"; fi
build="${WORK:-/tmp}/oblique-cfl-build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_COMPILER="$CC" -DCMAKE_CXX_COMPILER="$CXX" \
  -DCMAKE_C_FLAGS="$CFLAGS" -DCMAKE_CXX_FLAGS="$CXXFLAGS" \
  -DOBLIQUE_BUILD_TESTS=OFF -DOBLIQUE_FUZZ=ON \
  -DOBLIQUE_FUZZ_ENGINE="$LIB_FUZZING_ENGINE" -DOBLIQUE_FUZZ_SANITIZERS=""
targets=()
for source in "$root"/fuzz/fuzz_*.cpp; do targets+=("$(basename "$source" .cpp)"); done
cmake --build "$build" --target "${targets[@]}" -j"$(nproc)"
for target in "${targets[@]}"; do
  cp "$build/fuzz/$target" "$OUT/"
  cp "$root/fuzz/$target.dict" "$OUT/$target.dict"
  if [[ -f "$root/fuzz/$target.options" ]]; then cp "$root/fuzz/$target.options" "$OUT/"; fi
  rm -f "$OUT/${target}_seed_corpus.zip"
  (cd "$root/fuzz/corpus/$target" && python3 -m zipfile -c "$OUT/${target}_seed_corpus.zip" .)
done
