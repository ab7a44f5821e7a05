"""Shared fixtures: the repository's scenes and the `flexrig` CLI the package is checked against.

The CLI is found at $FLEXRIG_BIN, else at $CARGO_TARGET_DIR/release/flexrig, else at
target/release/flexrig. Without it the comparisons skip, unless FLEXRIG_REQUIRE_ALL=1 (set by
scripts/python-package.sh, so CI fails instead); the same holds for the Dask tests.
"""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
SCENES = ROOT / "assets" / "scenes"
REQUIRE_ALL = os.environ.get("FLEXRIG_REQUIRE_ALL") == "1"


def scene_path(name: str) -> Path:
    return SCENES / f"{name}.toml"


def missing(what: str) -> None:
    if REQUIRE_ALL:
        pytest.fail(f"{what} is missing (FLEXRIG_REQUIRE_ALL=1)")
    pytest.skip(f"{what} is missing")


def _cli_path():
    candidates = []
    if os.environ.get("FLEXRIG_BIN"):
        candidates.append(Path(os.environ["FLEXRIG_BIN"]))
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    if not target.is_absolute():
        target = ROOT / target
    candidates.append(target / "release" / "flexrig")
    return next((c for c in candidates if c.is_file()), None)


class Cli:
    def __init__(self, path: Path):
        self.path = path

    def __call__(self, *args: str, check: bool = True) -> subprocess.CompletedProcess:
        result = subprocess.run([str(self.path), *map(str, args)], capture_output=True, text=True)
        if check and result.returncode != 0:
            raise AssertionError(f"flexrig {' '.join(map(str, args))} failed: {result.stderr}")
        return result

    def json(self, *args: str):
        return json.loads(self(*args, "--json").stdout)


@pytest.fixture(scope="session")
def cli() -> Cli:
    path = _cli_path()
    if path is None:
        missing("the flexrig CLI (cargo build --release; or set FLEXRIG_BIN)")
    return Cli(path)
