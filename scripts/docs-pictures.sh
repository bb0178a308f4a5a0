#!/usr/bin/env bash
# Regenerates the pictures of docs/images/ from genflow's own HTML reports, rendered by headless
# Chromium: a match of the MakeHuman body (CC0, from $GENFLOW_DATA) onto another of its poses,
# coloured by the error against the ground truth; a fairing of that body with noise added,
# before and after; the built-in demo. Needs build/release/genflow (scripts/setup.sh) and
# python3 (the noise). Usage: scripts/docs-pictures.sh [OUTPUT_DIR] (default docs/images).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
data=${GENFLOW_DATA:-$PWD/../shared/data}
out=${1:-docs/images}
genflow=build/release/genflow
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
body=$data/rigs/makehuman_body

# A report's view alone (#view) as a PNG of WIDTHxHEIGHT.
picture() {
  local report=$1 png=$2 size=$3
  chromium --headless --no-sandbox --enable-unsafe-swiftshader --hide-scrollbars \
    --user-data-dir="$work/profile" --window-size="$size" --screenshot="$png" \
    "file://$report#view" >/dev/null 2>&1
  echo "docs-pictures: wrote $png"
}

# The body in its rest pose onto its second pose, the ground truth the posed vertices.
$genflow match "$body/body_rest.ply" "$body/body_pose2.ply" -o "$work/matched.ply" \
  --ground-truth "$body/body_pose2.ply" --report "$work/match.html" --quiet >/dev/null
picture "$work/match.html" "$out/match_report.png" 1200,560

# The body with Gaussian noise of a tenth of its mean edge length, faired in 3 steps.
$genflow smooth "$body/body_rest.ply" "$work/body.obj" --steps 0 --json >/dev/null
python3 - "$work/body.obj" "$work/noisy.obj" <<'EOF'
import math, random, sys
random.seed(7)
lines = open(sys.argv[1]).read().splitlines()
vertices = [list(map(float, l.split()[1:4])) for l in lines if l.startswith("v ")]
faces = [[int(t) - 1 for t in l.split()[1:4]] for l in lines if l.startswith("f ")]
edges = [math.dist(vertices[f[k]], vertices[f[(k + 1) % 3]]) for f in faces for k in range(3)]
sigma = 0.1 * sum(edges) / len(edges)
with open(sys.argv[2], "w") as out:
    for v in vertices:
        out.write("v %r %r %r\n" % tuple(x + random.gauss(0, sigma) for x in v))
    for f in faces:
        out.write("f %d %d %d\n" % tuple(i + 1 for i in f))
EOF
$genflow smooth "$work/noisy.obj" "$work/smooth.ply" --steps 3 --report "$work/smooth.html" \
  >/dev/null 2>&1
picture "$work/smooth.html" "$out/smooth_report.png" 1000,560

$genflow demo --quiet --output-dir "$work/demo" >/dev/null
picture "$work/demo/report.html" "$out/demo_report.png" 1000,420
