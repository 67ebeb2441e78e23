#!/usr/bin/env python3
"""What the command costs beside the physics: each `autobal` command a user runs, as a whole
process, against the library doing the same work in-process (the examples' own clocks around
the library call), in paired, interleaved runs (command, library, command, library, ...).

  simulate  `autobal simulate` (paper 004's passage, CSV + 4 SVG)  vs examples/passage.rs
  map       `autobal map --threads 1 --quantity margin` 400 x 400 (CSV + SVG + PNG)
            vs examples/bench_map.rs's margin map (BENCH_THREADS=1)
  campbell  `autobal campbell --points 200 --omega-max 5 --format json`
            vs examples/bench_campbell.rs's `command` mode: the command's library calls (the
            default config, the tracked modes over the same 200 speeds, balls free, each
            speed's modes checked and kept, the fixed axes' curves and crossings with 1 x Omega),
            one run a process; the crossings are checked equal to the command's JSON first
  sweep     `autobal sweep --threads 1` 20 x 20 short passages (CSV) vs the sum of the runs'
            own in-process times (the CSV's wall_s column)

For each: wall and CPU time of the command's process (getrusage), the library's in-process
wall time and its example's process CPU, the ratios pair by pair (median, min-max): command CPU
/ example process CPU (the figure that holds on a loaded machine) and command wall / library
in-process wall (the one a user sees, quotable only from a quiet run). The goal (issue 22) is a
command within 1.3x of the library. Load and LOADED rule: bench/measure.py.

Usage: python3 bench/commands.py [--runs 7] [--only simulate,map] [--allow-loaded] [--json FILE]
Needs cargo build --release -p autobal-cli and -p autobal --examples.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import measure  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "target", "release", "autobal")
EX = os.path.join(ROOT, "target", "release", "examples")


def lib_json(cmd, env=None):
    """Run an example; (its JSON line, process CPU)."""
    c0 = measure.children_cpu()
    r = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env)
    return json.loads(r.stdout.strip().splitlines()[-1]), measure.children_cpu() - c0


def cases(d):
    env1 = dict(os.environ, BENCH_THREADS="1")
    sweep_out = os.path.join(d, "sw")

    def sweep_lib():
        with open(sweep_out + ".csv") as f:
            return sum(float(r["wall_s"]) for r in csv.DictReader(f))

    return {
        "simulate": ([EXE, "simulate", "--out", os.path.join(d, "sim.csv")],
                     lambda: (lambda j: (j[0]["wall_s"][0], j[1]))(lib_json([os.path.join(EX, "passage")]))),
        # the rotor of bench_map and stability_map.py (bench/stability_map.toml)
        "map": ([EXE, "map", "--config", os.path.join(ROOT, "bench", "stability_map.toml"), "--threads", "1", "--quantity", "margin", "--x", "dimensionless.z_a=-2:2:400", "--y", "omega=0.05:4.5:400",
                 "--out", os.path.join(d, "map")],
                lambda: (lambda j: (j[0]["margin_s"], j[1]))(lib_json([os.path.join(EX, "bench_map"), "400", "400", os.path.join(d, "m.bin"), "maps"], env1))),
        "campbell": ([EXE, "campbell", "--points", "200", "--omega-max", "5", "--format", "json"],
                     lambda: (lambda j: (j[0]["command"]["median_s"], j[1]))(lib_json([os.path.join(EX, "bench_campbell"), "200", "1", "command"]))),
        "sweep": ([EXE, "sweep", "--threads", "1", "--x", "planar.c_psi=0.05:0.2:20", "--y", "drive.b=100:200:20", "--set", "drive.t_end=0.5",
                   "--set", "drive.omega0=250", "--set", "integration.dt=0.5", "--out", sweep_out],
                  lambda: (sweep_lib(), None)),
    }


def same_work(cmd, d):
    """Check that examples/bench_campbell's `command` mode computes the command's diagram: the
    same crossings with 1 x Omega, to the bit (both print the shortest round-trip decimal)."""
    r = subprocess.run(cmd, cwd=d, check=True, capture_output=True, text=True)
    got = [c["omega"] for c in json.loads(r.stdout)["critical_speeds"]]
    lib, _ = lib_json([os.path.join(EX, "bench_campbell"), "200", "1", "command"])
    want = lib["command"]["critical_omega"]
    if got != want:
        sys.exit(f"campbell: the example's crossings {want} are not the command's {got}: not the same work")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--only", help="comma-separated subset of simulate,map,campbell,sweep")
    measure.add_args(ap)
    a = ap.parse_args()
    sess = measure.Session("commands", allow_loaded=a.allow_loaded)
    report = {}
    with tempfile.TemporaryDirectory() as d:
        for name, (cmd, lib) in cases(d).items():
            if a.only and name not in a.only.split(","):
                continue
            measure.run_cmd(cmd, cwd=d)  # warm-up (page cache, fonts)
            if name == "campbell":
                same_work(cmd, d)
            rows = []
            for i in range(a.runs):
                if name == "sweep":  # the library time is read from the command's own output
                    wall, cpu = measure.run_cmd(cmd, cwd=d)
                    lw, lc = lib()
                elif i % 2 == 0:
                    wall, cpu = measure.run_cmd(cmd, cwd=d)
                    lw, lc = lib()
                else:
                    lw, lc = lib()
                    wall, cpu = measure.run_cmd(cmd, cwd=d)
                rows.append({"command_wall_s": wall, "command_cpu_s": cpu, "library_s": lw, "library_process_cpu_s": lc})
            ms = measure.median_spread
            report[name] = {
                "command_wall_s": ms([r["command_wall_s"] for r in rows]),
                "command_cpu_s": ms([r["command_cpu_s"] for r in rows]),
                "library_in_process_s": ms([r["library_s"] for r in rows]),
                "library_process_cpu_s": ms([r["library_process_cpu_s"] for r in rows]),
                # CPU against CPU (both whole processes; the example's includes its start, ~1 ms),
                # wall against the library's in-process wall; for the sweep the runs' own
                # in-process times are all there is (one thread: their wall is their CPU when
                # nothing preempts them)
                # only where the example does the same work as the command: bench_map also maps
                # the verdict and traces the boundary
                "ratio_command_cpu_to_library": ms([r["command_cpu_s"] / (r["library_process_cpu_s"] or r["library_s"]) for r in rows])
                if name in ("simulate", "sweep", "campbell") else {"median": None, "min": None, "max": None,
                                                                   "note": "the example does more work: see bench/instructions.sh"},
                "ratio_command_wall_to_library": ms([r["command_wall_s"] / r["library_s"] for r in rows]),
            }
            r = report[name]
            print(f"{name}: command {r['command_wall_s']['median'] * 1e3:.1f} ms wall, {r['command_cpu_s']['median'] * 1e3:.1f} ms CPU; "
                  f"library {r['library_in_process_s']['median'] * 1e3:.1f} ms (process CPU {(r['library_process_cpu_s']['median'] or 0) * 1e3:.1f} ms); "
                  f"command CPU / library {r['ratio_command_cpu_to_library']['median']}", file=sys.stderr)
    ok = sess.finish(report)
    print(json.dumps(report, indent=2))
    measure.write_table(a.json, report, ok)


if __name__ == "__main__":
    main()
