"""Cost of the Python API against the CLI on the same sweep, and Python's overhead per call.

The sweep: 10 000 short passages of paper 004's rotor (0.5 s of a run-up from 250 rad/s at
100 1/s², through the resonance at 288 rad/s), a 100 × 100 grid over planar.c_psi and drive.b,
summaries only. The same points, the same library code, the same summaries (checked equal bit
for bit on the physics columns before timing):

- CLI: `autobal sweep --x planar.c_psi=0.05:0.2:100 --y drive.b=50:150:100 --set ...` (CSV
  written as rows arrive);
- Python: `autobal.sweep(problem, axes)` returning a pandas DataFrame.

Runs are paired and interleaved (CLI, Python, CLI, Python, ...), each pair in a random order,
on all cores (the machine is shared: read the spread). Prints the median and min-max of the
ratio Python/CLI. Then the overhead of one call: `simulate_batch` of 1 point against the cost
per point inside a batch of 2000 (threads=1 for both).

    python3 bench/python_sweep.py [--pairs 7] [--bin target/release/autobal]

The package must be installed (`pip install ./crates/autobal-py`, a release build) and the CLI
built with the same profile (`cargo build --release -p autobal-cli`).
"""

from __future__ import annotations

import argparse
import os
import random
import statistics
import subprocess
import tempfile
import time

import numpy as np

import autobal

SETS = {"drive.t_end": 0.5, "drive.omega0": 250.0, "integration.dt": 0.5}
X, Y = "planar.c_psi=0.05:0.2:100", "drive.b=50:150:100"


def cli(exe: str, out: str) -> float:
    args = [exe, "sweep", "--x", X, "--y", Y, "--out", out]
    for k, v in SETS.items():
        args += ["--set", f"{k}={v}"]
    t = time.perf_counter()
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t


def python(problem) -> float:
    t = time.perf_counter()
    autobal.sweep(problem, [X, Y])
    return time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", type=int, default=7)
    ap.add_argument("--bin", default=os.environ.get("AUTOBAL_BIN", "target/release/autobal"))
    a = ap.parse_args()
    problem = autobal.PlanarProblem(set=SETS)
    tmp = tempfile.mkdtemp()
    out = os.path.join(tmp, "sw")
    # same results first
    cli(a.bin, out)
    import pandas as pd

    c = pd.read_csv(out + ".csv")
    p = autobal.sweep(problem, [X, Y])
    cols = ["planar.c_psi", "drive.b", *autobal.SUMMARY_COLUMNS]
    assert c[cols].to_numpy().tobytes() == p[cols].to_numpy().tobytes(), "CLI and Python differ"
    ratios, tc, tp = [], [], []
    for _ in range(a.pairs):
        order = [0, 1]
        random.shuffle(order)
        t = {}
        for o in order:
            t[o] = cli(a.bin, out) if o == 0 else python(problem)
        tc.append(t[0])
        tp.append(t[1])
        ratios.append(t[1] / t[0])
    print(f"10 000 passages, {a.pairs} interleaved pairs on {os.cpu_count()} cores")
    print(f"CLI    median {statistics.median(tc):.3f} s (min {min(tc):.3f}, max {max(tc):.3f})")
    print(f"Python median {statistics.median(tp):.3f} s (min {min(tp):.3f}, max {max(tp):.3f})")
    print(f"ratio Python/CLI median {statistics.median(ratios):.3f} (min {min(ratios):.3f}, max {max(ratios):.3f})")
    # overhead of one call
    paths = ["planar.c_psi"]
    one = np.array([[0.1]])
    many = np.full((2000, 1), 0.1)
    autobal.simulate_batch(problem, paths, one, threads=1)
    reps = 200
    t = time.perf_counter()
    for _ in range(reps):
        autobal.simulate_batch(problem, paths, one, threads=1)
    per_call = (time.perf_counter() - t) / reps
    t = time.perf_counter()
    autobal.simulate_batch(problem, paths, many, threads=1)
    per_point = (time.perf_counter() - t) / len(many)
    print(f"one call of simulate_batch with 1 point: {1e6 * per_call:.0f} µs; a point inside a batch: {1e6 * per_point:.0f} µs; overhead per call {1e6 * (per_call - per_point):.0f} µs")


if __name__ == "__main__":
    main()
