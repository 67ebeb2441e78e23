"""Running the release CLI and writing configs, for the independent checks."""

from __future__ import annotations

import json
import os
import subprocess
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
AUTOBAL = os.environ.get("AUTOBAL", os.path.join(ROOT, "target", "release", "autobal"))
TMP = tempfile.mkdtemp(prefix="autobal_indep_")


def _f(x):
    return repr(float(x))


def planar_toml(name, *, m1, m2, s1, s2, gamma, r, k=None, c=None, kx=None, ky=None, cx=None,
                cy=None, m3=None, c_psi=None, ball_masses=None, ball_drags=None, n=2,
                omega0=400.0, t_end=20.0, psi0=None, extra=""):
    lst = lambda xs: "[" + ", ".join(_f(x) for x in xs) + "]"
    lines = ["[planar]", f"m1 = {_f(m1)}", f"m2 = {_f(m2)}", f"n = {int(n)}", f"s1 = {_f(s1)}",
             f"s2 = {_f(s2)}", f"gamma = {_f(gamma)}", f"r = {_f(r)}", "c_theta = 0.0",
             "i_g = 0.0025"]
    if k is not None:
        lines += [f"k = {_f(k)}", f"c = {_f(c)}"]
    else:
        lines += [f"k_x = {_f(kx)}", f"k_y = {_f(ky)}", f"c_x = {_f(cx)}", f"c_y = {_f(cy)}"]
    if m3 is not None:
        lines += [f"m3 = {_f(m3)}", f"c_psi = {_f(c_psi)}"]
    else:
        lines += [f"ball_masses = {lst(ball_masses)}", f"ball_drags = {lst(ball_drags)}"]
    lines += ["[drive]", 'kind = "speed"', f"omega0 = {_f(omega0)}", f"t_end = {_f(t_end)}"]
    if psi0 is not None:
        lines += [f"psi0 = {lst(psi0)}"]
    lines += [extra]
    path = os.path.join(TMP, name + ".toml")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def run(args, check=True):
    """Runs the CLI; returns (stdout, stderr, rc)."""
    p = subprocess.run([AUTOBAL, *args], capture_output=True, text=True, cwd=TMP)
    if check and p.returncode != 0:
        raise RuntimeError(f"autobal {' '.join(args)} -> rc {p.returncode}: {p.stderr[-2000:]}")
    return p.stdout, p.stderr, p.returncode


def run_json(args):
    out, err, rc = run([*args, "--format", "json"])
    return json.loads(out), err
