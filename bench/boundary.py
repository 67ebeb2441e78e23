"""The boundary tracer against autobal's own stability maps of the same plane (issue 22, item 5:
the traced boundary at least 10x cheaper than the verdict map).

The plane is `bench_map`'s (003 Fig. 5a's layout): the 12-state model of 000 eq (6),
z̄_A in [-2, 2] x Ω in [0.05, 4.5], one thread. Each of `verdict` and `margin` (the library's
maps on an N x N grid) and `boundary` (the traced curves, default settings) runs as its own
process of `target/release/examples/bench_boundary`, and so does `none` (the set-up alone),
which is subtracted from each.

Two measures, both independent of wall time:
- instructions (`valgrind --tool=callgrind`, "I refs"): deterministic, the same on a busy and a
  quiet machine (they miss cache misses and system calls: a floor of the cost, not a time);
- CPU time (user + system of the child, `measure.run_cmd`), median of REPS runs, with the load
  average before and after (a LOADED run writes no table without --allow-loaded).

Usage:
    cargo build --release -p autobal --example bench_boundary
    python3 bench/boundary.py [N] [REPS] [--docs] [--json FILE] [--allow-loaded]     (default 400 5)
    (--docs: the default rotor, the plane of the docs' `map --boundary` example)
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(__file__))
from measure import Session, median_spread, run_cmd, strip_args  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "target", "release", "examples", "bench_boundary")
MODES = ["none", "verdict", "margin", "boundary"]


def instructions(mode: str, n: int, extra: list[str]) -> int | None:
    """Instructions of one run of `mode` (callgrind's I refs), or None without valgrind."""
    if not shutil.which("valgrind"):
        return None
    r = subprocess.run(
        ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", EXE, mode, str(n), *extra],
        capture_output=True,
        text=True,
        check=True,
    )
    m = re.search(r"refs:\s*([\d,]+)", r.stderr)
    return int(m.group(1).replace(",", "")) if m else None


def main() -> None:
    docs = "--docs" in sys.argv
    if docs:
        sys.argv.remove("--docs")
    extra = ["docs"] if docs else []
    opts = strip_args(sys.argv)
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 400
    reps = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    if not os.path.exists(EXE):
        sys.exit(f"{EXE} missing: cargo build --release -p autobal --example bench_boundary")
    s = Session("boundary", allow_loaded=opts.allow_loaded)
    report: dict = {"n": n, "reps": reps, "model": "docs" if docs else "bench", "modes": {}}
    for mode in MODES:
        out = subprocess.run([EXE, mode, str(n), *extra], capture_output=True, text=True, check=True).stdout
        cpu = [run_cmd([EXE, mode, str(n), *extra])[1] for _ in range(reps)]
        report["modes"][mode] = {"result": json.loads(out), "instructions": instructions(mode, n, extra), "cpu_s": median_spread(cpu)}
    base = report["modes"]["none"]
    for mode in MODES[1:]:
        m = report["modes"][mode]
        if m["instructions"] is not None and base["instructions"] is not None:
            m["instructions_net"] = m["instructions"] - base["instructions"]
        m["cpu_net_s"] = m["cpu_s"]["median"] - base["cpu_s"]["median"]
    b = report["modes"]["boundary"]
    pts = b["result"]["points"]
    b["per_point"] = {k: b["result"][k] / pts for k in ("evaluations", "corrections") if k in b["result"]}
    ratios = {}
    for mode in ["verdict", "margin"]:
        m = report["modes"][mode]
        if "instructions_net" in m and "instructions_net" in b:
            ratios[f"{mode}_map_over_boundary_instructions"] = m["instructions_net"] / b["instructions_net"]
        ratios[f"{mode}_map_over_boundary_cpu"] = m["cpu_net_s"] / b["cpu_net_s"]
    report["ratios"] = ratios
    ok = s.finish(report)
    print(json.dumps(report, indent=2))
    for k, v in ratios.items():
        print(f"{k}: {v:.1f}", file=sys.stderr)
    if opts.json:
        from measure import write_table

        write_table(opts.json, report, ok)


if __name__ == "__main__":
    main()
