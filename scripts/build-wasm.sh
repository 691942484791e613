#!/usr/bin/env bash
# Builds the wasm module into www/pkg: cargo → wasm-bindgen (the CLI pinned to the crate) →
# wasm-opt from npm's binaryen (Debian's breaks the module; see shared/TOOLCHAIN.md).
set -euo pipefail
cd "$(dirname "$0")/.."
# The target's flags of .cargo/config.toml (SIMD, getrandom's backend), and the build machine's paths left out of
# the module's panic messages (the crates' sources under CARGO_HOME, this checkout): the npm
# package ships this file.
export RUSTFLAGS="-C target-feature=+simd128 --cfg getrandom_backend=\"wasm_js\" --remap-path-prefix=${CARGO_HOME:-$HOME/.cargo}=/cargo --remap-path-prefix=$PWD=/swarf"
# The wasm profile: the release build, the file readers built for size (Cargo.toml).
cargo build --profile wasm --lib --target wasm32-unknown-unknown
wasm-bindgen --target web --no-typescript --out-dir www/pkg target/wasm32-unknown-unknown/wasm/swarf.wasm
# -Os, not -O3: the module 1.5 % smaller (the npm package ships it twice, under 2.5 MB), and the
# sample part's Generate in the page as quick (5.1–5.6 s against 5.3–6.3 s, three runs each).
node_modules/.bin/wasm-opt -Os --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext --enable-mutable-globals --enable-reference-types --enable-multivalue --enable-simd www/pkg/swarf_bg.wasm -o www/pkg/swarf_bg.wasm
ls -l www/pkg/swarf_bg.wasm
node scripts/single-file.mjs
