#!/bin/sh
# Trunk build hook: builds the ridelab crate's *library* for the browser and runs
# wasm-bindgen into Trunk's staging directory, giving ridelab.js + ridelab_bg.wasm.
#
# Why not Trunk's rust pipeline: the crate has a cdylib and a native binary both named
# `ridelab`; on wasm32 both are written to ridelab.wasm and Trunk has no `--lib` switch,
# so it finds two artifacts. `cargo build --lib` builds the library alone.
#
# wasm-opt is not run: Debian's binaryen 108 breaks the module (see TOOLCHAIN.md).
# Needs: the wasm32-unknown-unknown target and wasm-bindgen-cli equal to the crate's
# pinned wasm-bindgen version (0.2.130).
set -eu

profile="${TRUNK_PROFILE:-release}"
out="${TRUNK_STAGING_DIR:-dist}"
if [ "$profile" = release ]; then
  flags="--release"
else
  flags=""
fi

# shellcheck disable=SC2086
cargo build $flags --lib --target wasm32-unknown-unknown --manifest-path crate/Cargo.toml

target_dir="$(cargo metadata --format-version 1 --no-deps --manifest-path crate/Cargo.toml \
  | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')"
wasm="$target_dir/wasm32-unknown-unknown/$profile/deps/ridelab.wasm"

want="$(sed -n '/^name = "wasm-bindgen"$/{n;s/^version = "\(.*\)"$/\1/p;}' Cargo.lock)"
have="$(wasm-bindgen --version | sed 's/^wasm-bindgen //; s/ .*//')"
if [ "$want" != "$have" ]; then
  echo "build-wasm.sh: wasm-bindgen-cli is $have but Cargo.lock has wasm-bindgen $want;" >&2
  echo "  install it with: cargo install wasm-bindgen-cli --version $want" >&2
  exit 1
fi

mkdir -p "$out"
wasm-bindgen --target web --no-typescript --out-dir "$out" --out-name ridelab "$wasm"
