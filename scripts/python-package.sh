#!/usr/bin/env bash
# Builds the Python package `flexrig` (crates/python: PyO3 + maturin, abi3) into the project's
# virtual environment .venv and runs its pytest suite (crates/python/tests). Never touches the
# system interpreter.
#   1. bash scripts/python-env.sh --package   .venv with maturin, numpy, pandas, pytest, dask
#                                             (skipped with --no-env: .venv already made)
#   2. cargo build --release --workspace --bins
#                                             the CLI the tests compare against, and nothing
#                                             else: the build of the README's first command
#                                             (`cargo run --release`), so nothing to do after it
#                                             or after `cargo test --release --workspace` (as in
#                                             CI); the whole workspace, so that its features are
#                                             those of both README commands and the libraries
#                                             are shared with them
#   3. maturin develop --release              the extension, on the same release build as
#                                             both README commands (same CARGO_TARGET_DIR,
#                                             PYO3_PYTHON, the features of
#                                             crates/python/Cargo.toml's alignment section and,
#                                             from .cargo/config.toml, PYO3_BUILD_EXTENSION_MODULE)
#   4. pytest crates/python/tests             with FLEXRIG_REQUIRE_ALL=1: the comparisons with the
#                                             CLI and the Dask tests fail instead of skipping
# Usage: bash scripts/python-package.sh [--no-env] [pytest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
if [ "${1:-}" = "--no-env" ]; then
  shift
else
  bash scripts/python-env.sh --package
fi
[ -x .venv/bin/maturin ] || { echo "no maturin in .venv: run bash scripts/python-env.sh --package"; exit 1; }
export VIRTUAL_ENV="$root/.venv"
export PATH="$VIRTUAL_ENV/bin:$PATH"
export PYO3_PYTHON="$VIRTUAL_ENV/bin/python"
target=${CARGO_TARGET_DIR:-$root/target}
case "$target" in /*) ;; *) target="$root/$target" ;; esac

echo "== cargo build --release --workspace --bins (the CLI)"
cargo build --release --workspace --bins
echo "== maturin develop --release (crates/python into .venv)"
(cd crates/python && maturin develop --release)
echo "== pytest crates/python/tests"
cd crates/python
FLEXRIG_BIN="$target/release/flexrig" FLEXRIG_REQUIRE_ALL=1 \
  python -m pytest -p no:cacheprovider -q -rfEs tests "$@"
