#!/usr/bin/env python3
"""Scaling of the parallel commands (issue 22, item 6): `map`, `sweep` and `basins` on 1 and 2
threads, a Dask `LocalCluster` sweep's throughput per worker against the CLI's per core, and
the peak memory of a process against the number of points (it should be flat: results are
streamed to disk, not held).

What it runs (release binary, `--exe`):
- threads: each command with `--threads 1` and `--threads T` (T = 2 by default, `--threads`),
  paired and interleaved (1, T, T, 1, ...: the order alternates), `--repeats` pairs. For each
  run: wall time, CPU time (user + system of that process, all its threads) and peak resident
  memory (`ru_maxrss` of that child, from `os.wait4`). Reported per command: the speed-up
  wall(1)/wall(T) (median and min-max over the pairs) and the parallel overhead cpu(T)/cpu(1)
  (1 when the threads do no extra work). On a machine with fewer free cores than T the
  speed-up measures the load, not the program: the run is then LOADED (bench/measure.py).
  - `map --threads N --x dimensionless.z_a=-2:2:G --y omega=0.05:4.5:G` (G = 300: 90 000 cells);
  - `sweep --threads N`, G × G short passages of paper 004's rotor (0.5 s of a run-up through
    the resonance, bench/python_sweep.py's sweep; G = 40: 1 600 passages);
  - `basins --threads N --config examples/spatial.toml --n G --set drive.t_end=200` (G = 16:
    256 runs of the spatial rotor).
- memory: the same commands on 1 thread at growing grids (points × 1, × 4, × 16): peak RSS
  against the number of points, and the growth per point (kB) between the smallest and the
  largest grid.
- Dask (when `autobal` and `dask.distributed` import, else skipped with the reason): the same
  sweep as the CLI's (`autobal.sweep(problem, axes, client=client)`) on a `LocalCluster` of
  W = 1 and T worker processes, one thread each; wall time and the workers' CPU time (psutil,
  read on each worker before and after) per run, the cluster's start-up reported apart.
  Throughput per worker = points / wall / W, against the CLI's per core = points / wall of
  `sweep --threads 1`; and points per CPU second of each. The extension must be a release
  build, as the CLI is: the script prints `_autobal.build_info()` and skips the Dask section
  for a dev-profile extension (what scripts/test.sh installs into .venv: opt-level 1, debug
  assertions; 2.8 times the instructions per passage of this sweep) unless
  `--allow-dev-extension`, which marks its rows DEV-EXTENSION. To time a release wheel (docs/notes/benchmarks.md, "Reproduce"):
  `PYTHONPATH=DIR .venv/bin/python bench/scaling.py`, DIR holding
  `pip install --no-deps --target DIR` of a wheel from `maturin build --release`.

The load average before and after, CPU time beside wall time, LOADED flagging and the JSON table
follow bench/measure.py.

    .venv/bin/python bench/scaling.py [--exe target/release/autobal] [--threads 2] [--repeats 3]
        [--quick] [--no-dask] [--json FILE] [--allow-loaded] [--allow-dev-extension]
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import measure  # noqa: E402

SWEEP_SETS = ["drive.t_end=0.5", "drive.omega0=250", "integration.dt=0.5"]


def run_child(cmd, cwd) -> dict:
    """One child process to completion: wall s, CPU s (user + system of this child alone) and
    peak RSS in MB (`ru_maxrss`, kB on Linux), from `os.wait4`."""
    with tempfile.TemporaryFile() as errf:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=errf)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
        if p.returncode != 0:
            errf.seek(0)
            err = errf.read().decode(errors="replace")
            raise SystemExit(f"scaling.py: {' '.join(cmd)} failed ({p.returncode}): {err.strip()[-400:]}")
    return {"wall_s": wall, "cpu_s": ru.ru_utime + ru.ru_stime, "rss_mb": ru.ru_maxrss / 1024.0}


def commands(exe: str, grid: dict) -> dict:
    """name -> (function of the thread count -> argv, points)."""
    gm, gs, gb = grid["map"], grid["sweep"], grid["basins"]
    spatial = os.path.join(ROOT, "examples", "spatial.toml")
    sweep_sets = [a for s in SWEEP_SETS for a in ("--set", s)]
    return {
        "map": (lambda t, out: [exe, "map", "--threads", str(t), "--x", f"dimensionless.z_a=-2:2:{gm}", "--y", f"omega=0.05:4.5:{gm}", "--out", out], gm * gm),
        "sweep": (lambda t, out: [exe, "sweep", "--threads", str(t), "--x", f"planar.c_psi=0.05:0.2:{gs}", "--y", f"drive.b=100:200:{gs}", *sweep_sets, "--out", out], gs * gs),
        "basins": (lambda t, out: [exe, "basins", "--threads", str(t), "--config", spatial, "--n", str(gb), "--set", "drive.t_end=200", "--out", out + ".csv"], gb * gb),
    }


def threads_section(exe, grid, threads, repeats, work) -> dict:
    out = {}
    for name, (argv, points) in commands(exe, grid).items():
        runs = {1: [], threads: []}
        run_child(argv(1, os.path.join(work, name)), work)  # warm the page cache
        for k in range(repeats):
            for t in ((1, threads) if k % 2 == 0 else (threads, 1)):
                runs[t].append(run_child(argv(t, os.path.join(work, f"{name}{t}")), work))
        speedup = [a["wall_s"] / b["wall_s"] for a, b in zip(runs[1], runs[threads])]
        overhead = [b["cpu_s"] / a["cpu_s"] for a, b in zip(runs[1], runs[threads])]
        row = {
            "points": points,
            "threads": [1, threads],
            "wall_s": {t: measure.median_spread([r["wall_s"] for r in runs[t]]) for t in runs},
            "cpu_s": {t: measure.median_spread([r["cpu_s"] for r in runs[t]]) for t in runs},
            "rss_mb": {t: measure.median_spread([r["rss_mb"] for r in runs[t]]) for t in runs},
            "speedup_wall": measure.median_spread(speedup),
            "cpu_ratio": measure.median_spread(overhead),
        }
        out[name] = row
        w1, wt = row["wall_s"][1]["median"], row["wall_s"][threads]["median"]
        c1, ct = row["cpu_s"][1]["median"], row["cpu_s"][threads]["median"]
        print(f"{name:7} {points:7d} points: 1 thread {w1:.3f} s wall {c1:.3f} s CPU; {threads} threads {wt:.3f} s wall {ct:.3f} s CPU; "
              f"speed-up {row['speedup_wall']['median']:.2f} ({row['speedup_wall']['min']:.2f}-{row['speedup_wall']['max']:.2f}), "
              f"CPU {threads} / 1 thread {row['cpu_ratio']['median']:.2f}", file=sys.stderr)
    return out


def memory_section(exe, grid, work) -> dict:
    """Peak RSS on 1 thread at the grid, twice and four times its side (1, 4, 16 × the points)."""
    out = {}
    for name in ("map", "sweep", "basins"):
        rows = []
        for f in (1, 2, 4):
            g = {k: v * f for k, v in grid.items()}
            argv, points = commands(exe, g)[name]
            r = run_child(argv(1, os.path.join(work, f"mem-{name}")), work)
            rows.append({"points": points, "rss_mb": r["rss_mb"], "wall_s": r["wall_s"], "cpu_s": r["cpu_s"]})
            print(f"{name:7} {points:8d} points: peak RSS {r['rss_mb']:.1f} MB ({r['cpu_s']:.2f} s CPU)", file=sys.stderr)
        growth = (rows[-1]["rss_mb"] - rows[0]["rss_mb"]) * 1024.0 / (rows[-1]["points"] - rows[0]["points"])
        out[name] = {"runs": rows, "growth_kb_per_point": growth, "largest_over_smallest": rows[-1]["rss_mb"] / rows[0]["rss_mb"]}
        print(f"{name:7} peak RSS grows {growth:.3f} kB per point ({rows[-1]['rss_mb'] / rows[0]['rss_mb']:.2f}x over {rows[-1]['points'] // rows[0]['points']}x the points)", file=sys.stderr)
    return out


def dask_section(exe, grid, threads, repeats, work, cli_rows, allow_dev=False) -> dict:
    try:
        import autobal
        import psutil
        from dask.distributed import Client, LocalCluster
    except ImportError as e:
        print(f"Dask section skipped: {e}", file=sys.stderr)
        return {"skipped": str(e)}
    build, ok = measure.check_extension("scaling", allow_dev)
    if not ok:
        print("Dask section skipped: the autobal extension is not a release build (--allow-dev-extension to time it)", file=sys.stderr)
        return {"skipped": "the autobal extension is not a release build", "extension": build}
    mark = "" if build["release"] else " DEV-EXTENSION"
    gs = grid["sweep"]
    axes = [f"planar.c_psi=0.05:0.2:{gs}", f"drive.b=100:200:{gs}"]
    problem = autobal.PlanarProblem(set={k: float(v) for k, v in (s.split("=") for s in SWEEP_SETS)})
    points = gs * gs

    def worker_cpu():
        t = psutil.Process().cpu_times()
        return t.user + t.system

    out = {"points": points, "workers": {}, "extension": build}
    reference = None
    for w in (1, threads):
        t0 = time.perf_counter()
        with LocalCluster(n_workers=w, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
            startup = time.perf_counter() - t0
            autobal.sweep(problem, axes, client=client)  # warm: imports on the workers
            walls, cpus = [], []
            for _ in range(repeats):
                c0 = sum(client.run(worker_cpu).values())
                t = time.perf_counter()
                table = autobal.sweep(problem, axes, client=client)
                walls.append(time.perf_counter() - t)
                cpus.append(sum(client.run(worker_cpu).values()) - c0)
            cols = list(autobal.SUMMARY_COLUMNS)
            bits = table[cols].to_numpy().tobytes()
            same = reference is None or bits == reference
            reference = reference or bits
        wall = measure.median_spread(walls)
        cpu = measure.median_spread(cpus)
        row = {
            "startup_s": startup,
            "wall_s": wall,
            "workers_cpu_s": cpu,
            "points_per_s_per_worker": points / wall["median"] / w,
            "points_per_cpu_s": points / cpu["median"],
            "same_bits_as_one_worker": same,
        }
        out["workers"][w] = row
        print(f"dask{mark}    {w} worker(s): start-up {startup:.2f} s; sweep {wall['median']:.3f} s wall, workers' CPU {cpu['median']:.3f} s; "
              f"{row['points_per_s_per_worker']:.0f} points/s per worker, {row['points_per_cpu_s']:.0f} per CPU s", file=sys.stderr)
    cli = cli_rows.get("sweep")
    if cli:
        per_core = points / cli["wall_s"][1]["median"]
        per_cpu = points / cli["cpu_s"][1]["median"]
        out["cli_points_per_s_per_core"] = per_core
        out["cli_points_per_cpu_s"] = per_cpu
        for w, row in out["workers"].items():
            row["per_worker_over_cli_per_core"] = row["points_per_s_per_worker"] / per_core
            print(f"dask{mark}    {w} worker(s) per worker / CLI per core (wall): {row['per_worker_over_cli_per_core']:.2f}; "
                  f"per CPU s: {row['points_per_cpu_s'] / per_cpu:.2f}", file=sys.stderr)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "target", "release", "autobal"))
    ap.add_argument("--threads", type=int, default=2, help="the thread (and Dask worker) count compared with 1")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="smaller grids (a check that the script runs, not a measurement)")
    ap.add_argument("--no-dask", action="store_true")
    measure.add_args(ap)
    measure.add_extension_args(ap)
    a = ap.parse_args()
    grid = {"map": 100, "sweep": 12, "basins": 6} if a.quick else {"map": 300, "sweep": 40, "basins": 16}
    sess = measure.Session("scaling", allow_loaded=a.allow_loaded)
    report = {"grid": grid, "threads_compared": [1, a.threads]}
    with tempfile.TemporaryDirectory() as work:
        report["threads"] = threads_section(a.exe, grid, a.threads, a.repeats, work)
        report["memory"] = memory_section(a.exe, grid, work)
        report["dask"] = {"skipped": "--no-dask"} if a.no_dask else dask_section(a.exe, grid, a.threads, a.repeats, work, report["threads"], a.allow_dev_extension)
    ok = sess.finish(report)
    measure.write_table(a.json, report, ok)


if __name__ == "__main__":
    main()
