#!/usr/bin/env bash
# The Python that builds the generated parts (scripts/pocket-plate.py, scripts/mould-core.py):
# a venv of its own in target/plate-venv with manifold3d and numpy, pinned, made on first use.
# Prints its path.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=target/plate-venv
if ! "$VENV/bin/python" -c "import manifold3d, numpy" 2>/dev/null; then
  python3 -m venv "$VENV" >&2
  "$VENV/bin/pip" install -q "manifold3d==3.5.4" "numpy==2.4.6" >&2
fi
echo "$PWD/$VENV/bin/python"
