#!/usr/bin/env bash
# Run the benchmark set and write one markdown table of the results with the conditions they
# were taken under (date, machine, load before/after), medians and spread of paired runs.
#
#   bench/run_all.sh [--quick] [--allow-loaded] [--out FILE.md] [--python PY] [--bench-python PY]
#
#   --quick          the commands against the library and the compiled peers only (minutes);
#                    without it also SciPy (passage, spatial), the stability map and the
#                    Campbell benchmarks (the SciPy ladders take tens of minutes)
#   --allow-loaded   keep the figures of runs whose 1-minute load average was above 1 per core
#                    (marked LOADED); without it such a run's table is not written
#   --out FILE.md    where the table goes (default target/bench/results.md)
#   --python PY      the Python with numpy/scipy (default .venv/bin/python)
#   --bench-python   the Python with the peers (default .venv-bench/bin/python; see
#                    bench/requirements-bench.txt); skipped if absent
#
# Each script prints its load before/after and CPU beside wall (bench/measure.py) to stderr and
# writes its JSON table into target/bench/; the summary below is built from those files. Rules
# and the published results: docs/notes/benchmarks.md.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
QUICK=0; ALLOW=(); OUT="target/bench/results.md"; PY=".venv/bin/python"; BPY=".venv-bench/bin/python"
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) QUICK=1 ;;
    --allow-loaded) ALLOW=(--allow-loaded) ;;
    --out) OUT="$2"; shift ;;
    --python) PY="$2"; shift ;;
    --bench-python) BPY="$2"; shift ;;
    *) echo "unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
D="target/bench"; mkdir -p "$D"; rm -f "$D"/*.json
echo "load before the set: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores" >&2
cargo build --release --quiet -p autobal-cli && cargo build --release --quiet -p autobal --examples || exit 1

run() { # name, python, script args...: runs one benchmark into $D/name.json
  local name="$1" py="$2"; shift 2
  echo "== $name" >&2
  "$py" "$@" "${ALLOW[@]}" --json "$D/$name.json" >"$D/$name.out" || echo "$name: exit $? (see $D/$name.out)" >&2
}
run commands "$PY" bench/commands.py
if [ -x "$BPY" ]; then run peers_passage "$BPY" bench/peers_passage.py; else echo "peers skipped: no $BPY" >&2; fi
if [ "$QUICK" = 0 ]; then
  run passage "$PY" bench/passage.py --methods DOP853,Radau --pairs 3
  run stability_map "$PY" bench/stability_map.py 400 5
  run campbell "$PY" bench/campbell.py 200 7
  run spatial "$PY" bench/spatial.py --case runup --methods DOP853 --pairs 3
fi
echo "load after the set: $(cut -d' ' -f1-3 /proc/loadavg)" >&2

"$PY" - "$D" "$OUT" <<'EOF'
import glob, json, os, sys
d, out = sys.argv[1], sys.argv[2]
def f(x, unit=1.0, fmt="{:.3g}"):
    return "-" if x is None else fmt.format(x * unit)
def ms(s):  # median (min-max) in ms of a median_spread dict
    return f"{f(s['median'], 1e3)} ({f(s['min'], 1e3)}-{f(s['max'], 1e3)})" if s and s.get("median") is not None else "-"
def rt(s):
    return f"{f(s['median'])} ({f(s['min'])}-{f(s['max'])})" if s and s.get("median") is not None else "-"
lines = []
for path in sorted(glob.glob(os.path.join(d, "*.json"))):
    name = os.path.basename(path)[:-5]
    r = json.load(open(path))
    c = r.get("conditions", {})
    flag = " **LOADED**" if c.get("loaded") else ""
    lines.append(f"### {name}{flag}\n")
    lines.append(f"{c.get('date_utc')} UTC, {c.get('machine')}, load average before {c.get('load_before')}, after {c.get('load_after')}\n")
    if name == "commands":
        lines += ["| command | command wall ms | command CPU ms | library in-process ms | command CPU / library |", "| --- | ---: | ---: | ---: | ---: |"]
        for k, v in r.items():
            if k != "conditions":
                lines.append(f"| {k} | {ms(v['command_wall_s'])} | {ms(v['command_cpu_s'])} | {ms(v['library_in_process_s'])} | {rt(v['ratio_command_cpu_to_library'])} |")
    elif name == "peers_passage":
        a = r["autobal"]
        lines += ["| solver | rtol | error before peak | wall ms | CPU ms | compile s | CPU / command's | CPU / library process's |", "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
        lines.append(f"| autobal simulate (command) | 1e-08 | {f(a['error_before_peak'])} | {ms(a['command_wall_s'])} | {ms(a['command_cpu_s'])} | - | 1 | - |")
        lines.append(f"| autobal library (examples/passage) | 1e-08 | {f(a['error_before_peak'])} | {ms(a['library_wall_s'])} | {ms(a['library_process_cpu_s'])} | - | - | 1 |")
        for k, v in r["peers"].items():
            if "error" in v:
                lines.append(f"| {k} | failed: {v['error']} | | | | | | |")
                continue
            if v.get("failed_at_every_rung"):
                lines.append(f"| {k} | failed at every rung of the ladder | | | | | | |")
                continue
            e = next((x.get("error_before_peak") for x in v["ladder"] if x["rtol"] == v["rtol"]), None)
            note = "" if v["reached_target"] else " (target not reached)"
            lines.append(f"| {k} | {v['rtol']:g}{note} | {f(e)} | {ms(v['wall_s'])} | {ms(v['cpu_s'])} | {f(v.get('compile_s'))} | {f(v.get('cpu_vs_command'))} | {f(v.get('cpu_vs_library_process'))} |")
    else:
        lines.append("```json\n" + json.dumps({k: v for k, v in r.items() if k != "conditions"}, indent=1)[:4000] + "\n```")
    lines.append("")
os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
open(out, "w").write("\n".join(lines) + "\n")
print(f"wrote {out}", file=sys.stderr)
EOF
