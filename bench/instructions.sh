#!/usr/bin/env bash
# Instruction counts (valgrind --tool=callgrind, "I refs"): independent of the load on the
# machine, so a before/after comparison made on a busy machine still holds. Counts the whole
# process of each command and the library's in-process examples of the same work.
#
#   bench/instructions.sh [AUTOBAL_BINARY]      (default target/release/autobal)
#
# Needs valgrind and the release examples (cargo build --release -p autobal --examples).
# Prints one markdown row per command: instructions of the command, of the library, ratio.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
EXE="${1:-$ROOT/target/release/autobal}"
EX="$ROOT/target/release/examples"
W="$(mktemp -d)"
trap 'rm -rf "$W"' EXIT
count() { # name, command...: prints the instruction count of the whole process
  local name="$1"; shift
  (cd "$W" && valgrind --tool=callgrind --callgrind-out-file="$W/$name.cg" "$@" >/dev/null 2>"$W/$name.err") || true
  grep -o 'refs: *[0-9,]*' "$W/$name.err" | tr -dc '0-9'
}
echo "| work | command (instructions) | library (instructions) | command / library |"
echo "| --- | ---: | ---: | ---: |"
row() { printf '| %s | %s | %s | %.2f |\n' "$1" "$2" "$3" "$(echo "$2 / $3" | bc -l)"; }
c=$(count sim "$EXE" simulate --out "$W/sim.csv"); l=$(count passage "$EX/passage"); row "simulate (paper 004 passage, CSV + 4 SVG)" "$c" "$l"
# the map: one thread so that the count is the work, margin (the command's default)
c=$(count map "$EXE" map --threads 1 --x dimensionless.z_a=-2:2:400 --y omega=0.05:4.5:400 --out "$W/map")
l=$(cd "$W" && BENCH_THREADS=1 count mapl "$EX/bench_map" 400 400 "$W/m.bin" maps)
row "map 400x400 margin + verdict example (CSV + SVG + PNG)" "$c" "$l"
c=$(count campbell "$EXE" campbell --points 200 --omega-max 5 --format json); l=$(count campbelll "$EX/bench_campbell" 200 1)
row "campbell 200 speeds (JSON; library: free + locked)" "$c" "$l"
