#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test with CTest (unit and end-to-end; the
# end-to-end tests read ../shared/data in place), then every fuzz target for 10 s (clang, ASan,
# UBSan: fuzz/README.md), then the threaded parts' tests under ThreadSanitizer
# (scripts/sanitize.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --tests
bash scripts/build.sh
ctest --preset release
bash scripts/fuzz.sh --seconds 10
bash scripts/sanitize.sh tsan
