"""How every bench/ script measures: the load on the machine, CPU time beside wall time, and a
refusal to publish numbers taken on a loaded machine.

Rules (docs/notes/benchmarks.md):
- the 1-, 5- and 15-minute load averages are printed (to stderr) before and after the run;
- a run is LOADED when the 1-minute load average, before or after, is above 1 per core
  (`os.cpu_count()`): other work then shares the cores and slows the two sides of a comparison
  by different amounts (a Python process more than a short Rust one);
- a LOADED run prints `LOADED` and its figures, but writes no result table (no --json/--table
  file) unless `--allow-loaded` is given, and then the table says LOADED;
- a script that times the Python extension (`import autobal`) prints how it was built
  (`_autobal.build_info()`, `extension_build`) and refuses to time a dev-profile one (opt-level
  1, debug assertions: what scripts/test.sh installs into .venv) against the release CLI unless
  `--allow-dev-extension` is given, and then its figures say DEV-EXTENSION; a release wheel for
  benchmarking: docs/notes/benchmarks.md, "Reproduce";
- CPU time (user + system) is reported beside every wall time: of this process
  (`time.process_time`, all its threads) for in-process work, of the finished child processes
  (`resource.getrusage(RUSAGE_CHILDREN)`) for commands. CPU time does not count the time a
  process waits for a core, so it moves less with the load than wall time (it still moves:
  caches and frequency are shared).

Use:
    from measure import Session, run_cmd, cpu_of
    s = Session("passage", allow_loaded=args.allow_loaded)      # prints the load before
    wall, cpu = run_cmd([exe, ...])                               # one child process
    (wall, cpu), result = cpu_of(lambda: solve_ivp(...))          # in-process work
    s.finish(report)          # prints the load after, adds "conditions" to report; False if
                              # LOADED and not allowed (the caller then writes no table)
"""

from __future__ import annotations

import datetime
import os
import platform
import resource
import subprocess
import sys
import time


def cores() -> int:
    """Logical processors of this machine (what `nproc` prints without affinity limits)."""
    return os.cpu_count() or 1


def cpu_model() -> str:
    """The processor's model name from /proc/cpuinfo (Linux), else platform's guess."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def loadavg() -> tuple[float, float, float]:
    """The 1-, 5- and 15-minute load averages."""
    return os.getloadavg()


def is_loaded(load1: float) -> bool:
    """The rule: a 1-minute load average above 1 per core."""
    return load1 > cores()


def children_cpu() -> float:
    """User + system seconds of all finished, waited-for child processes so far."""
    u, s = children_cpu_split()
    return u + s


def children_cpu_split() -> tuple[float, float]:
    """User and system seconds, apart, of all finished, waited-for child processes so far (the
    system part is the kernel's: page faults, writes)."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime, r.ru_stime


# (user, system) CPU seconds of the last `run_cmd`'s command, for scripts that report them apart
last_split: tuple[float, float] = (0.0, 0.0)


def run_cmd(cmd, **kw) -> tuple[float, float]:
    """Run `cmd` to completion (output discarded unless `kw` says otherwise): its wall time and
    its CPU time (user + system, all its threads and children), in seconds; the two apart in
    `last_split`."""
    kw.setdefault("stdout", subprocess.DEVNULL)
    kw.setdefault("stderr", subprocess.DEVNULL)
    global last_split
    u0, s0 = children_cpu_split()
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, **kw)
    wall = time.perf_counter() - t0
    u1, s1 = children_cpu_split()
    last_split = (u1 - u0, s1 - s0)
    return wall, last_split[0] + last_split[1]


def cpu_of(fn):
    """((wall, cpu), fn()) for in-process work: wall clock and this process's CPU time."""
    c0 = time.process_time()
    t0 = time.perf_counter()
    out = fn()
    return (time.perf_counter() - t0, time.process_time() - c0), out


