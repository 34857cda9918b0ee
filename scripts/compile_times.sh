#!/usr/bin/env bash
# What adopting oblique costs a user's build: compile time and peak memory of three small files,
# built as a user's project builds them (find_package(oblique) against the installed package, the
# flags CMake gives a Release build), one compile at a time, best of N runs:
#   one_test.cpp          the README's one-test file (oblique/testing.h, one OBLIQUE_PROPERTY_TEST)
#   calls_apply.cpp       a function calling oblique::apply<double> (linking oblique::core)
#   includes_oblique.cpp  #include <oblique/oblique.h> alone
#   fuzz_target.cpp       the README's fuzz target (oblique/fuzzing.h; held to the one-test target)
#   judges.cpp            a test judging an answer with oblique/oracle/checker.h (the same)
# Usage: bash scripts/compile_times.sh [--build DIR] [--runs N] [--fresh-clone]
#   --build DIR    the configured and built tree to install from (default build/release)
#   --runs N       compiles per file (default 3); the fastest is reported, with its peak memory
#   --fresh-clone  also times `bash scripts/test.sh` in a fresh clone of HEAD (15 minutes or so)
# Prints one line per file: seconds, MB, and the target of issue 24 it is measured against.
# A measurement, not a test: it exits 0 whatever the figures, non-zero when it could not measure.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build/release
runs=3
fresh_clone=0
while (($#)); do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --fresh-clone) fresh_clone=1; shift ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "compile_times.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
if [[ ! -x /usr/bin/time ]]; then
  echo "compile_times.sh: needs GNU time (/usr/bin/time); bash scripts/setup.sh installs it" >&2
  exit 2
fi
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  echo "compile_times.sh: $build is not a configured build (cmake --preset release" \
       "&& cmake --build --preset release)" >&2
  exit 2
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > /dev/null
mkdir -p "$work/project"
cat > "$work/project/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.25)
project(compile_times LANGUAGES CXX)
find_package(oblique CONFIG REQUIRED)
add_library(one_test OBJECT one_test.cpp)
target_link_libraries(one_test PRIVATE oblique::testing)
add_library(calls_apply OBJECT calls_apply.cpp)
target_link_libraries(calls_apply PRIVATE oblique::core)
add_library(includes_oblique OBJECT includes_oblique.cpp)
target_link_libraries(includes_oblique PRIVATE oblique::core)
add_library(fuzz_target OBJECT fuzz_target.cpp)
target_link_libraries(fuzz_target PRIVATE oblique::fuzzing)
add_library(judges OBJECT judges.cpp)
target_link_libraries(judges PRIVATE oblique::properties)
EOF
# The README's file, as printed there.
cat > "$work/project/one_test.cpp" <<'EOF'
#include <oblique/testing.h>
bool make_oblique(float m[16], const float plane[4]);  // yours: column-major, false = refused

// It takes no convention, so it says which it serves; the default contract checks that one,
// every family, place and property, and (from the bool) accepts any refusal of an input
// without an answer.
const auto mine = oblique::adapt<float>("make_oblique", oblique::Layout::column_major,
                                        oblique::Convention::gl, make_oblique,
                                        oblique::engine_perspective_only<float>);
OBLIQUE_PROPERTY_TEST(MyEngine, makeObliqueHasEveryProperty, mine, oblique::Contract{})
EOF
cat > "$work/project/calls_apply.cpp" <<'EOF'
#include <oblique/oblique.h>
oblique::ObliqueResult<double> mirror(const oblique::Matrix4<double>& m,
                                      const oblique::Vector4<double>& plane) {
  return oblique::apply<double>(m, plane, oblique::Convention::gl);
}
EOF
echo '#include <oblique/oblique.h>' > "$work/project/includes_oblique.cpp"
cat > "$work/project/fuzz_target.cpp" <<'EOF'
#include <oblique/fuzzing.h>
void make_oblique(float m[16], const float plane[4]);  // yours

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto mine = oblique::adapt<float>("make_oblique", oblique::Layout::column_major,
                                                 oblique::Convention::gl, make_oblique,
                                                 oblique::engine_perspective_only<float>);
  return oblique::fuzzing::test_one_input(data, size, mine);  // or a Contract as third argument
}
EOF
cat > "$work/project/judges.cpp" <<'EOF'
#include <oblique/oblique.h>
#include <oblique/oracle/checker.h>
bool holds(const oblique::Matrix4<float>& m, const oblique::Vector4<float>& plane,
           const oblique::Matrix4<float>& mine) {
  const oblique::oracle::Checker<float> checker(m, plane, oblique::Convention::gl);
  return checker.judge(oblique::Answer<float>{oblique::Status::ok, mine}).holds();
}
EOF

# Each compile runs under GNU time (seconds, peak KB), appended to one log.
log="$work/times.log"
cat > "$work/timed.sh" <<EOF
#!/usr/bin/env bash
source_file=""
for a in "\$@"; do [[ "\$a" == *.cpp ]] && source_file=\$(basename "\$a"); done
exec /usr/bin/time -f "\$source_file %e %M" -a -o "$log" "\$@"
EOF
chmod +x "$work/timed.sh"
cmake -S "$work/project" -B "$work/build" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_COMPILER_LAUNCHER="$work/timed.sh" > /dev/null
for ((run = 1; run <= runs; ++run)); do
  cmake --build "$work/build" --clean-first -j1 > /dev/null
done

echo "compile time and peak memory, fastest of $runs ($(${CXX:-c++} --version | head -n 1)):"
report() {  # file, target seconds, target MB (0: none)
  local line
  line=$(awk -v f="$1" '$1 == f' "$log" | sort -k2,2g | head -n 1)
  if [[ -z "$line" ]]; then
    echo "compile_times.sh: $1 was not compiled" >&2
    exit 1
  fi
  awk -v s="$2" -v m="$3" '{
    mb = $3 / 1024
    ok = ($2 <= s) && (m == 0 || mb <= m)
    printf "  %-22s %6.2f s %7.0f MB   target <= %s s%s: %s\n", $1, $2, mb, s,
           (m ? sprintf(", <= %d MB", m) : ""), (ok ? "within" : "over")
  }' <<< "$line"
}
report one_test.cpp 3 400
report calls_apply.cpp 2 0
report includes_oblique.cpp 1.5 0
report fuzz_target.cpp 3 400
report judges.cpp 3 400

if ((fresh_clone)); then
  git clone --quiet . "$work/clone"
  start=$(date +%s)
  if (cd "$work/clone" && bash scripts/test.sh > "$work/test.log" 2>&1); then
    echo "fresh-clone bash scripts/test.sh: $(($(date +%s) - start)) s (target <= 480 s)"
  else
    tail -n 20 "$work/test.log" >&2
    echo "compile_times.sh: the fresh-clone test run failed" >&2
    exit 1
  fi
fi
