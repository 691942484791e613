#!/usr/bin/env bash
# The main job: set up a fresh machine, build the wasm, and serve the page on 127.0.0.1.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build-wasm.sh
PORT="${PORT:-8080}"
echo "swarf is at http://127.0.0.1:$PORT/ (the sample part is loaded; Ctrl-C stops)"
exec python3 -m http.server "$PORT" --bind 127.0.0.1 --directory www
