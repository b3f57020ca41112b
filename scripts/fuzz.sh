#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, the `fuzz` preset: clang with ASan and UBSan) and runs each
# on its corpus, for a bounded time or number of runs; prints one line per target (executions,
# executions per second, new inputs) and exits 1 on the first crash, leak or sanitizer report
# (the input is kept in build/fuzz/artifacts/). New inputs go to build/fuzz/corpus/, not to the
# repository's fuzz/corpus/ (copy the ones worth keeping by hand).
#   scripts/fuzz.sh                  # 30 s per target
#   scripts/fuzz.sh --seconds 10     # CI
#   scripts/fuzz.sh --runs 1000000   # the README's figures
set -euo pipefail
cd "$(dirname "$0")/.."
limit=(-max_total_time=30)
case "${1:-}" in
  --seconds) limit=(-max_total_time="$2") ;;
  --runs) limit=(-runs="$2") ;;
  "") ;;
  *) echo "usage: scripts/fuzz.sh [--seconds N | --runs N]" >&2; exit 2 ;;
esac
export CCACHE_DIR="${CCACHE_DIR:-$HOME/.cache/ccache}"
cmake --preset fuzz > /dev/null
cmake --build --preset fuzz -j "$(nproc)"
bin=build/fuzz/fuzz
mkdir -p build/fuzz/artifacts
for target in rig_file color_classes calib_files run_files segment; do
  work="build/fuzz/corpus/$target"
  mkdir -p "$work"
  log="build/fuzz/$target.log"
  if ! "$bin/${target}_fuzz" "$work" "fuzz/corpus/$target" "${limit[@]}" -max_len=4096 \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="build/fuzz/artifacts/${target}-" > "$log" 2>&1; then
    echo "fuzz: $target FAILED (log: $log)" >&2
    grep -E "ERROR|SUMMARY|Test unit written|==[0-9]+==" "$log" | head -20 >&2
    exit 1
  fi
  runs=$(awk '/stat::number_of_executed_units/ { print $2 }' "$log")
  speed=$(awk '/stat::average_exec_per_sec/ { print $2 }' "$log")
  added=$(awk '/stat::new_units_added/ { print $2 }' "$log")
  printf "fuzz: %-14s %10s runs, %6s/s, %4s new inputs, no crash\n" "$target" "$runs" "$speed" "$added"
done
