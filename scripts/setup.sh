#!/usr/bin/env bash
# Installs what the project needs on a fresh Debian/Ubuntu machine: the system libraries Bevy
# builds against, Mesa's software Vulkan and Xvfb for headless rendering, and cargo-nextest.
# Safe to re-run: it installs only what is missing.
set -euo pipefail

packages=(pkg-config libudev-dev libwayland-dev libxkbcommon-dev libvulkan1 mesa-vulkan-drivers xvfb xauth)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

if ! cargo nextest --version >/dev/null 2>&1; then
  cargo install --locked cargo-nextest
fi
