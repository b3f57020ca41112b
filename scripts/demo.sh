#!/usr/bin/env bash
# The main job on built-in data, no camera needed: installs what is missing, builds, simulates a
# short match seen by 2 cameras (1280x720, 120 fps, H.264), tracks the ball in 3D from the videos
# and prints the evaluation against the simulator's ground truth.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh --target p4track
out="${1:-out/demo}"
p4track=./build/release/apps/p4track/p4track
"$p4track" simulate --out "$out/sim" --points 4 --seed 1
"$p4track" track --rig "$out/sim/rig.yaml" --out "$out/run" "$out/sim/cam0.mp4" "$out/sim/cam1.mp4"
echo
echo "== evaluation of $out/run against $out/sim"
"$p4track" eval --truth "$out/sim" --run "$out/run" --out "$out/eval.json"
