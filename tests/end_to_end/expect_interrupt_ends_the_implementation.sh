#!/bin/sh
# expect_interrupt_ends_the_implementation.sh OBLIQUE DIR SIGNAL [ARG...]: starts oblique verify
# (with ARGs, e.g. --consumers all) on an
# implementation that never answers, sends verify SIGNAL (INT as a Ctrl-C does, or TERM) once the
# implementation runs, and requires verify to die of it (exit 128 + n) and the implementation,
# which runs in a process group of its own, to be gone too.
oblique=$1
dir=$2
sig=$3
shift 3
rm -rf "$dir"
mkdir -p "$dir"
# (A background command of a non-interactive shell starts with SIGINT ignored; a terminal's
# foreground command has it at its default, which env --default-signal restores.)
env --default-signal=INT "$oblique" verify --impl "echo \$\$ > $dir/impl.pid; exec sleep 60" --time-limit 30 \
  --report-dir "$dir/reports" "$@" > "$dir/verify.log" 2>&1 &
verify=$!
tries=0
while [ ! -s "$dir/impl.pid" ]; do
  tries=$((tries + 1))
  if [ "$tries" -gt 100 ]; then
    echo "expect_interrupt: the implementation never started"
    kill "$verify"
    exit 1
  fi
  sleep 0.1
done
impl=$(cat "$dir/impl.pid")
kill -s "$sig" "$verify"
wait "$verify"
status=$?
case "$sig" in
  INT) expected=130 ;;
  TERM) expected=143 ;;
  *) expected=unknown ;;
esac
if [ "$status" != "$expected" ]; then
  echo "expect_interrupt: oblique verify exited with $status after SIG$sig, expected $expected"
  kill "$impl" 2>/dev/null
  exit 1
fi
# Ended: gone, or a zombie waiting for init to reap it (verify, its parent, is dead).
running() {
  state=$(ps -o stat= -p "$1" 2>/dev/null)
  [ -n "$state" ] && [ "${state#Z}" = "$state" ]
}
sleep 0.2
if running "$impl"; then
  echo "expect_interrupt: the implementation $impl survived SIG$sig to oblique verify"
  kill "$impl"
  exit 1
fi
echo "SIG$sig ended oblique verify (exit $status) and the implementation $impl"
