#!/usr/bin/env bash
# Makes (or refreshes) the project's Python virtual environment at .venv (never the system
# interpreter) with what the independent checks and the Python package use:
#   mcap, mcap-protobuf-support  the MCAP check (scripts/check_mcap.py, run by `cargo test`)
#   numpy, scipy, mpmath         the peer/reference scripts (flexrig bench, scripts/*.py)
#   maturin, numpy, pandas, pyarrow, pytest, dask[distributed]
#                                building and testing the Python package (crates/python;
#                                scripts/python-package.sh)
#   mujoco, exudyn               the peer codes timed side by side (scripts/peers/*.py), only
#                                with --peers
# Usage: bash scripts/python-env.sh [--minimal | --package | --peers]
#   --minimal  only the MCAP check's packages
#   --package  the MCAP check's and the Python package's (what .ci/run uses)
#   --peers    everything below, and MuJoCo and Exudyn for the side-by-side timings
#   (none)     everything above except the peer codes
# The tests find it at .venv/bin/python, or wherever FLEXRIG_PYTHON points.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v python3 >/dev/null || { echo "python3 is not installed: the Python checks will skip"; exit 1; }
[ -x .venv/bin/python ] || python3 -m venv .venv
packages=(mcap mcap-protobuf-support)
package=("maturin>=1.9,<2" "numpy>=1.22" "pandas>=1.5" "pyarrow" "pytest>=7" "dask[distributed]>=2023.1")
case "${1:-}" in
  --minimal) ;;
  --package) packages+=("${package[@]}") ;;
  "") packages+=(scipy mpmath "${package[@]}") ;;
  --peers) packages+=(scipy mpmath "${package[@]}" mujoco exudyn) ;;
  *) echo "usage: bash scripts/python-env.sh [--minimal | --package | --peers]"; exit 2 ;;
esac
.venv/bin/python -m pip install -q --disable-pip-version-check "${packages[@]}"
echo "Python environment ready: $(pwd)/.venv (${packages[*]})"
