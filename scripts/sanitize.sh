#!/usr/bin/env bash
# The threaded parts under ThreadSanitizer: the camera pool (track), the live hub and the web
# server (server), the frame-set reader's reconnecting sources (pipeline). Builds the `tsan`
# preset (those tests only) and runs them; exits 1 on any data race or failure.
#   scripts/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_DIR="${CCACHE_DIR:-$HOME/.cache/ccache}"
cmake --preset tsan > /dev/null
cmake --build --preset tsan -j "$(nproc)"
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$PWD/scripts/tsan.supp"
# The tests run from the project's root, as CTest runs them.
for t in src/p4/track/p4_track_test:'FrameSetTrackerTest.ThreadsChangeNothingButTheSpeed' \
  src/p4/server/p4_server_test:'*' src/p4/pipeline/p4_pipeline_test:'FrameSetReader*'; do
  bin="build/tsan/${t%%:*}"
  "$bin" --gtest_filter="${t#*:}" --gtest_brief=1 ||
    { echo "sanitize: ${bin##*/} FAILED" >&2; exit 1; }
  echo "sanitize: ${bin##*/} (${t#*:}): no data race"
done
