#!/usr/bin/env bash
# Installs the Node.js tools the tests use (the Khronos glTF validator, pinned in scripts/gltf_validate/).
# Idempotent and quiet: does nothing when node is absent (the validator test then skips) or when the
# packages are already installed; otherwise runs `npm ci` from the lock file.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prefix="$root/scripts/gltf_validate"

if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  echo "setup_node.sh: node/npm not found; the glTF validator test will be skipped" >&2
  exit 0
fi
if [ -f "$prefix/node_modules/gltf-validator/package.json" ]; then
  exit 0
fi
npm ci --prefix "$prefix" --no-audit --no-fund --loglevel=error >/dev/null
