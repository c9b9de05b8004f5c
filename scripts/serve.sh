#!/usr/bin/env bash
# Builds the explorer (wasm + static page into dist/) and serves it on http://127.0.0.1:8080
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-tools.sh
# npm's wasm-opt (binaryen) for Trunk's release build.
export PATH="$PWD/node_modules/.bin:$PATH"
exec trunk serve --release --offline
