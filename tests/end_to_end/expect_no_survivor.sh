#!/bin/sh
# expect_no_survivor.sh OBLIQUE IMPL DIR: runs oblique verify on IMPL wrapped in
# leaves_a_grandchild.sh, then requires the grandchild (setsid, outside the process group) to be
# gone once verify has exited.
oblique=$1
impl=$2
dir=$3
examples=$(cd "$(dirname "$0")/../../examples" && pwd)
rm -rf "$dir"
mkdir -p "$dir"
"$oblique" verify --impl "sh $examples/implementations/leaves_a_grandchild.sh $dir/grandchild.pid $impl" \
  --cases 2000 --seed 1 --quiet --report-dir "$dir/reports" || exit 1
if [ ! -s "$dir/grandchild.pid" ]; then
  echo "expect_no_survivor.sh: the grandchild never wrote its pid"
  exit 1
fi
pid=$(cat "$dir/grandchild.pid")
sleep 0.2
if kill -0 "$pid" 2>/dev/null; then
  echo "expect_no_survivor.sh: the grandchild $pid survived oblique verify"
  kill "$pid"
  exit 1
fi
echo "the grandchild $pid was ended with the implementation"
