#!/usr/bin/env bash
# Rewrites the documented sample outputs with what the commands print today: the command
# samples (`<!-- sample -->` blocks in README.md and docs/*.md) and docs/validation.md through
# crates/cli/tests/doc_samples.rs, the Python sessions (`<!-- sample: python -->`) through
# crates/python/tests/test_doc_samples.py (when the package is built into .venv:
# bash scripts/python-package.sh). Review the diff before committing it.
# Usage: bash scripts/bless-docs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
echo "== command samples and docs/validation.md"
FLEXRIG_BLESS=1 cargo test --release --workspace --test doc_samples
if [ -x .venv/bin/python ] && .venv/bin/python -c "import flexrig" 2>/dev/null; then
  echo "== Python sessions"
  (cd crates/python && FLEXRIG_BLESS=1 "$root/.venv/bin/python" -m pytest -p no:cacheprovider -q \
    tests/test_doc_samples.py)
else
  echo "== Python sessions skipped: no flexrig package in .venv (bash scripts/python-package.sh)"
fi
git --no-pager diff --stat -- README.md docs
