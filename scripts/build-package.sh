#!/usr/bin/env bash
# Builds swarf's npm package: the wasm (scripts/build-wasm.sh, unless --no-wasm: then the one
# in www/pkg is packed), the package folder (scripts/package.mjs → target/package/swarf/) and
# its tarball, target/package/swarf-X.Y.Z.tgz, which a portal installs with
# `npm install ./swarf-X.Y.Z.tgz`. Nothing is published.
set -euo pipefail
cd "$(dirname "$0")/.."
[ "${1:-}" = "--no-wasm" ] || bash scripts/build-wasm.sh
node scripts/package.mjs
cd target/package
rm -f swarf-*.tgz
npm pack ./swarf --pack-destination . --silent
# The tarball gzipped again by zopfli where scripts/setup.sh installed it: the same tar, 2 %
# smaller than npm's gzip, read by npm as any .tgz.
if command -v zopfli >/dev/null; then
  for t in swarf-*.tgz; do
    gunzip -c "$t" > "${t%.tgz}.tar" && zopfli --i5 -c "${t%.tgz}.tar" > "$t.new" && mv "$t.new" "$t"
    rm -f "${t%.tgz}.tar"
  done
fi
ls -l swarf-*.tgz
