#!/usr/bin/env bash
# Soak benchmark: `p4track track --ui --realtime --loop` over a simulated 3-camera match
# (1280x720 at 60 fps) for MINUTES (default 30), watched by CLIENTS (default 20): one Chromium
# page on the live view and HTTP clients polling as it does. Prints memory over time, late frame
# sets, events lost by the clients and failed requests, writes OUT (JSON), and exits 1 when a
# target is missed (web/bench/soak.mjs). Needs a release build and `scripts/setup.sh --tests`
# (Chromium, playwright-core).
#   scripts/soak.sh [MINUTES=30] [CLIENTS=20] [OUT=out/soak.json]
set -euo pipefail
cd "$(dirname "$0")/.."
p4track="$PWD/build/release/apps/p4track/p4track"
[ -x "$p4track" ] || { echo "build first: scripts/build.sh --target p4track" >&2; exit 2; }
[ -d web/node_modules/playwright-core ] || { echo "run scripts/setup.sh --tests first" >&2; exit 2; }
out="${3:-out/soak.json}"
case "$out" in /*) ;; *) out="$PWD/$out" ;; esac
mkdir -p "$(dirname "$out")"
P4TRACK="$p4track" SOAK_MINUTES="${1:-30}" SOAK_CLIENTS="${2:-20}" SOAK_OUT="$out" \
  CHROMIUM="${CHROMIUM:-$(command -v chromium)}" node web/bench/soak.mjs
