#!/usr/bin/env bash
# Installs every Debian 12 package P4 needs to build, test and run. Idempotent: packages that are
# already installed are left alone, so a second run takes seconds.
#   bash scripts/setup.sh            # build + test dependencies
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config git
  libeigen3-dev
  libopencv-dev libopencv-contrib-dev
  libavformat-dev libavcodec-dev libavdevice-dev libavutil-dev libswscale-dev ffmpeg
  libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libcpp-httplib-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  rtsp-server-perl  # a real RTSP server for the network-camera test
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "setup: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -q
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "setup: done"
