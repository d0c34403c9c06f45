#!/usr/bin/env bash
# Writes docs/methods.md from the registry (`shaftlab methods --markdown`). The test
# Docs.MethodsPageMatchesTheRegistry fails when the committed page and the registry differ.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"${SHAFTLAB_BINARY:-$repo/build/shaftlab}" methods --markdown > "$repo/docs/methods.md.tmp"
mv "$repo/docs/methods.md.tmp" "$repo/docs/methods.md"
