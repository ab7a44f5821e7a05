#!/usr/bin/env bash
# Makes (or refreshes) the project's Python virtual environment at .venv (never the system
# interpreter) with what the independent checks use:
#   mcap, mcap-protobuf-support  the MCAP check (scripts/check_mcap.py, run by `cargo test`)
#   numpy, scipy, mpmath         the peer/reference scripts (flexrig bench, scripts/*.py)
# Usage: bash scripts/python-env.sh [--minimal]   (--minimal: only the MCAP check's packages)
# The tests find it at .venv/bin/python, or wherever FLEXRIG_PYTHON points.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v python3 >/dev/null || { echo "python3 is not installed: the Python checks will skip"; exit 1; }
[ -x .venv/bin/python ] || python3 -m venv .venv
packages=(mcap mcap-protobuf-support)
[ "${1:-}" = "--minimal" ] || packages+=(numpy scipy mpmath)
.venv/bin/python -m pip install -q --disable-pip-version-check "${packages[@]}"
echo "Python environment ready: $(pwd)/.venv (${packages[*]})"
