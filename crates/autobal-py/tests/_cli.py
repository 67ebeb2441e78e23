"""The `autobal` binary for the tests that compare Python with the CLI: $AUTOBAL_BIN, else the
debug build cargo makes (target/debug/autobal). Without it a test is skipped, unless
AUTOBAL_REQUIRE_PYTHON is set (scripts/test.sh sets it), where it fails."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


def binary() -> str:
    exe = os.environ.get("AUTOBAL_BIN", str(ROOT / "target" / "debug" / "autobal"))
    if not Path(exe).exists():
        if os.environ.get("AUTOBAL_REQUIRE_PYTHON"):
            raise FileNotFoundError(f"{exe}: build the CLI first (cargo build -p autobal-cli)")
        pytest.skip("needs the autobal binary")
    return exe


def cli(*args: str) -> subprocess.CompletedProcess:
    """`autobal ARGS…` run in $TMPDIR (default /tmp); fails the test on a non-zero exit."""
    out = subprocess.run([binary(), *args], capture_output=True, text=True, cwd=os.environ.get("TMPDIR", "/tmp"))
    assert out.returncode == 0, out.stderr
    return out
