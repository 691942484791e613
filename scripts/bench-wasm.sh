#!/usr/bin/env bash
# Runs the wasm benchmarks in headless Chromium and prints their figures (see BENCHMARKS.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh >/dev/null
WASM_BINDGEN_TEST_TIMEOUT=${WASM_BINDGEN_TEST_TIMEOUT:-600} cargo test --release --target wasm32-unknown-unknown --test bench_wasm -- --nocapture 2>&1 | grep -E '^\||die |wasm |test result'
