# Sourced by scripts/fuzz.sh and scripts/fuzz_steadiness.sh: read_fuzz_options TARGET reads
# fuzz/TARGET.options (OSS-Fuzz's format: sections "[libfuzzer]", "[asan]", ... of "name = value"
# lines) into `libfuzzer_flags` (an array of -name=value) and `asan_options` (name=value:...).
read_fuzz_options() {
  libfuzzer_flags=()
  asan_options=""
  local file="fuzz/$1.options" section="" name value
  [[ -f "$file" ]] || return 0
  while IFS='= ' read -r name value; do
    if [[ "$name" == \[*\] ]]; then section="$name"; continue; fi
    [[ -n "$name" && -n "$value" ]] || continue
    case "$section" in
      "[libfuzzer]") libfuzzer_flags+=("-$name=$value") ;;
      "[asan]") asan_options+="${asan_options:+:}$name=$value" ;;
    esac
  done < "$file"
}
