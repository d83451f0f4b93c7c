#!/usr/bin/env bash
# Installs what building and testing need on a Debian 12 machine (run as root, or with sudo
# available). Safe to run again: packages already present are left alone. Slurm and munge
# are for the render farm's tests (tests/farm), which start their own cluster.
set -euo pipefail

packages=(build-essential cmake cpp python3 libpng-dev zlib1g-dev libgtest-dev googletest)
slurm_packages=(slurmctld slurmd slurm-client munge)
missing=()
missing_slurm=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
for p in "${slurm_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing_slurm+=("$p")
done
if [ ${#missing[@]} -eq 0 ] && [ ${#missing_slurm[@]} -eq 0 ]; then
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
if [ ${#missing[@]} -gt 0 ]; then
  $sudo apt-get install -y -q "${missing[@]}"
fi
# Without recommends (they would add mail and database servers). The package scripts try to
# start the daemons as services and are refused; nothing is left running.
if [ ${#missing_slurm[@]} -gt 0 ]; then
  $sudo apt-get install -y -q --no-install-recommends "${missing_slurm[@]}"
fi
