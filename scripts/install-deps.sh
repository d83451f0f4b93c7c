#!/usr/bin/env bash
# Installs what building and testing need on a Debian 12 machine (run as root, or with sudo
# available). Safe to run again: packages already present are left alone.
set -euo pipefail

packages=(build-essential cmake cpp python3 libpng-dev zlib1g-dev libgtest-dev googletest)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q "${missing[@]}"
