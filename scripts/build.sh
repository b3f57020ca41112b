#!/usr/bin/env bash
# Configures and builds P4 (Release, tests on) into build/release with ccache.
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_DIR="${CCACHE_DIR:-$HOME/.cache/ccache}"
cmake --preset release > /dev/null
cmake --build --preset release -j "$(nproc)" "$@"
