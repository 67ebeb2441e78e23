#!/usr/bin/env python3
"""Campbell-diagram benchmark: autobal beside ROSS and NumPy, 200 speeds, in paired, interleaved
runs.

What each computes, per speed: every eigenvalue, its mode shape, tracking into lines, and the
whirl direction of each mode.
  autobal: `campbell_stream` (example bench_campbell) on paper 000's base case with masses
           (the default config), balls free (12 states) and locked (8 states).
  ROSS:    `Rotor.run_campbell` on a rotor of comparable size: one Timoshenko shaft element and
           a disk on two bearings (2 nodes x 6 DOF = 24 states; ROSS has no ball balancer, so
           this is not the same model: the comparison is what an engineer would otherwise run
           for a Campbell diagram of a rigid rotor on two supports).
  NumPy:   the same 12-state model as autobal, the stacked state matrices of all speeds
           assembled vectorised and `numpy.linalg.eig` (eigenvalues and vectors) on the stack:
           the floor for any Python tool that needs the mode shapes, before tracking or
           classification.

ROSS is not a test requirement: install it into a separate environment, e.g.
    python3 -m venv .venv-bench && .venv-bench/bin/pip install -r bench/requirements-bench.txt
(on Python 3.11 pip resolves ross-rotordynamics 2.3.0: 3.x needs Python >= 3.12/3.13). Without
ROSS the script compares with NumPy only and says so.

Also the command a user runs, `autobal campbell --points SPEEDS --omega-max 5 --format json`,
as a whole process (wall and CPU). Load average before and after, CPU beside wall, LOADED rule:
bench/measure.py.

Usage: python3 bench/campbell.py [SPEEDS] [REPEATS] [--allow-loaded] [--json FILE]   (default 200 7)
"""
import json
import os
import statistics
import subprocess
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import measure  # noqa: E402

OPTS = measure.strip_args(sys.argv)  # --allow-loaded, --json FILE
SPEEDS = int(sys.argv[1]) if len(sys.argv) > 1 else 200
REPEATS = int(sys.argv[2]) if len(sys.argv) > 2 else 7
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def ross_rotor():
    # ROSS's import prints (CoolProp's REFPROP notice) from C, straight to file descriptor 1:
    # silence the descriptor itself, so that stdout carries only the JSON report
    sys.stdout.flush()
    saved, null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    try:
        import ross as rs
    finally:
        os.dup2(saved, 1)
        os.close(null)
        os.close(saved)
    steel = rs.Material(name="Steel", rho=7810, E=211e9, G_s=81.2e9)
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel)]
    disk = [rs.DiskElement.from_geometry(n=0, material=steel, width=0.07, i_d=0.05, o_d=0.28)]
    brg = [rs.BearingElement(n=0, kxx=1e6, cxx=50.0), rs.BearingElement(n=1, kxx=1e6, cxx=50.0)]
    return rs.Rotor(shaft, disk, brg), rs.__version__


def numpy_campbell(n):
    """All eigenvalues and eigenvectors of the 12-state model at n speeds (stacked eig)."""
    from stability_map import assemble  # the same independent NumPy assembly
    w = 5.0 * (np.arange(n) + 0.5) / n
    t0 = time.perf_counter()
    A = assemble(np.full(n, 0.8), w)
    lam, vec = np.linalg.eig(A)
    return time.perf_counter() - t0


def spread(xs):
    return {"median": statistics.median(xs), "min": min(xs), "max": max(xs)}


def main():
    sess = measure.Session("campbell", allow_loaded=OPTS.allow_loaded)
    cli = os.path.join(ROOT, "target", "release", "autobal")
    cmd_runs, np_cpu = [], []
    subprocess.run(["cargo", "build", "--quiet", "--release", "--example", "bench_campbell", "-p", "autobal"], cwd=ROOT, check=True)
    exe = os.path.join(ROOT, "target", "release", "examples", "bench_campbell")
    try:
        rotor, ross_version = ross_rotor()
        speeds = np.linspace(0.0, 500.0, SPEEDS)
        rotor.run_campbell(speeds[:3], frequencies=8)  # warm-up (numba compilation, caches)
    except Exception as e:  # noqa: BLE001
        rotor, ross_version = None, f"not available ({type(e).__name__}: {e})"
    runs = []
    for r in range(REPEATS):
        t_ross = None
        if rotor is not None:
            t0 = time.perf_counter()
            rotor.run_campbell(speeds, frequencies=8)
            t_ross = time.perf_counter() - t0
        res = subprocess.run([exe, str(SPEEDS), "5"], check=True, capture_output=True, text=True)
        ab = json.loads(res.stdout.strip().splitlines()[-1])
        c0 = time.process_time()
        t_np = numpy_campbell(SPEEDS)
        np_cpu.append(time.process_time() - c0)
        if os.path.exists(cli):
            cmd_runs.append(measure.run_cmd([cli, "campbell", "--points", str(SPEEDS), "--omega-max", "5", "--format", "json"]))
        runs.append((t_ross, ab, t_np))
        print(f"repetition {r + 1}/{REPEATS}: ROSS {t_ross} s, autobal free {ab['free']['median_s']:.4f} s, "
              f"locked {ab['locked']['median_s']:.4f} s, NumPy eig {t_np:.4f} s", file=sys.stderr)
    report = {
        "speeds": SPEEDS,
        "repeats": REPEATS,
        "ross_version": ross_version,
        "seconds": {
            "autobal_free_12_states": spread([a["free"]["median_s"] for _, a, _ in runs]),
            "autobal_locked_8_states": spread([a["locked"]["median_s"] for _, a, _ in runs]),
            "numpy_eig_stack_12_states": spread([t for _, _, t in runs]),
        },
        "ratios_paired": {
            "numpy eig (12 states) / autobal free (12 states)": spread([t / a["free"]["median_s"] for _, a, t in runs]),
        },
        "autobal_speeds_by_continuation": runs[-1][1]["free"]["continued"],
        "autobal_speeds_by_qr": runs[-1][1]["free"]["direct"],
    }
    if rotor is not None:
        report["seconds"]["ross_run_campbell_24_states"] = spread([t for t, _, _ in runs])
        report["ratios_paired"]["ROSS / autobal free"] = spread([t / a["free"]["median_s"] for t, a, _ in runs])
        report["ratios_paired"]["ROSS / autobal locked"] = spread([t / a["locked"]["median_s"] for t, a, _ in runs])
    report["cpu_s"] = {"numpy_eig_stack_12_states": spread(np_cpu)}
    if cmd_runs:
        report["seconds"]["autobal_campbell_command_wall"] = spread([w for w, _ in cmd_runs])
        report["cpu_s"]["autobal_campbell_command"] = spread([c for _, c in cmd_runs])
        report["ratios_paired"]["command wall / library free"] = spread([w / a["free"]["median_s"] for (w, _), (_, a, _) in zip(cmd_runs, runs)])
    ok = sess.finish(report)
    print(json.dumps(report, indent=2))
    measure.write_table(OPTS.json, report, ok)


if __name__ == "__main__":
    main()
