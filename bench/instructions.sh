#!/usr/bin/env bash
# Instruction counts (valgrind --tool=callgrind, "I refs"): independent of the load on the
# machine, so a before/after comparison made on a busy machine still holds. For each command,
# the whole process against the library's share of the same work:
#   simulate  the library example examples/passage (the same passage, samples in memory)
#   map       inside the command's own profile: Line::new + Line::cells + LinePlane::new (the map's library work)
#   campbell  the library example examples/bench_campbell in its `command` mode (the command's
#             library calls: config, campbell_stream over the same speeds keeping every speed's
#             modes, fixed_axes; one run), whole process against whole process
#   sweep     inside the command's own profile: planar::simulate_summary
#   spatial   `simulate` of bench/peers_spatial.py's 1000-revolution run-up (examples/spatial.toml):
#             inside the command's own profile, spatial::dynamics::simulate::simulate_sampled
#             less the command's sample callback (the CSV rows, written on the run's thread)
#
#   bench/instructions.sh [AUTOBAL_BINARY]      (default target/release/autobal)
#   ONLY="simulate spatial" bench/instructions.sh   (rows: simulate map campbell sweep spatial)
#   KEEP=DIR bench/instructions.sh                   (keep the callgrind profiles in DIR)
#
# Needs valgrind and the release examples (cargo build --release -p autobal --example passage
# --example bench_campbell).
# Prints a markdown table. Instruction counts miss system calls and cache misses: they are the
# floor of a process's cost, not its time (docs/notes/benchmarks.md).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
EXE="${1:-$ROOT/target/release/autobal}"
EX="$ROOT/target/release/examples"
W="$(mktemp -d)"
# KEEP=DIR: keep the profiles (callgrind_annotate DIR/NAME.cg)
trap 'if [ -n "${KEEP:-}" ]; then mkdir -p "$KEEP" && cp "$W"/*.cg* "$KEEP"/ 2>/dev/null; fi; rm -rf "$W"' EXIT
count() { # name, command...: the instruction count of the whole process; profile in $W/name.cg
  local name="$1"; shift
  (cd "$W" && valgrind --tool=callgrind --callgrind-out-file="$W/$name.cg" "$@" >/dev/null 2>"$W/$name.err") || true
  grep -o 'refs: *[0-9,]*' "$W/$name.err" | tr -dc '0-9'
}
incl() { # profile, function name pattern: its inclusive count (sum over matching lines); a
  # pattern that matches nothing (a function renamed) stops the script with its name, not silently
  local n
  n=$(callgrind_annotate --inclusive=yes "$1" 2>/dev/null | { grep -E "$2" || true; } | awk '{gsub(",","",$1); s+=$1} END {print s+0}')
  if [ "$n" = 0 ]; then echo "instructions.sh: no function matches '$2' in $1 (renamed?)" >&2; exit 1; fi
  echo "$n"
}
want() { [ -z "${ONLY:-}" ] || [[ " $ONLY " == *" $1 "* ]]; }
row() { printf '| %s | %s | %s | %.2f |\n' "$1" "$2" "$3" "$(echo "$2 / $3" | bc -l)"; }
echo "| command | process (instructions) | library's share (instructions) | process / library |"
echo "| --- | ---: | ---: | ---: |"
# simulate writes its CSV on a second thread and two of its figures on another: the process's
# count (all threads: its CPU) and the main thread's (the run's: what its wall time follows)
if want simulate; then
(cd "$W" && valgrind --tool=callgrind --separate-threads=yes --callgrind-out-file="$W/simt.cg" "$EXE" simulate --out "$W/simt.csv" >/dev/null 2>&1) || true
c=$(count sim "$EXE" simulate --out "$W/sim.csv"); l=$(count passage "$EX/passage")
m=$(grep -h '^summary:' "$W"/simt.cg-01 | tr -dc '0-9')
row "simulate (paper 004 passage, CSV + 4 SVG), all threads" "$c" "$l"
row "simulate, its main thread (the integration's)" "$m" "$l"
fi
if want map; then
c=$(count map "$EXE" map --threads 1 --x dimensionless.z_a=-2:2:400 --y omega=0.05:4.5:400 --out "$W/map")
l=$(incl "$W/map.cg" 'spatial::map::(Line::(new|cells)|LinePlane::new) \[')
row "map --threads 1, 400 x 400 margin (CSV + SVG + PNG)" "$c" "$l"
fi
if want campbell; then
c=$(count campbell "$EXE" campbell --points 200 --omega-max 5 --format json)
# the library: the same calls in the example's process (its in-process share, the tracked modes
# and the fixed axes less the command's callback, was what this row counted before: it left out
# the example's own start and config, and counted the callback's kept modes as overhead)
l=$(count bench_campbell "$EX/bench_campbell" 200 1 command)
row "campbell --points 200 --omega-max 5 --format json (JSON on stdout)" "$c" "$l"
fi
if want sweep; then
c=$(count sweep "$EXE" sweep --threads 1 --x planar.c_psi=0.05:0.2:20 --y drive.b=100:200:20 --set drive.t_end=0.5 \
  --set drive.omega0=250 --set integration.dt=0.5 --out "$W/sw")
l=$(incl "$W/sweep.cg" 'planar::simulate_summary \[')
row "sweep --threads 1, 20 x 20 short passages (CSV)" "$c" "$l"
fi
if want spatial; then
c=$(count spatial "$EXE" simulate --config "$ROOT/examples/spatial.toml" --set 'drive.kind="acceleration"' --set drive.omega0=0 \
  --set drive.b=0.0012732395447351628 --set drive.t_end=3141.592653589793 --out "$W/spatial.csv")
l=$(( $(incl "$W/spatial.cg" 'spatial::dynamics::simulate::simulate_sampled \[') - $(incl "$W/spatial.cg" 'simulate::Plan::run::\{\{closure\}\} \[') ))
row "simulate, spatial 1000-revolution run-up (CSV + SVG)" "$c" "$l"
fi
