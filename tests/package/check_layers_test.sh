#!/usr/bin/env bash
# scripts/check_layers.sh on small trees of its own: a tree that keeps its layers passes; each
# planted break (an include up the layers, a third-party header in the core, the core's
# internals included elsewhere, a child process outside the client, another library's detail
# name, a third-party detail name in a header) fails, naming the file and line.
# Usage: bash tests/package/check_layers_test.sh   (exit 0: every case behaved)
set -euo pipefail
check="$(cd "$(dirname "$0")/../.." && pwd)/scripts/check_layers.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

# A clean tree: core, protocol over core, oracle over both, with detail namespaces.
make_tree() {
  rm -rf "$work/tree"
  mkdir -p "$work/tree/core/include/oblique/detail" "$work/tree/protocol/include/oblique/protocol" \
           "$work/tree/oracle/include/oblique/oracle"
  cat > "$work/tree/core/include/oblique/oblique.h" <<'EOF'
#pragma once
#include <Eigen/Core>
#include <cmath>
#include "oblique/detail/scale.h"
namespace oblique {
inline double apply(double x) { return detail::scale(x, detail::Side::right); }
}  // namespace oblique
EOF
  cat > "$work/tree/core/include/oblique/detail/scale.h" <<'EOF'
#pragma once
namespace oblique::detail {
enum class Side : bool { left, right };
inline double scale(double x, Side = Side::left) { return 2 * x; }
}  // namespace oblique::detail
EOF
  cat > "$work/tree/protocol/include/oblique/protocol/wire.h" <<'EOF'
#pragma once
#include "oblique/oblique.h"
EOF
  cat > "$work/tree/protocol/include/oblique/protocol/child_process.h" <<'EOF'
#pragma once
EOF
  cat > "$work/tree/protocol/wire.cpp" <<'EOF'
#include <nlohmann/json.hpp>
#include "oblique/protocol/wire.h"
void f(const nlohmann::detail::exception&);  // a third-party detail in a compiled source
EOF
  cat > "$work/tree/oracle/include/oblique/oracle/judge.h" <<'EOF'
#pragma once
#include "oblique/oblique.h"
#include "oblique/protocol/wire.h"
namespace oblique::oracle {
namespace detail {
template <class T>
T twice(T x) {
  return x + x;
}
}  // namespace detail
inline double judged(double x) { return detail::twice(x); }  // its own detail: fine
}  // namespace oblique::oracle
EOF
}

expect() {  # name, expected exit, text the output must hold (empty: any)
  local out code=0
  out=$(bash "$check" "$work/tree" 2>&1) || code=$?
  if [[ "$code" != "$2" ]] || [[ -n "$3" && "$out" != *"$3"* ]]; then
    echo "FAIL: $1: exit $code (expected $2), output:"
    echo "$out"
    failures=$((failures + 1))
  else
    echo "ok: $1"
  fi
}

make_tree
expect "a tree that keeps its layers" 0 "every library keeps to its layer"

make_tree
sed -i 's|#include <cmath>|#include "oblique/oracle/judge.h"|' "$work/tree/core/include/oblique/oblique.h"
expect "the core including the oracle" 1 \
  "core/include/oblique/oblique.h:3: core includes oblique/oracle/judge.h, of oracle"

make_tree
echo '#include "oblique/oracle/judge.h"' >> "$work/tree/protocol/include/oblique/protocol/wire.h"
expect "the protocol including the oracle" 1 "protocol includes oblique/oracle/judge.h"

make_tree
sed -i 's|#include <cmath>|#include <gmpxx.h>|' "$work/tree/core/include/oblique/oblique.h"
expect "a third-party header in the core" 1 "core includes gmpxx.h"

make_tree
echo '#include "oblique/detail/scale.h"' >> "$work/tree/protocol/include/oblique/protocol/wire.h"
expect "another library including the core's internals" 1 \
  "protocol/include/oblique/protocol/wire.h:3: protocol includes oblique/detail/scale.h, one of the core's internals"

make_tree
echo 'inline double g(double x) { return oblique::detail::scale(x); }' \
  >> "$work/tree/protocol/include/oblique/protocol/wire.h"
expect "the core's detail named with its namespace" 1 "protocol uses oblique::detail::scale"

make_tree
printf 'namespace oblique::oracle {\ninline double h(double x) { return detail::scale(x); }\n}\n' \
  >> "$work/tree/oracle/include/oblique/oracle/judge.h"
expect "the core's detail reached from inside oblique::" 1 \
  "oracle uses detail::scale, which it does not declare"

make_tree
echo '#include "oblique/protocol/child_process.h"' >> "$work/tree/oracle/include/oblique/oracle/judge.h"
expect "a child process outside the client" 1 \
  "oracle includes oblique/protocol/child_process.h (programs are asked through oblique::client alone)"

make_tree
echo 'void g(const nlohmann::detail::exception&);' >> "$work/tree/protocol/include/oblique/protocol/wire.h"
expect "a third-party detail in a header" 1 "protocol uses nlohmann::detail::exception in a header"

make_tree
printf '// a stray \0 byte\n#include <gmpxx.h>\n' > "$work/tree/core/include/oblique/detail/stray.h"
expect "a header with a NUL byte is still read" 1 "core includes gmpxx.h"

code=0
bash "$check" "$work/no-such-tree" > /dev/null 2>&1 || code=$?
if [[ "$code" == 2 ]]; then echo "ok: a missing tree"; else
  echo "FAIL: a missing tree: exit $code (expected 2)"; failures=$((failures + 1)); fi

((failures == 0)) || { echo "$failures case(s) failed"; exit 1; }
