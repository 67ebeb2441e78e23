"""Cost of the Python API against the CLI on the same sweep, and Python's overhead per call.

The sweep: 10 000 short passages of paper 004's rotor (0.5 s of a run-up from 250 rad/s at
100-200 1/s², through the resonance at 288 rad/s to 300-350 rad/s), a 100 × 100 grid over
planar.c_psi and drive.b, summaries only. The same points, the same library code, the same summaries (checked equal bit
for bit on the physics columns before timing):

- CLI: `autobal sweep --x planar.c_psi=0.05:0.2:100 --y drive.b=50:150:100 --set ...` (CSV
  written as rows arrive);
- Python: `autobal.sweep(problem, axes)` returning a pandas DataFrame.

Runs are paired and interleaved (CLI, Python, CLI, Python, ...), each pair in a random order,
on all cores (the machine is shared: read the spread). Prints the median and min-max of the
ratio Python/CLI of the wall time and of the CPU time (user + system, all threads: less
sensitive to other work on the machine). Then the overhead of one call: `simulate_batch` of 1
point against the cost per point inside a batch of 2000 (threads=1 for both).

    python3 bench/python_sweep.py [--pairs 7] [--bin target/release/autobal] [--overhead-only]

The package must be a release build, as the CLI is (`cargo build --release -p autobal-cli`): the
script prints `_autobal.build_info()` and refuses a dev-profile extension (what scripts/test.sh
installs into .venv) unless `--allow-dev-extension` (its figures then marked DEV-EXTENSION). A
release wheel for benchmarking: docs/notes/benchmarks.md, "Reproduce" (`PYTHONPATH=DIR`).
"""

from __future__ import annotations

import argparse
import os
import random
import resource
import statistics
import subprocess
import tempfile
import time

import numpy as np

import autobal

import sys  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import measure  # noqa: E402

SETS = {"drive.t_end": 0.5, "drive.omega0": 250.0, "integration.dt": 0.5}
X, Y = "planar.c_psi=0.05:0.2:100", "drive.b=100:200:100"


def cli(exe: str, out: str) -> tuple[float, float]:
    """Wall and CPU time (s) of the CLI's sweep."""
    args = [exe, "sweep", "--x", X, "--y", Y, "--out", out]
    for k, v in SETS.items():
        args += ["--set", f"{k}={v}"]
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


def python(problem) -> tuple[float, float]:
    """Wall and CPU time (s) of the same sweep through the Python API."""
    c = time.process_time()
    t = time.perf_counter()
    autobal.sweep(problem, [X, Y])
    return time.perf_counter() - t, time.process_time() - c


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", type=int, default=7)
    measure.add_args(ap)
    ap.add_argument("--bin", default=os.environ.get("AUTOBAL_BIN", "target/release/autobal"))
    ap.add_argument("--overhead-only", action="store_true", help="only the cost per call")
    measure.add_extension_args(ap)
    a = ap.parse_args()
    sess = measure.Session("python_sweep", allow_loaded=a.allow_loaded)
    build, ok = measure.check_extension("python_sweep", a.allow_dev_extension)
    if not ok:
        raise SystemExit("python_sweep.py: the autobal extension is not a release build (--allow-dev-extension to time it anyway)")
    problem = autobal.PlanarProblem(set=SETS)
    if a.overhead_only:
        overhead(problem)
        return
    tmp = tempfile.mkdtemp()
    out = os.path.join(tmp, "sw")
    # same results first
    cli(a.bin, out)
    import pandas as pd

    c = pd.read_csv(out + ".csv")
    p = autobal.sweep(problem, [X, Y])
    cols = ["planar.c_psi", "drive.b", *autobal.SUMMARY_COLUMNS]
    assert c[cols].to_numpy().tobytes() == p[cols].to_numpy().tobytes(), "CLI and Python differ"
    runs = {0: [], 1: []}  # (wall, cpu) of the CLI and of Python
    for _ in range(a.pairs):
        order = [0, 1]
        random.shuffle(order)
        for o in order:
            runs[o].append(cli(a.bin, out) if o == 0 else python(problem))
    print(f"10 000 passages, {a.pairs} interleaved pairs on {os.cpu_count()} cores, load average at the end {os.getloadavg()[0]:.1f}")

    def spread(v: list) -> str:
        return f"median {statistics.median(v):.3f} (min {min(v):.3f}, max {max(v):.3f})"

    for k, name in ((0, "wall"), (1, "CPU")):
        c, p = [r[k] for r in runs[0]], [r[k] for r in runs[1]]
        print(f"{name:4}: CLI {spread(c)} s; Python {spread(p)} s; ratio Python/CLI {spread([y / x for x, y in zip(c, p)])}")
    overhead(problem)
    report = {"extension": build, "cli_wall_s": [r[0] for r in runs[0]], "cli_cpu_s": [r[1] for r in runs[0]],
              "python_wall_s": [r[0] for r in runs[1]], "python_cpu_s": [r[1] for r in runs[1]]}
    measure.write_table(a.json, report, sess.finish(report))


def overhead(problem) -> None:
    """Python's cost per call: `simulate_batch` of 1 point against a point inside a batch of
    2000 (threads=1 for both), wall and CPU time, repeated 5 times interleaved."""
    paths = ["planar.c_psi"]
    one = np.array([[0.1]])
    many = np.full((2000, 1), 0.1)
    autobal.simulate_batch(problem, paths, one, threads=1)
    reps = 200
    rows = []
    for _ in range(5):
        w, c = time.perf_counter(), time.process_time()
        for _ in range(reps):
            autobal.simulate_batch(problem, paths, one, threads=1)
        call = ((time.perf_counter() - w) / reps, (time.process_time() - c) / reps)
        w, c = time.perf_counter(), time.process_time()
        autobal.simulate_batch(problem, paths, many, threads=1)
        point = ((time.perf_counter() - w) / len(many), (time.process_time() - c) / len(many))
        rows.append((call, point))
    for k, name in ((0, "wall"), (1, "CPU")):
        calls = [1e6 * r[0][k] for r in rows]
        points = [1e6 * r[1][k] for r in rows]
        extra = [a - b for a, b in zip(calls, points)]
        print(
            f"{name:4}: one call of simulate_batch with 1 point {statistics.median(calls):.0f} µs; a point inside a batch "
            f"{statistics.median(points):.0f} µs; overhead per call median {statistics.median(extra):.0f} µs (min {min(extra):.0f}, max {max(extra):.0f})"
        )

if __name__ == "__main__":
    main()
