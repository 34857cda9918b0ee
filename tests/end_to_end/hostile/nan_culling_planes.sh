#!/bin/sh
# A culling_planes program gone wrong: every plane it answers is NaN (the six planes as 24 numbers).
# Judging must say "not finite", never die of it (GMP given a NaN raised SIGFPE).
while read -r _; do
  echo '{"planes": ["nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan", "nan"]}'
done
