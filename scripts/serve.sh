#!/usr/bin/env bash
# Builds the explorer (wasm + static page into dist/) and serves it on http://127.0.0.1:8080
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-tools.sh
# npm's wasm-opt (binaryen) for Trunk's release build.
export PATH="$PWD/node_modules/.bin:$PATH"
# The page's crates (wasm-only ones such as wasm-bindgen-futures for the GPU path) are
# fetched first: Trunk builds offline.
cargo fetch --target wasm32-unknown-unknown
exec trunk serve --release --offline
