#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test with CTest (unit and end-to-end; the
# end-to-end tests read ../shared/data in place).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --tests
bash scripts/build.sh
ctest --preset release
