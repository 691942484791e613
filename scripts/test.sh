#!/usr/bin/env bash
# Runs every test: the habits (fmt, clippy, doc), native (cargo test), the pipeline in headless Chromium (wasm-bindgen-test),
# and the page end to end (Playwright driving Chromium, rs274 checking the downloaded G-code).
# Installs what the tests need first (scripts/setup.sh skips what is already there).
set -euo pipefail
cd "$(dirname "$0")/.."
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# Each stage's time, printed as it ends and together at the end (a fresh run must stay well
# inside CI's 90 minutes: the slowest stages and tests are named there).
times=()
stage_name=""
stage_start=$SECONDS
end_stage() { if [ -n "$stage_name" ]; then times+=("$(printf '%5d s  %s' $((SECONDS - stage_start)) "$stage_name")"); printf '\033[1m-- %s: %d s\033[0m\n' "$stage_name" $((SECONDS - stage_start)); fi; }
step() { end_stage; stage_name="$*"; stage_start=$SECONDS; printf '\n\033[1m== %s\033[0m\n' "$*"; }

step "setup"
bash scripts/setup.sh

# A stage that fails is named and the run goes on, so that one failing test binary or stage
# hides none of the rest; the run fails at the end, listing every failure.
failed_stages=()
run() { last_ok=1; if ! "$@" 2>&1 | tee -a "$log"; then last_ok=0; failed_stages+=("$stage_name: $*"); fi; }

step "the habits: formatting, lints, docs (cargo fmt, clippy, doc)"
run cargo fmt --check
run cargo clippy --all-targets -- -D warnings
RUSTDOCFLAGS="-D warnings" run cargo doc --no-deps --quiet

step "native tests (cargo test)"
# --no-fail-fast: every test binary runs though an earlier one failed.
run cargo test --no-fail-fast --lib --bins --tests

step "the pipeline in headless Chromium (wasm-bindgen-test)"
# The runner gives a test 20 s by default; a loaded machine can need more.
WASM_BINDGEN_TEST_TIMEOUT=${WASM_BINDGEN_TEST_TIMEOUT:-600} run cargo test --target wasm32-unknown-unknown --test web

step "the page end to end (Playwright + Chromium + rs274)"
run bash scripts/build-wasm.sh
if [ "$last_ok" = 1 ]; then run node --test tests/e2e/; fi
end_stage

echo
echo "stage times:"
printf '%s\n' "${times[@]}"
# The slowest page tests (node's TAP: a test's duration follows its "ok" line).
echo "slowest page tests:"
awk '/^ *(not )?ok [0-9]+ - / { sub(/^ *(not )?ok [0-9]+ - /, ""); name = $0 } /duration_ms:/ && name != "" { printf "%8.1f s  %s\n", $2 / 1000, name; name = "" }' "$log" | grep -v '/tests/e2e/' | sort -rn | head -8 || true

# One closing line over all three runners.
read -r passed failed < <(awk '
  /test result: / { for (i = 1; i <= NF; i++) { if ($(i+1) ~ /^passed/) p += $i; if ($(i+1) ~ /^failed/) f += $i } }
  /^# pass / { p += $3 } /^# fail / { f += $3 }
  END { print p + 0, f + 0 }' "$log")
if [ ${#failed_stages[@]} -gt 0 ] || [ "$failed" -gt 0 ]; then
  echo
  echo "what failed:"
  printf '  stage  %s\n' "${failed_stages[@]}"
  grep -E '^test .* \.\.\. FAILED$|^ *not ok [0-9]+ - ' "$log" | sed 's/^ */  test   /' || true
fi
# A stage that failed without a test counted as failing (a build, a lint) still fails the run.
[ ${#failed_stages[@]} -eq 0 ] || [ "$failed" -gt 0 ] || failed=${#failed_stages[@]}
echo
echo "all tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
