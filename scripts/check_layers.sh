#!/usr/bin/env bash
# The libraries' layering, checked over their sources (#include lines and detail:: names):
#   - a library includes headers only of the libraries below it (the table below); the core
#     includes nothing outside the core but Eigen and the standard library;
#   - the core's internals (oblique/detail/: the methods' steps, the solver, the accurate method)
#     are the core's alone: another library includes its front doors (oblique/*.h), its
#     references (oblique/references/), its numeric primitives (oblique/numeric/) and its
#     support headers (oblique/util/), never oblique/detail/;
#   - a child process is oblique::client's alone: no other library (protocol aside, which has it)
#     includes oblique/protocol/child_process.h; the tools ask programs through the client. The
#     one exception is oblique::shader, which runs glslang and spirv-cross (tools of ours, under
#     its own time and memory limits, not a user's program speaking the protocol);
#   - a library names no other library's detail namespace: every `detail::NAME` in a library's
#     files is declared in a `namespace detail` block of that same library; a third-party one's
#     (`rc::detail`, `nlohmann::detail`) appears only in compiled sources, never in a header.
# Usage: bash scripts/check_layers.sh [ROOT]   (ROOT: the source tree, default the repository)
# Prints each violation as FILE:LINE: what; exits 1 when there is one, 0 when there is none, 2
# when ROOT is not a directory.
# Tests (files named *_test.cpp, and the tests/, bench/, examples/ and fuzz/ folders) are users of
# the libraries, not layers, and are not checked.
set -euo pipefail
root="${1:-$(cd "$(dirname "$0")/.." && pwd)}"
if [[ ! -d "$root" ]]; then
  echo "check_layers: $root is not a directory (give the source tree's root)" >&2
  exit 2
fi
cd "$root"

# Each library, its folder, and the libraries it may include (besides itself).
declare -A below=(
  [core]=""
  [protocol]="core"
  [report_files]="core protocol"
  [cases]="core protocol"
  [oracle]="core protocol cases"
  [mistakes]="core protocol cases oracle"
  [client]="core protocol cases oracle"
  [run]="core protocol cases"
  [report]="core protocol report_files cases oracle mistakes client"
  [raster]="core protocol report_files cases oracle mistakes"
  [shader]="core protocol report_files cases oracle mistakes raster"
  [fuzzing]="core protocol report_files cases run oracle mistakes client report"
  [scene]="core protocol report_files cases run oracle mistakes client report"
  [testing]="core protocol report_files cases run oracle mistakes client report raster shader"
  [verify]="core protocol report_files cases run oracle mistakes client report raster shader"
  [cli]="core protocol report_files cases run oracle mistakes client report raster shader fuzzing verify scene"
)
libraries=(core protocol report_files cases run oracle mistakes client report raster shader fuzzing scene testing verify cli)

sources_of() {  # the library's own files, tests left out
  find "$1" -type f \( -name '*.h' -o -name '*.cpp' \) ! -name '*_test.cpp' | sort
}

# The library a project header (as written in #include) belongs to: the one whose include/
# folder holds it, or whose folder holds it beside the including file's folder. Empty: not ours.
owner_of() {  # include path, including file
  local lib
  for lib in "${libraries[@]}"; do
    if [[ -f "$lib/include/$1" ]]; then echo "$lib"; return; fi
  done
  local here
  here=$(dirname "$2")
  if [[ -f "$here/$1" ]]; then echo "${2%%/*}"; fi
}

status=0
violation() {
  echo "$1"
  status=1
}

for lib in "${libraries[@]}"; do
  [[ -d "$lib" ]] || continue
  allowed=" $lib ${below[$lib]} "
  files=$(sources_of "$lib")
  [[ -n "$files" ]] || continue
  # Includes.
  while IFS=: read -r file line text; do
    header=$(sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"].*/\1/' <<< "$text")
    owner=$(owner_of "$header" "$file")
    if [[ -n "$owner" ]]; then
      [[ "$allowed" == *" $owner "* ]] ||
        violation "$file:$line: $lib includes $header, of $owner (allowed: ${below[$lib]:-none})"
      [[ "$owner" != core || "$lib" == core || "$header" != oblique/detail/* ]] ||
        violation "$file:$line: $lib includes $header, one of the core's internals (oblique/detail/)"
      [[ "$header" != oblique/protocol/child_process.h || "$lib" == protocol || "$lib" == client ||
         "$lib" == shader ]] ||
        violation "$file:$line: $lib includes $header (programs are asked through oblique::client alone)"
    elif [[ "$lib" == core && ! "$header" =~ ^Eigen/ && "$header" == *.* ]]; then
      violation "$file:$line: core includes $header (the core uses only Eigen and the standard library)"
    fi
  done < <(grep -anE '^[[:space:]]*#[[:space:]]*include' $files /dev/null | cut -d: -f1-3)

  # The names the library declares in its own detail namespaces (top-level declarations of
  # `namespace ...detail {` blocks: types, aliases, functions, variables).
  declared=$(awk '
    function strip(s) { gsub(/"([^"\\]|\\.)*"/, "\"\"", s); gsub(/\/\/.*$/, "", s); return s }
    {
      line = strip($0)
      if (depth == 0 && line ~ /namespace[[:space:]]+([A-Za-z_:]*::)?detail[[:space:]]*\{/) {
        depth = 1
        next
      }
      if (depth == 1) {
        if (match(line, /(struct|class|union|enum([[:space:]]+(class|struct))?)[[:space:]]+[A-Za-z_][A-Za-z0-9_]*/)) {
          n = split(substr(line, RSTART, RLENGTH), w, /[[:space:]]+/); print w[n]
        } else if (match(line, /using[[:space:]]+[A-Za-z_][A-Za-z0-9_]*[[:space:]]*=/)) {
          s = substr(line, RSTART, RLENGTH); sub(/^using[[:space:]]+/, "", s); sub(/[[:space:]]*=$/, "", s); print s
        } else if (match(line, /[A-Za-z_][A-Za-z0-9_]*[[:space:]]*[(=]/)) {
          s = substr(line, RSTART, RLENGTH); sub(/[[:space:]]*[(=]$/, "", s); print s
        }
      }
      if (depth > 0) {
        opened = gsub(/\{/, "{", line); closed = gsub(/\}/, "}", line)
        depth += opened - closed
      }
    }' $files | sort -u)
  # Every detail:: name the library uses.
  while IFS=: read -r file line text; do
    while read -r use; do
      [[ -n "$use" ]] || continue
      qualifier="${use%%detail::*}"
      name="${use##*detail::}"
      if [[ -n "$qualifier" && "$qualifier" != "oblique::" ]]; then
        # A third-party library's internals (RapidCheck's test runner has no other API) may be
        # used in compiled sources, never in a header users include.
        [[ "$file" == *.cpp ]] ||
          violation "$file:$line: $lib uses ${use} in a header (another library's detail namespace)"
      elif [[ "$qualifier" == "oblique::" && "$lib" != core ]]; then
        violation "$file:$line: $lib uses ${use} (the core's detail namespace)"
      elif ! grep -qxF "$name" <<< "$declared"; then
        violation "$file:$line: $lib uses detail::$name, which it does not declare (another library's detail namespace)"
      fi
    done < <(grep -oE '([A-Za-z_][A-Za-z0-9_]*::)?detail::[A-Za-z_][A-Za-z0-9_]*' <<< "$text" || true)
  done < <(grep -anE 'detail::' $files /dev/null | sed -E 's://.*$::' || true)
done
if ((status == 0)); then echo "check_layers: every library keeps to its layer"; fi
exit $status
