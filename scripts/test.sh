#!/usr/bin/env bash
# Runs every test: Rust unit, integration and doc tests, the wasm build of the page,
# and the browser end-to-end suite in headless Chromium.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-tools.sh

echo "== Rust unit, integration and doc tests (the GPU tests on lavapipe: required, not skipped)"
RIDELAB_REQUIRE_GPU=1 cargo test --workspace

# `cargo test` has built the native CLI too (target/debug/ridelab, for tests/cli.rs): the
# end-to-end suite compares the page with it. A separate `cargo build` would rebuild the
# dependencies with other features (no dev-dependencies) for about 2 minutes.
test -x target/debug/ridelab

echo "== wasm build of the page (trunk build --release --offline)"
trunk build --release --offline

echo "== browser end-to-end tests (headless Chromium)"
RIDELAB_CLI="$PWD/target/debug/ridelab" npm run --silent test:e2e
