#!/usr/bin/env bash
# Installs every Debian 12 package P4 needs to build, test and run, and the web UI's npm packages
# (three.js; playwright-core for the browser tests). Idempotent: what is installed is left alone,
# so a second run takes seconds.
#   bash scripts/setup.sh            # build + run (the web UI included)
#   bash scripts/setup.sh --tests    # and Chromium for the browser tests, clang for the fuzzers
set -euo pipefail
cd "$(dirname "$0")/.."
with_tests=0
[ "${1:-}" = "--tests" ] && with_tests=1

packages=(
  build-essential cmake ninja-build ccache pkg-config git
  libeigen3-dev libceres-dev
  libopencv-dev libopencv-contrib-dev
  libavformat-dev libavcodec-dev libavdevice-dev libavutil-dev libswscale-dev ffmpeg
  libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libcpp-httplib-dev libyaml-cpp-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  rtsp-server-perl  # a real RTSP server for the network-camera test
)
# Node.js and npm for the web UI's three.js: Debian's, unless the machine has a Node.js already.
if ! command -v node > /dev/null || ! command -v npm > /dev/null; then packages+=(nodejs npm); fi
if [ "$with_tests" -eq 1 ]; then packages+=(chromium clang); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
else
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  echo "setup: installing ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -q
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The web UI's packages, exactly as package-lock.json pins them (again only when it changed).
if [ ! -f web/node_modules/.package-lock.json ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
  echo "setup: npm ci in web/"
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
fi
echo "setup: done"
