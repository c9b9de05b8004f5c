#!/usr/bin/env bash
# Runs every test: Rust unit, integration and doc tests, the wasm build of the page,
# and the browser end-to-end suite in headless Chromium.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-tools.sh

echo "== Rust unit, integration and doc tests"
cargo test --workspace

echo "== native CLI (the end-to-end suite compares the page with it)"
cargo build -p ridelab --bin ridelab

echo "== wasm build of the page (trunk build --release --offline)"
trunk build --release --offline

echo "== browser end-to-end tests (headless Chromium)"
RIDELAB_CLI="$PWD/target/debug/ridelab" npm run --silent test:e2e
