#!/bin/sh
# expect_accuracy_contract.sh OBLIQUE DIR IMPL: `oblique report accuracy --impl IMPL`, where IMPL is
# right in zero_one only, counts its gl answers as violating; limited to the contract it claims
# (--convention zero_one --families perspective) it measures only that: no violation, no regime of
# another family, the contract named in the report. A contract no regime meets is refused.
oblique=$1
dir=$2
impl=$3
rm -rf "$dir"
fail() {
  echo "expect_accuracy_contract: $*"
  exit 1
}
"$oblique" report accuracy --cases 2 --quiet --out "$dir/all" --impl "$impl" > "$dir.all.log" 2>&1
grep -q "violating the properties" "$dir/all/accuracy.md" ||
  fail "asked every convention, the gl-wrong implementation shows no violating answer"
"$oblique" report accuracy --cases 2 --quiet --out "$dir/contract" --impl "$impl" \
  --convention zero_one --families perspective > "$dir.contract.log" 2>&1 ||
  fail "the run under the contract exited $?: $(cat "$dir.contract.log")"
md="$dir/contract/accuracy.md"
grep -q 'Measured under the contract `{.*"conventions": \["zero_one"\]' "$md" ||
  fail "the report does not name its contract"
if grep -q "violating" "$md"; then fail "answers in the claimed convention counted as violating"; fi
for regime in infinite orthographic scaled; do
  if grep -q "^| $regime |" "$md"; then fail "regime $regime of a family not claimed was measured"; fi
done
grep -q "^| typical |" "$md" || fail "the perspective regime typical was not measured"
"$oblique" report accuracy --cases 2 --quiet --out "$dir/some" --families perspective,y_flipped \
  > "$dir.some.log" 2>&1 || fail "--families perspective,y_flipped exited $?"
grep -q "Not measured: the families y_flipped of the contract" "$dir/some/accuracy.md" ||
  fail "a claimed family no regime builds is not said to be unmeasured"
out=$("$oblique" report accuracy --cases 2 --quiet --out "$dir/none" --families y_flipped 2>&1)
status=$?
[ "$status" = 2 ] || fail "--families y_flipped exited $status, expected 2: $out"
echo "$out" | grep -q "nothing to measure" || fail "--families y_flipped: $out"
out=$("$oblique" report accuracy --cases 2 --quiet --out "$dir/none" --convention zero-one 2>&1)
status=$?
[ "$status" = 2 ] || fail "--convention zero-one exited $status, expected 2: $out"
echo "$out" | grep -q -- '--convention: unknown convention "zero-one" (did you mean zero_one?' ||
  fail "--convention zero-one: $out"
echo "report accuracy measures what the contract claims"
