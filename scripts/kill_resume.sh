#!/usr/bin/env bash
# Crash safety, measured: `p4track track` killed with SIGKILL at N random moments of a simulated
# match (odd kills at a random time of the whole run: the sync, the colour learning or the
# tracking; even ones when trajectory.csv reaches a random number of lines); after each kill the
# folder must
# read back (`p4track eval` on what was left), and `track --resume` must end with the files of an
# uninterrupted run, byte for byte (trajectory.csv, detections.csv, events.jsonl, score.json).
# Prints one line per kill and a summary; exits 1 if any kill fails. Needs a release build.
#   scripts/kill_resume.sh [N=20] [SEED=1] [OUT=out/kill_resume]
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-20}"
seed="${2:-1}"
out="${3:-out/kill_resume}"
p4track=./build/release/apps/p4track/p4track
[ -x "$p4track" ] || { echo "build first: scripts/build.sh --target p4track" >&2; exit 2; }
rm -rf "$out"
mkdir -p "$out"
"$p4track" simulate --out "$out/sim" --points 3 --seed "$seed" > /dev/null 2>&1
sources=("$out/sim/cam0.mp4" "$out/sim/cam1.mp4")
start=$(date +%s.%N)
"$p4track" track --rig "$out/sim/rig.yaml" --out "$out/whole" "${sources[@]}" > /dev/null 2>&1
lines=$(wc -l < "$out/whole/trajectory.csv")
span=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
echo "uninterrupted run: $span s, $lines trajectory lines"
files=(trajectory.csv detections.csv events.jsonl score.json)
failed=0
RANDOM=$seed
for i in $(seq 1 "$n"); do
  run="$out/killed_$i"
  "$p4track" track --rig "$out/sim/rig.yaml" --out "$run" "${sources[@]}" > "$run.log" 2>&1 &
  pid=$!
  if [ $((i % 2)) -eq 1 ]; then
    # A moment anywhere in the run (the whole span, in thousandths).
    moment=$(awk -v s="$span" -v r=$((RANDOM % 1000)) 'BEGIN { printf "%.3f s", s * r / 1000 }')
    sleep "${moment% s}"
  else
    target=$((1 + RANDOM % lines))
    moment="line $target"
    while kill -0 "$pid" 2> /dev/null &&
      [ "$( [ -f "$run/trajectory.csv" ] && wc -l < "$run/trajectory.csv" || echo 0)" -lt "$target" ]; do
      sleep 0.01
    done
  fi
  kill -9 "$pid" 2> /dev/null || true
  wait "$pid" 2> /dev/null || true
  rows=$( [ -f "$run/trajectory.csv" ] && wc -l < "$run/trajectory.csv" || echo 0)
  readback=ok
  if [ -f "$run/trajectory.csv" ] && ! "$p4track" eval --truth "$out/sim" --run "$run" > /dev/null 2>&1; then
    readback=FAILED
  fi
  result=same
  if [ ! -f "$run/run.json" ]; then
    # Killed before the run began (no run.json): nothing to resume, the run is started again.
    result="not begun, run again:"
    "$p4track" track --rig "$out/sim/rig.yaml" --out "$run" "${sources[@]}" >> "$run.log" 2>&1 ||
      result="run FAILED"
  elif ! "$p4track" track --resume "$run" >> "$run.log" 2>&1; then
    result="resume FAILED"
  fi
  if [ "$result" = same ] || [ "$result" = "not begun, run again:" ]; then
    for f in "${files[@]}"; do cmp -s "$out/whole/$f" "$run/$f" || result="$f differs"; done
    [ "$result" = "not begun, run again:" ] && result="not begun (run again): same"
  fi
  case "$result" in *same) ;; *) failed=$((failed + 1)) ;; esac
  [ "$readback" = ok ] || failed=$((failed + 1))
  printf "kill %2d at %-10s: %5d trajectory lines left, read back %s, after --resume: %s\n" \
    "$i" "$moment" "$rows" "$readback" "$result"
done
echo "$((n - failed)) of $n kills resumed to the uninterrupted run's files"
[ "$failed" -eq 0 ]
