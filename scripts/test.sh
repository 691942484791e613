#!/usr/bin/env bash
# Runs every test: the habits (fmt, clippy, doc), native (cargo test), the pipeline in headless Chromium (wasm-bindgen-test),
# and the page end to end (Playwright driving Chromium, rs274 checking the downloaded G-code).
# Installs what the tests need first (scripts/setup.sh skips what is already there).
set -euo pipefail
cd "$(dirname "$0")/.."
log=$(mktemp)
trap 'rm -f "$log"' EXIT
step() { printf '\n\033[1m== %s\033[0m\n' "$*"; }

step "setup"
bash scripts/setup.sh

step "the habits: formatting, lints, docs (cargo fmt, clippy, doc)"
cargo fmt --check
cargo clippy --all-targets -- -D warnings
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --quiet

step "native tests (cargo test)"
cargo test --lib --bins --tests 2>&1 | tee -a "$log"

step "the pipeline in headless Chromium (wasm-bindgen-test)"
# The runner gives a test 20 s by default; a loaded machine can need more.
WASM_BINDGEN_TEST_TIMEOUT=${WASM_BINDGEN_TEST_TIMEOUT:-600} cargo test --target wasm32-unknown-unknown --test web 2>&1 | tee -a "$log"

step "the page end to end (Playwright + Chromium + rs274)"
bash scripts/build-wasm.sh
node --test tests/e2e/ 2>&1 | tee -a "$log"

# One closing line over all three runners.
read -r passed failed < <(awk '
  /test result: / { for (i = 1; i <= NF; i++) { if ($(i+1) ~ /^passed/) p += $i; if ($(i+1) ~ /^failed/) f += $i } }
  /^# pass / { p += $3 } /^# fail / { f += $3 }
  END { print p + 0, f + 0 }' "$log")
echo
echo "all tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
