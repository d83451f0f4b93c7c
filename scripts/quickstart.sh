#!/usr/bin/env bash
# From a fresh Debian 12 machine to a rendered picture: installs the dependencies, builds
# rayshade, and renders examples/spheres.ray to spheres.png in the current directory.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
"$here/scripts/install-deps.sh"
cmake -S "$here" -B "$here/build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$here/build" -j"$(nproc 2>/dev/null || echo 2)" --target rayshade
"$here/build/rayshade/rayshade" -O spheres.png "$here/examples/spheres.ray"
echo "Wrote $(pwd)/spheres.png"
