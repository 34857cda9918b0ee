#!/bin/sh
# An implementation that leaves a process behind outside its process group (setsid), as a
# daemonising helper would: oblique verify must end it too.
#   leaves_a_grandchild.sh PIDFILE COMMAND...: the grandchild writes its pid to PIDFILE.
pidfile=$1
shift
setsid sh -c 'echo $$ > "$0"; exec sleep 300' "$pidfile" &
exec "$@"
