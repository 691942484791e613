#!/usr/bin/env bash
# Installs everything swarf needs on a fresh Debian machine of this kind, skipping what is there.
# Called by scripts/serve.sh and scripts/test.sh; safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

# The CLI must equal the crate pinned in Cargo.toml / Cargo.lock.
WASM_BINDGEN_VERSION=$(sed -n 's/^wasm-bindgen = "=\([0-9.]*\)"/\1/p' Cargo.toml 2>/dev/null || true)
: "${WASM_BINDGEN_VERSION:=0.2.130}"

say() { printf '\033[1m[setup]\033[0m %s\n' "$*"; }

# The habits the tests hold (scripts/test.sh): rustfmt and clippy.
for component in rustfmt clippy; do
  if ! rustup component list --installed | grep -q "^$component"; then
    say "adding $component"
    rustup component add "$component"
  fi
done

if ! rustup target list --installed | grep -q '^wasm32-unknown-unknown$'; then
  say "adding the wasm32 target"
  rustup target add wasm32-unknown-unknown
fi

if ! command -v wasm-bindgen >/dev/null || [ "$(wasm-bindgen --version | awk '{print $2}')" != "$WASM_BINDGEN_VERSION" ]; then
  say "installing wasm-bindgen-cli $WASM_BINDGEN_VERSION (several minutes, once)"
  # --locked fails on this registry (see shared/TOOLCHAIN.md); the version pin is what matters.
  cargo install wasm-bindgen-cli --version "$WASM_BINDGEN_VERSION" --force
fi

apt_missing=()
command -v chromium >/dev/null || apt_missing+=(chromium)
command -v chromedriver >/dev/null || apt_missing+=(chromium-driver)
# zopfli: the npm package's wasm gzipped smallest (scripts/package.mjs, build-package.sh).
command -v zopfli >/dev/null || apt_missing+=(zopfli)
# FreeCAD's own Python (its Quantity parser): the oracle the FreeCAD tool-bit reader is held to
# (tests/tool_library.rs).
[ -d /usr/lib/freecad-python3/lib ] || apt_missing+=(freecad-python3)
if [ "${SWARF_SKIP_LINUXCNC:-0}" != 1 ] && ! command -v rs274 >/dev/null; then apt_missing+=(linuxcnc-uspace); fi
if [ ${#apt_missing[@]} -gt 0 ]; then
  say "installing Debian packages: ${apt_missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${apt_missing[@]}"
fi

# binaryen from npm (Debian's wasm-opt breaks the module), playwright-core (no browser download)
# TypeScript (to check the module's types) and the bundlers a portal of the npm package uses (esbuild, Vite, webpack).
if [ ! -x node_modules/.bin/wasm-opt ] || [ ! -d node_modules/playwright-core ] || [ ! -x node_modules/.bin/tsc ] || [ ! -d node_modules/typescript-5.0 ] || [ ! -x node_modules/.bin/esbuild ] || [ ! -x node_modules/.bin/vite ] || [ ! -x node_modules/.bin/webpack ]; then
  say "installing npm packages"
  if [ -f package-lock.json ]; then npm ci --no-audit --no-fund; else npm install --no-audit --no-fund; fi
fi
# ezdxf, the DXF reader tests/dxf_spec.rs holds swarf's to, in the project's own venv (Debian's
# python3 needs python3-venv for it); pinned so its readings stay put.
EZDXF_VERSION=1.4.5
if ! .venv/bin/python -c "import ezdxf, sys; sys.exit(ezdxf.__version__ != '$EZDXF_VERSION')" 2>/dev/null; then
  say "installing ezdxf $EZDXF_VERSION (the DXF tests' oracle)"
  rm -rf .venv
  if ! python3 -m venv .venv >/dev/null 2>&1; then
    say "installing Debian packages: python3-venv"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    apt-get install -y -q --no-install-recommends python3-venv
    rm -rf .venv
    python3 -m venv .venv
  fi
  .venv/bin/pip install -q "ezdxf==$EZDXF_VERSION"
fi
# OpenCAMLib, whose drop cutter tests/setups.rs holds each setup's program to (the shared
# tools' gcheck.py), in the same venv; pinned as ezdxf is.
OCL_VERSION=2023.1.11
if ! .venv/bin/python -c "import opencamlib" 2>/dev/null; then
  say "installing opencamlib $OCL_VERSION (the setups' gouge oracle)"
  .venv/bin/pip install -q "opencamlib==$OCL_VERSION"
fi
# numpy-stl, which the shared tools' gsim.py reads a part with (BENCHMARKS.md's gouge and
# material-left figures); pinned as the others are.
NUMPY_STL_VERSION=4.1.1
if ! .venv/bin/python -c "import stl" 2>/dev/null; then
  say "installing numpy-stl $NUMPY_STL_VERSION (gsim.py's reader)"
  .venv/bin/pip install -q "numpy-stl==$NUMPY_STL_VERSION"
fi
say "ready"
