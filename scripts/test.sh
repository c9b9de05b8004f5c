#!/usr/bin/env bash
# Runs every test: Rust unit, integration and doc tests, the wasm build of the page,
# and the browser end-to-end suite in headless Chromium.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-tools.sh
# npm's wasm-opt (binaryen) for Trunk's release build.
export PATH="$PWD/node_modules/.bin:$PATH"

echo "== Rust unit, integration and doc tests, with the GPU route (on lavapipe without a GPU)"
# Without an adapter the GPU tests print SKIPPED and pass; the CPU path is tested either way.
cargo test --workspace --features ridelab/gpu

# `cargo test` has built the native CLI too (target/debug/ridelab, for tests/cli.rs): the
# end-to-end suite compares the page with it. A separate `cargo build` would rebuild the
# dependencies with other features (no dev-dependencies) for about 2 minutes.
test -x target/debug/ridelab

# The page's crates (wasm-only ones such as wasm-bindgen-futures for the GPU path) are
# fetched first: Trunk builds offline.
cargo fetch --target wasm32-unknown-unknown
echo "== wasm build of the page (trunk build --release --offline)"
trunk build --release --offline

echo "== browser end-to-end tests (headless Chromium)"
RIDELAB_CLI="$PWD/target/debug/ridelab" npm run --silent test:e2e
