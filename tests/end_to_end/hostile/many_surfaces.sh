#!/bin/sh
# many_surfaces.sh OBLIQUE DIR: `oblique check` on a scene of 10,000 mirrors behind the camera,
# then one in front of it, in file order. The one in view must be rendered and judged, and the
# rest counted as not listed (the passes were capped in file order, so the first 512, all out of
# view, were looked at, nothing was rendered, and the run passed).
oblique=$1
dir=$2
rm -rf "$dir"
mkdir -p "$dir"
awk 'BEGIN {
  print "{\"name\": \"10,000 mirrors behind the camera, one in front\", \"convention\": \"gl\",";
  print " \"camera\": {\"projection\": {\"type\": \"perspective\", \"fovy_deg\": 60, \"aspect\": 1.5, \"near\": 0.1, \"far\": 100},";
  print "            \"view\": {\"eye\": [0, 0, 0], \"target\": [0, 0, -1], \"up\": [0, 1, 0]}},";
  print " \"surfaces\": [";
  for (i = 0; i < 10000; ++i)
    printf "  {\"name\": \"behind %d\", \"kind\": \"mirror\", \"rectangle\": {\"center\": [0, 0, %g], \"normal\": [0, 0, -1], \"up\": [0, 1, 0], \"size\": [1, 1]}},\n", i, 2 + i * 0.001;
  print "  {\"name\": \"in view\", \"kind\": \"mirror\", \"rectangle\": {\"center\": [0, 0, -3], \"normal\": [0, 0, 1], \"up\": [0, 1, 0], \"size\": [1, 1]}}";
  print " ]}";
}' > "$dir/scene.json"
"$oblique" check "$dir/scene.json" > "$dir/check.log" 2>&1
status=$?
tail -n 20 "$dir/check.log"
if [ "$status" != 0 ]; then
  echo "many_surfaces: oblique check exited with $status, expected 0"
  exit 1
fi
if ! grep -q "^ *in view.*render" "$dir/check.log"; then
  echo "many_surfaces: the mirror in view was not rendered"
  exit 1
fi
if ! grep -q "more surfaces out of view" "$dir/check.log"; then
  echo "many_surfaces: the surfaces not listed are not counted"
  exit 1
fi
echo "many_surfaces: the mirror in view rendered, the rest counted"
