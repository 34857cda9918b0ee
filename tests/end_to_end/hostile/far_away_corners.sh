#!/bin/sh
# A corners program gone wrong: the same small box, 1e300 away, whatever it is asked. The corners
# are judged against a bound taken from the right answer; a bound taken from these corners grew
# past w = 0 and left the round out instead of failing it.
while read -r _; do
  echo '{"corners": [[1e300, 1e300, 1e300], [1.1e300, 1e300, 1e300], [1e300, 1.1e300, 1e300], [1.1e300, 1.1e300, 1e300], [1e300, 1e300, 1.1e300], [1.1e300, 1e300, 1.1e300], [1e300, 1.1e300, 1.1e300], [1.1e300, 1.1e300, 1.1e300]]}'
done
