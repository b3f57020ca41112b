#!/usr/bin/env bash
# The main job on built-in data, no camera needed: installs what is missing, builds, simulates a
# short match seen by 2 cameras (1280x720, 120 fps) and prints what was written.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh --target p4track
out="${1:-out/demo}"
./build/release/apps/p4track/p4track simulate --out "$out" --points 4 --seed 1
echo
echo "== $out"
ls -l "$out"
echo
echo "== events ($out/truth_events.jsonl)"
grep -c . "$out/truth_events.jsonl" | xargs echo "lines:"
grep '"point"' "$out/truth_events.jsonl"
echo
echo "== final score ($out/truth_score.json)"
cat "$out/truth_score.json"
