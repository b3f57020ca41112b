#!/usr/bin/env bash
# Tests under the sanitizers; exits 1 on any report or failure.
#   scripts/sanitize.sh [tsan|asan|all]   (default tsan: what CI runs)
# tsan: the threaded parts under ThreadSanitizer: the camera pool (track), the live hub and the
#       web server (server), the frame-set reader's reconnecting sources (pipeline). Builds the
#       `tsan` preset (those tests only; about 4.5 minutes cold on 2 cores).
# asan: every library's unit tests (core to eval) and the segmenter's rendered scenes under
#       ASan and UBSan, optimised (`asan` preset, those targets only; about 14 minutes cold on 2
#       cores, so not in CI; 5.4 minutes to run).
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-tsan}"
case "$mode" in tsan | asan | all) ;; *)
  echo "usage: scripts/sanitize.sh [tsan|asan|all] (got '$mode')" >&2
  exit 2
  ;;
esac
export CCACHE_DIR="${CCACHE_DIR:-$HOME/.cache/ccache}"

# Runs build/PRESET/BIN with a gtest filter; the tests run from the project's root, as CTest
# runs them.
run() {
  local preset="$1" bin="build/$1/$2" filter="$3"
  "$bin" --gtest_filter="$filter" --gtest_brief=1 ||
    { echo "sanitize ($preset): ${bin##*/} FAILED" >&2; exit 1; }
  echo "sanitize ($preset): ${bin##*/} ($filter): no report"
}

if [[ "$mode" == tsan || "$mode" == all ]]; then
  cmake --preset tsan > /dev/null
  cmake --build --preset tsan -j "$(nproc)"
  export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$PWD/scripts/tsan.supp"
  run tsan src/p4/track/p4_track_test 'FrameSetTrackerTest.ThreadsChangeNothingButTheSpeed'
  run tsan src/p4/server/p4_server_test '*'
  run tsan src/p4/pipeline/p4_pipeline_test 'FrameSetReader*'
fi

if [[ "$mode" == asan || "$mode" == all ]]; then
  cmake --preset asan > /dev/null
  cmake --build --preset asan -j "$(nproc)"
  export ASAN_OPTIONS="detect_leaks=1 abort_on_error=1"
  export UBSAN_OPTIONS="print_stacktrace=1 halt_on_error=1"
  for lib in core segment geometry sync game sim track io eval; do
    run asan "src/p4/$lib/p4_${lib}_test" '*'
  done
  run asan src/p4/segment/p4_segment_scene_test '*'
fi
