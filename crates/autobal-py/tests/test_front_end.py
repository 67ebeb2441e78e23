"""The wheel as a whole front end (issue 20 §3, §6): the `autobal` command it installs, every
command's JSON equal to the CLI's, the figures of the result objects equal to the report's, the
report from Python equal to the CLI's, and the stubs equal to the module.

The CLI comparisons need the `autobal` binary cargo built: $AUTOBAL_BIN, else target/debug/autobal.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import autobal

ROOT = Path(__file__).resolve().parents[3]
REQUIRE = bool(os.environ.get("AUTOBAL_REQUIRE_PYTHON"))


def binary() -> str:
    exe = os.environ.get("AUTOBAL_BIN", str(ROOT / "target" / "debug" / "autobal"))
    if not Path(exe).exists():
        if REQUIRE:
            raise FileNotFoundError(f"{exe}: build the CLI first (cargo build -p autobal-cli)")
        pytest.skip("needs the autobal binary")
    return exe


def script() -> str:
    """The console script the wheel installed beside this Python."""
    exe = Path(sys.executable).parent / "autobal"
    assert exe.exists(), f"{exe}: the wheel installs the autobal command ([project.scripts])"
    return str(exe)


def run(exe: str, *args: str, cwd=None) -> subprocess.CompletedProcess:
    return subprocess.run([exe, *args], capture_output=True, text=True, cwd=cwd or os.environ.get("TMPDIR", "/tmp"))


@pytest.mark.parametrize(
    "args",
    [
        ("critical",),
        ("critical", "--format", "json", "--set", "dimensionless.l_left=1.2"),
        ("--version",),
        ("stability", "--omega-max", "nope"),
        ("frobnicate",),
    ],
)
def test_the_installed_command_is_the_clis(args):
    # the same stdout, stderr and exit code as the binary cargo built (errors and usage included)
    a, b = run(script(), *args), run(binary(), *args)
    assert (a.returncode, a.stdout, a.stderr) == (b.returncode, b.stdout, b.stderr)