def median_spread(xs) -> dict:
    """Median, min and max of a list of numbers (None for an empty list)."""
    xs = sorted(x for x in xs if x is not None)
    if not xs:
        return {"median": None, "min": None, "max": None}
    n = len(xs)
    med = xs[n // 2] if n % 2 else 0.5 * (xs[n // 2 - 1] + xs[n // 2])
    return {"median": med, "min": xs[0], "max": xs[-1]}


class Session:
    """One benchmark run: prints the load before at construction and after at `finish`."""

    def __init__(self, name: str, allow_loaded: bool = False):
        self.name = name
        self.allow_loaded = allow_loaded
        self.start = datetime.datetime.now(datetime.timezone.utc)
        self.before = loadavg()
        self.wall0 = time.perf_counter()
        self.cpu0 = time.process_time() + children_cpu()
        print(f"[{name}] {self.start:%Y-%m-%d %H:%M} UTC, {cores()} cores ({cpu_model()}), "
              f"load average before {self.before[0]:.2f} {self.before[1]:.2f} {self.before[2]:.2f}", file=sys.stderr)
        if is_loaded(self.before[0]):
            print(f"[{name}] LOADED: 1-minute load {self.before[0]:.2f} > {cores()} (1 per core) at the start", file=sys.stderr)

    def conditions(self) -> dict:
        """Date, machine, load before/after and the verdict, for a result table."""
        after = loadavg()
        loaded = is_loaded(self.before[0]) or is_loaded(after[0])
        return {
            "date_utc": f"{self.start:%Y-%m-%d %H:%M}",
            "machine": f"{cores()} cores, {cpu_model()}",
            "cores": cores(),
            "load_before": [round(x, 2) for x in self.before],
            "load_after": [round(x, 2) for x in after],
            "loaded": loaded,
            "script_wall_s": time.perf_counter() - self.wall0,
            "script_cpu_s": time.process_time() + children_cpu() - self.cpu0,
        }

    def finish(self, report: dict | None = None) -> bool:
        """Print the load after; put the conditions into `report`. True when the figures may be
        written as a result table: the run was quiet, or --allow-loaded was given."""
        c = self.conditions()
        if report is not None:
            report["conditions"] = c
        a = c["load_after"]
        print(f"[{self.name}] load average after {a[0]:.2f} {a[1]:.2f} {a[2]:.2f}; "
              f"script {c['script_wall_s']:.1f} s wall, {c['script_cpu_s']:.1f} s CPU (this process and its children)", file=sys.stderr)
        if c["loaded"]:
            print(f"[{self.name}] LOADED: the 1-minute load average was above 1 per core ({cores()}); "
                  + ("figures kept because of --allow-loaded, marked LOADED" if self.allow_loaded else "no result table written (--allow-loaded to keep it)"),
                  file=sys.stderr)
            return self.allow_loaded
        return True


def extension_build() -> dict:
    """How the imported `autobal` extension was compiled: `_autobal.build_info()` (profile,
    opt_level, debug_assertions, debug_info) with `file` (the extension's path) and `release`:
    True for opt-level 3 without debug assertions, the settings of the release CLI. An extension
    from before `build_info` is reported as not release (its build is unknown)."""
    from autobal import _autobal

    info = {"file": _autobal.__file__}
    if hasattr(_autobal, "build_info"):
        info.update(_autobal.build_info())
        info["release"] = info["opt_level"] == "3" and not info["debug_assertions"]
    else:
        info.update(profile="unknown (no build_info: an older wheel)", release=False)
    return info


def check_extension(name: str, allow_dev: bool) -> tuple[dict, bool]:
    """Print how the imported autobal extension was built (stderr); (its `extension_build()`,
    True when it may be timed: a release build, or `allow_dev` (--allow-dev-extension), then
    marked DEV-EXTENSION)."""
    info = extension_build()
    flags = "" if "opt_level" not in info else (f", opt-level {info['opt_level']}, debug assertions {'on' if info['debug_assertions'] else 'off'}, "
                                                f"debug info {'on' if info['debug_info'] else 'off'}")
    print(f"[{name}] autobal extension {info['file']}: profile {info['profile']}{flags}", file=sys.stderr)
    if info["release"]:
        return info, True
    print(f"[{name}] DEV-EXTENSION: not a release build, so its timings are not comparable with the release CLI's; "
          + ("timed anyway because of --allow-dev-extension, marked DEV-EXTENSION" if allow_dev else
             "not timed (a release wheel: docs/notes/benchmarks.md, Reproduce; --allow-dev-extension to time it anyway)"), file=sys.stderr)
    return info, allow_dev


def add_args(ap) -> None:
    """The options every bench script shares: --allow-loaded and --json FILE (the result table)."""
    ap.add_argument("--allow-loaded", action="store_true", help="write the result table even if the load average was above 1 per core (marked LOADED)")
    ap.add_argument("--json", metavar="FILE", help="write the result table (JSON) to FILE; refused for a LOADED run without --allow-loaded")


def add_extension_args(ap) -> None:
    """The option of the scripts that time the Python extension: --allow-dev-extension."""
    ap.add_argument("--allow-dev-extension", action="store_true",
                    help="time the autobal extension even if it is not a release build (marked DEV-EXTENSION; see docs/notes/benchmarks.md)")


def write_table(path: str | None, report: dict, ok: bool) -> None:
    """Write `report` as JSON to `path` if given and allowed."""
    import json

    if path and ok:
        with open(path, "w") as f:
            json.dump(report, f, indent=2)
        print(f"wrote {path}", file=sys.stderr)
    elif path:
        print(f"not written: {path} (LOADED)", file=sys.stderr)


def strip_args(argv):
    """For scripts with positional arguments: take --allow-loaded, --allow-dev-extension and
    --json FILE out of `argv` (in place) and return them as an object with .allow_loaded,
    .allow_dev_extension and .json."""
    class Opts:
        allow_loaded = False
        allow_dev_extension = False
        json = None

    o = Opts()
    rest = [argv[0]]
    it = iter(argv[1:])
    for a in it:
        if a == "--allow-loaded":
            o.allow_loaded = True
        elif a == "--allow-dev-extension":
            o.allow_dev_extension = True
        elif a == "--json":
            o.json = next(it, None)
        elif a.startswith("--json="):
            o.json = a.split("=", 1)[1]
        else:
            rest.append(a)
    argv[:] = rest
    return o
