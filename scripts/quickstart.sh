#!/usr/bin/env bash
# From a fresh Debian 12 machine to a rendered picture: installs the dependencies, builds
# every program (scripts/build.sh: the same build scripts/run-tests.sh uses) and renders
# examples/spheres.ray to build/spheres.png, leaving nothing outside build/.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
"$here/scripts/install-deps.sh"
"$here/scripts/build.sh"
"$here/build/rayshade/rayshade" -O "$here/build/spheres.png" "$here/examples/spheres.ray"
echo "Wrote $here/build/spheres.png"
