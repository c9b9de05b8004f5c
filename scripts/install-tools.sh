#!/usr/bin/env bash
# Installs what RideLab's build and tests need, skipping what is already there.
# Versions are pinned here and nowhere else (see ../shared/TOOLCHAIN.md for why):
#   Trunk 0.21.14 (later versions need a newer rustc), wasm-bindgen-cli equal to the
#   wasm-bindgen crate pinned in crate/Cargo.toml, Debian's Chromium for the browser tests,
#   Debian's mesa-vulkan-drivers (lavapipe, a Vulkan device on the CPU, for the GPU
#   tests), playwright-core, binaryen (wasm-opt for the page's build; Debian's breaks
#   the wasm) and esbuild (the page's JavaScript bundled and minified) from npm (package-lock.json).
#   No tool is downloaded from outside the package registries.
set -euo pipefail
cd "$(dirname "$0")/.."

TRUNK_VERSION=0.21.14
WASM_BINDGEN_VERSION=$(sed -n 's/^wasm-bindgen = "=\(.*\)"$/\1/p' crate/Cargo.toml)

say() { printf '\n== %s\n' "$*"; }

if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  say "adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

if ! trunk --version 2>/dev/null | grep -qx "trunk $TRUNK_VERSION"; then
  say "installing trunk $TRUNK_VERSION (10 to 18 minutes on 2 cores)"
  cargo install --locked trunk --version "$TRUNK_VERSION"
fi

if ! wasm-bindgen --version 2>/dev/null | grep -q "^wasm-bindgen $WASM_BINDGEN_VERSION\b"; then
  say "installing wasm-bindgen-cli $WASM_BINDGEN_VERSION (about 4 minutes)"
  # --locked fails: one of its locked dependencies is missing from the registry.
  cargo install wasm-bindgen-cli --version "$WASM_BINDGEN_VERSION" --force
fi

if [ ! -x /usr/bin/chromium ]; then
  say "installing Debian's Chromium"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q chromium chromium-driver
fi

if ! dpkg-query -W -f='${Status}' mesa-vulkan-drivers 2>/dev/null | grep -q "install ok installed"; then
  say "installing Mesa's Vulkan drivers (lavapipe: the GPU tests run on the CPU)"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q mesa-vulkan-drivers
fi

if [ ! -d node_modules/playwright-core ] || [ ! -x node_modules/.bin/wasm-opt ] || [ ! -d node_modules/esbuild ]; then
  say "installing playwright-core, binaryen's wasm-opt and esbuild (npm ci; no browser download)"
  npm ci --no-audit --no-fund
fi
