#!/bin/sh
# interrupt_while_charting.sh OBLIQUE DIR: Ctrl-C (SIGINT) to `oblique report accuracy` while it
# draws its charts, with a gnuplot that takes its time. It must die of the interrupt (exit 130),
# leave its folder as the earlier run left it (no new accuracy.md beside the old accuracy.png, no
# staging folder), and leave no gnuplot running. (std::system() ignored SIGINT in the caller, so
# the run went on, wrote its report and exited 0.)
oblique=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir/bin" "$dir/out"
cat > "$dir/bin/gnuplot" <<SLOW
#!/bin/sh
echo \$\$ > "$dir/gnuplot.pid"
exec sleep 60
SLOW
chmod +x "$dir/bin/gnuplot"
echo "earlier run" > "$dir/out/accuracy.md"
echo "earlier chart" > "$dir/out/accuracy.png"
before=$(ls -A "$dir/out" | sort | tr '\n' ' ')
PATH="$dir/bin:$PATH" env --default-signal=INT "$oblique" report accuracy --cases 20 --quiet \
  --out "$dir/out" > "$dir/report.log" 2>&1 &
report=$!
tries=0
while [ ! -s "$dir/gnuplot.pid" ]; do
  tries=$((tries + 1))
  if [ "$tries" -gt 600 ]; then
    echo "interrupt_while_charting: gnuplot never started"
    cat "$dir/report.log"
    kill "$report"
    exit 1
  fi
  sleep 0.1
done
kill -s INT "$report"
wait "$report"
status=$?
cat "$dir/report.log"
gnuplot_pid=$(cat "$dir/gnuplot.pid")
sleep 0.2
state=$(ps -o stat= -p "$gnuplot_pid" 2>/dev/null)
if [ -n "$state" ] && [ "${state#Z}" = "$state" ]; then
  kill "$gnuplot_pid"
  echo "interrupt_while_charting: gnuplot $gnuplot_pid outlived the interrupted report"
  exit 1
fi
if [ "$status" != 130 ]; then
  echo "interrupt_while_charting: exit $status after SIGINT, expected 130"
  exit 1
fi
after=$(ls -A "$dir/out" | sort | tr '\n' ' ')
if [ "$before" != "$after" ] || [ "$(cat "$dir/out/accuracy.md")" != "earlier run" ]; then
  echo "interrupt_while_charting: the folder changed: before [$before], after [$after]"
  exit 1
fi
echo "interrupt_while_charting: exit 130, the folder as it was"
