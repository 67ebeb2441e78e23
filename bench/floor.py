#!/usr/bin/env python3
"""The floor of paper 004's passage (issue 22 §4): the fewest right-hand sides an 8th-order
explicit method needs at autobal's accuracy, times the cheapest right-hand side, against what
autobal's automatic method spends. Counts, not times: independent of the load on the machine.

What it does (the library example examples/passage.rs, release build):
1. the reference: the passage at rtol 1e-12 (atol 1e-14), and autobal at its defaults (rtol
   1e-8, atol 1e-9, automatic DOP853/RODAS): its error before the peak (max |radius - reference|
   / peak over the samples up to the peak) is the accuracy to match;
2. DOP853 alone (method=dop853) on the ladder 1e-6 … 1e-9 (atol = rtol / 10): the loosest rung
   whose error is no larger; its steps and right-hand sides (12 per accepted step: 11 stages
   and the derivative at the new point, FSAL; rejected steps cost 11 more each);
3. with --callgrind (valgrind installed): the instructions of one right-hand side (the
   `Equations::rhs` total over its calls) and of the whole example at the defaults, so that
   floor = right-hand sides of 2. x instructions per right-hand side, in instructions.

    .venv/bin/python bench/floor.py [--b 2.5] [--dt 0.05] [--callgrind] [--json FILE]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import measure  # noqa: E402
import passage as P  # noqa: E402

LADDER = [1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9]


def error_before_peak(amp, ref, t_peak, dt):
    n = min(len(amp), len(ref))
    t = np.arange(n) * dt
    pre = t <= t_peak
    return float(np.max(np.abs(amp[:n][pre] - ref[:n][pre])) / ref.max())


def callgrind(args):
    """(total instructions, {function: (inclusive instructions, calls)}) of the example."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "cg")
        res = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", P.example_binary()] + args,
                             capture_output=True, text=True, check=True)
        total = int(re.search(r"refs:\s*([\d,]+)", res.stderr).group(1).replace(",", ""))
        ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--tree=caller", out], capture_output=True, text=True).stdout
    # the caller tree: the lines "< caller (Nx)" just above the "* …::rhs" line count its calls
    calls, incl = 0, 0
    lines = ann.splitlines()
    for i, line in enumerate(lines):
        if "*" in line and "Equations as autobal::ode::System>::rhs" in line:
            incl = int(line.split()[0].replace(",", ""))
            j = i - 1
            while j >= 0 and "<" in lines[j]:
                c = re.search(r"\((\d[\d,]*)x\)", lines[j])
                if c:
                    calls += int(c.group(1).replace(",", ""))
                j -= 1
            break
    return total, {"rhs": (incl, calls)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--b", type=float, default=2.5)
    ap.add_argument("--dt", type=float, default=0.05)
    ap.add_argument("--callgrind", action="store_true")
    ap.add_argument("--json")
    a = ap.parse_args()
    b, t_end, dt = a.b, 600.0 / a.b, a.dt
    _, ref, amp_ref = P.run_autobal(0.0, b, t_end, dt, 1e-12, 1e-14)
    _, auto, amp = P.run_autobal(0.0, b, t_end, dt, 1e-8, 1e-9)
    t_peak = ref["t_at_peak"]
    target = error_before_peak(amp, amp_ref, t_peak, dt)
    report = {"problem": f"paper 004 passage, b = {b} 1/s^2 from rest, {t_end:g} s, samples every {dt} s",
              "autobal_auto": {k: auto[k] for k in ("steps", "implicit_steps", "switches", "rejected_steps", "rhs_evaluations")},
              "target_error_before_peak": target, "dop853_ladder": []}
    chosen = None
    for rtol in LADDER:
        _, s, amp = P.run_autobal(0.0, b, t_end, dt, rtol, rtol / 10, method="dop853")
        e = error_before_peak(amp, amp_ref, t_peak, dt)
        row = {"rtol": rtol, "error_before_peak": e, **{k: s[k] for k in ("steps", "rejected_steps", "rhs_evaluations")}}
        report["dop853_ladder"].append(row)
        print(f"DOP853 rtol {rtol:g}: error {e:.3g} (target {target:.3g}), {s['steps']} steps, {s['rhs_evaluations']} rhs", file=sys.stderr)
        if e <= target:
            chosen = row
            break
    report["dop853_at_target"] = chosen
    if chosen:
        # the fewest right-hand sides: 12 per accepted step (FSAL), none for the rejected
        report["floor_rhs"] = 12 * chosen["steps"]
    if a.callgrind:
        total, f = callgrind([f"b={b}", f"t_end={t_end!r}", f"dt={dt}"])
        incl, calls = f["rhs"]
        per = incl / calls if calls else None
        report["callgrind"] = {"example_instructions": total, "rhs_instructions": incl, "rhs_calls": calls, "instructions_per_rhs": per}
        if chosen and per:
            report["floor_instructions"] = report["floor_rhs"] * per
            report["example_over_floor"] = total / report["floor_instructions"]
            report["rhs_of_auto_instructions"] = auto["rhs_evaluations"] * per
    print(json.dumps(report, indent=2))
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(report, fh, indent=2)


if __name__ == "__main__":
    main()
