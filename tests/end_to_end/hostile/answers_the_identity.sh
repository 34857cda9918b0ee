#!/bin/sh
# A matrix program whose every answer violates the properties: the identity, whatever it is asked.
while read -r _; do
  echo '{"status": "ok", "projection": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}'
done
