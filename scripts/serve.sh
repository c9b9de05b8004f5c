#!/usr/bin/env bash
# Builds the explorer (wasm + static page into dist/) and serves it on http://127.0.0.1:8080
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-tools.sh
exec trunk serve --release --offline
