#!/usr/bin/env bash
# Installs every Debian package SMART-DDS needs to build, test and benchmark.
# A no-op (no apt call at all) when everything is already installed, so `make test` stays fast.
# Runs as root (CI) or through sudo when available.
# --agent: only what an agent-only build needs (a robot, docs/lab.md): no Simbody, Chromium,
# node, test or benchmark libraries.
set -euo pipefail

agent_packages=(
  build-essential cmake ninja-build pkg-config git
  cyclonedds-dev cyclonedds-tools libddsc0debian
  libeigen3-dev libyaml-cpp-dev libspdlog-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libi2c-dev openssl libssl-dev
)
if [ "${1:-}" = "--agent" ]; then
  packages=("${agent_packages[@]}")
else
packages=(
  build-essential cmake ninja-build pkg-config git
  cyclonedds-dev cyclonedds-tools
  libsimbody-dev libeigen3-dev libboost-dev
  libyaml-cpp-dev libspdlog-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libi2c-dev
  libfastrtps-dev
  clang-tidy clang
  openssl libssl-dev libddsc0debian
  libcpp-httplib-dev
  libzstd-dev zlib1g-dev
  chromium
  python3-matplotlib
  iproute2 nftables
  gdb
  linux-perf valgrind
)
# The web viewer's build and browser tests need node and npm; a machine may already have them
# from elsewhere (NodeSource), whose nodejs conflicts with Debian's npm package.
if ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "install-deps: missing packages (${missing[*]}) and not root; run this script as root" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
