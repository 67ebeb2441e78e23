#!/usr/bin/env bash
# Hostile inputs against every command, each with a time and a memory limit; prints a Markdown
# table of outcomes (docs/reference/robustness.md keeps the latest). Usage:
#   scripts/hostile.sh [path/to/autobal] > hostile.md
# Environment: HOSTILE_TIME_LIMIT (s, default 60), HOSTILE_MEMORY_KB (default 2000000),
# HOSTILE_ONLY (row numbers to run, e.g. "3 71").
# Expected outcome of every row: exit 0 with a finite result, or exit 2 with one line naming the
# field; never a panic (101), a signal, a hang or running out of memory. A run still going at the
# time limit gets Ctrl-C (SIGINT), as a user would send it: it must then stop within 10 s, keep
# what it wrote and say it was interrupted (exit 2); one that ignores it is killed (**HANG**).
# Rows `INT:…` (`INTFAST:…`) are sent Ctrl-C at a random time (0.1 to 3 s, 0.01 to 0.3 s;
# HOSTILE_SEED seeds it, default 23)
# in a folder of their own: each must finish, or stop saying so (exit 2), and every file it
# leaves must be whole (CSV: complete rows ending in a line end; Parquet: its footer; no
# temporary `*.part` file), else **TRUNCATED**. After every row, no `*.part` file may be left
# in the work folder either.
set -u
cd "$(dirname "$0")/.."
BIN=${1:-target/release/autobal}
[ -x "$BIN" ] || { echo "scripts/hostile.sh: build first: cargo build --release (or pass the binary)" >&2; exit 1; }
BIN=$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN")
LIMIT_S=${HOSTILE_TIME_LIMIT:-60}
LIMIT_KB=${HOSTILE_MEMORY_KB:-2000000}   # 2 GB of address space
EX=$PWD/examples
SP="--config $EX/spatial.toml"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
printf 'x = %s%s\n' "$(printf '[%.0s' $(seq 1 5000))" "$(printf ']%.0s' $(seq 1 5000))" > deep.toml
head -c 4096 /dev/urandom > binary.toml
printf '[planar]\nm1 = 1\n' > planar-only.toml
printf '[dimensionless]\nc_sigma = 0.75\n' > partial.toml
mkdir -p adir
# --out variants: a config that an output would overwrite
mkdir -p inputs
cp "$EX/planar.toml" inputs/cfg.csv
cp "$EX/planar.toml" sw.json
cp "$EX/default.toml" inputs/d.toml
# merges: two shards of one sweep, and damaged ones
mkdir -p shards
Q="--threads 1 --set drive.t_end=0.05 --x drive.b=2:3:4000"
for k in 1 2; do "$BIN" sweep $Q --shard $k/2 --out shards/s$k >/dev/null 2>&1; done
"$BIN" sweep $Q --set drive.t_end=0.06 --shard 2/2 --out shards/other >/dev/null 2>&1
cp shards/s1.csv shards/dup.csv; cp shards/s1.json shards/dup.json
head -c $(( $(wc -c < shards/s2.csv) - 9 )) shards/s2.csv > shards/cut.csv; cp shards/s2.json shards/cut.json
head -n 1000 shards/s2.csv > shards/short.csv; cp shards/s2.json shards/short.json
sed '3s/,/,x/' shards/s2.csv > shards/nan.csv; cp shards/s2.json shards/nan.json
sed 's/"definition_checksum": "fnv1a64:[0-9a-f]*"/"definition_checksum": "fnv1a64:0123456789abcdef"/' shards/s2.json > shards/sum.json; cp shards/s2.csv shards/sum.csv
: > shards/empty.csv; : > shards/empty.json
SH=$WORK/shards
# more damaged shards: a JSON cut short, a CSV with another header, CRLF line ends, a shard given twice
head -c 100 shards/s2.json > shards/jcut.json; cp shards/s2.csv shards/jcut.csv
sed '1s/^[^,]*,/renamed,/' shards/s2.csv > shards/hdr.csv; cp shards/s2.json shards/hdr.json
sed 's/$/\r/' shards/s2.csv > shards/crlf.csv; cp shards/s2.json shards/crlf.json
# the spatial rotor with every optional table and real balls on two planes (round 2)
TWO="--config $EX/spatial_two_plane.toml"
FULL="$TWO --set rotor.axis_tilt=0.001 --set rotor.axis_tilt_angle=0.5 --set spatial.spin_drag=0.01 --set spatial.lock_tilt=false --set initial.tilt=[0.001,0] --set initial.velocity=[0.001,0] --set balancer.contact=true --set balancer.rolling_resistance=1e-3 --set balancer.restitution=0.8 --set balancer2.contact=true --set balancer2.ball_diameter=0.02 --set balancer2.rolling_resistance=1e-4 --set balancer2.slip_rate=1e-3"
# --boundary axes over each field's full documented range (docs/reference/robustness.md's table, from
# autobal::limits): every dimensionless key, and every key of the SI tables on the dimensional
# example, at the ends of its range (an open end nudged in by 1e-9 of the span)
boundary_axes() {
    grep -E '^\| `(dimensionless|rotor|supports|unbalance|balancer)\.[a-z_0-9]*` \| [[(]' "$EX/../docs/reference/robustness.md" |
        grep -v 'balls`\|dimensionless.n`\|axis_tilt\|_y`\|unbalance.angle\|ball_diameter\|restitution\|contact_stiffness\|rolling_resistance\|slip_rate' |
        sed -E 's/^\| `([a-z_.0-9]*)` \| ([[(])([-0-9.e]*), ([-0-9.e]*)([])]).*/\1 \2 \3 \4 \5/' |
        awk '{ lo = $3; hi = $4; d = (hi - lo) * 1e-9; if ($2 == "(") lo += d; if ($5 == ")") hi -= d; printf "%s=%.12g:%.12g:3\n", $1, lo, hi }'
}

DIM="--config $EX/dimensional.toml"
cases=(
# spatial, dimensionless fields (embedded default)
"critical --set dimensionless.rho_s=1e-308"
"critical --set dimensionless.rho_s=1e308"
"critical --set dimensionless.l_left=-1e308"
"critical --set dimensionless.l_left=nan"
"critical --set dimensionless.z_a=1e308"
"critical --set dimensionless.delta_a=1e308"
"critical --set dimensionless.delta_a=0.45"
"critical --set dimensionless.c_sigma=0"
"critical --set dimensionless.c_sigma=2.5"
"critical --set dimensionless.c_sigma=0.1"
"critical --set dimensionless.m0=0.99"
"critical --set dimensionless.m0=-0"
"critical --set dimensionless.r0=1e308"
"critical --set dimensionless.r=1e-308"
"critical --set dimensionless.n=10000"
"critical --set dimensionless.n=-1"
"critical --set dimensionless.n=2.5"
"critical --set dimensionless.n=100 --set dimensionless.m=0.05"
"critical --set dimensionless.d_a=2"
"critical --set dimensionless.h_x=inf"
"critical --set dimensionless.h_s=1e308"
"critical --set analysis.anisotropy=sideways"
"critical --set analysis.sensitivity_limit=1"
"critical --set analysis.omega_max=-1"
"inertia --set dimensionless.m=0.5 --set dimensionless.m0=0.6"
"ranges --set dimensionless.l_left=1000 --format json"
# spatial, SI fields
"critical $DIM --set rotor.mass=1e308"
"critical $DIM --set rotor.mass=5e-324"
"critical $DIM --set rotor.mass=0"
"critical $DIM --set rotor.equatorial_moment=1e-300"
"critical $DIM --set rotor.polar_moment=10"
"critical $DIM --set rotor.z=-1e308"
"critical $DIM --set supports.z_right=1e308 --format json"
"critical $DIM --set supports.z_right=0"
"critical $DIM --set supports.z_right=5000"
"stability $DIM --set supports.stiffness_left=1e308"
"stability $DIM --set supports.stiffness_right=1e-300"
"stability $DIM --set supports.damping_left=1e12"
"critical $DIM --set unbalance.mass=1e9"
"critical $DIM --set unbalance.radius=-1"
"critical $DIM --set balancer.drag=-1"
"critical $DIM --set balancer.balls=1000"
"critical $DIM --set balancer.balls=100 --set balancer.ball_mass=0.001"
"stability $DIM --set balancer.balls=100 --set balancer.ball_mass=0.001"
"campbell $DIM --set balancer.balls=100 --set balancer.ball_mass=0.001"
"critical $DIM --set balancer.ball_mass=1e308"
"critical $DIM --set balancer.race_radius=1e308"
"critical $DIM --set balancer.z=1e4"
"inertia $DIM --set dimensionless.c_sigma=1"
# linear analysis options
"stability --omega-max 1e308"
"stability --omega-max 1e-300"
"stability --omega-max nan"
"stability --samples 0"
"stability --samples 1000000 --omega-max 5"
"stability --balls locked --format json"
"stability --svg /dev/null/x.svg"
"campbell --points 100000"
"campbell --points 2"
"campbell --omega-max 1e6 --points 50"
# maps
"map --x dimensionless.z_a=-2:2:5 --y omega=0.05:4.5:5 --out m1"
"map --x dimensionless.z_a=0:1:3 --y dimensionless.z_a=0:1:3 --out m2"
"map --x omega=0:1e308:3 --y dimensionless.z_a=0:1:3 --out m3"
"map --x dimensionless.rho_s=1e-308:1:3 --y omega=0.1:1:3 --out m4"
"map --x dimensionless.l_left=0:1:99999 --y omega=0.1:1:3 --out m5"
"map --x nonsense.key=0:1:3 --y omega=0.1:1:3 --out m6"
"map --x omega=0.1:1:3 --y dimensionless.z_a=0:1:3 --out /dev/null/m"
"map --x omega=0.1:1:3 --y dimensionless.z_a=0:1:3 --threads 0"
"map --x dimensionless.c_sigma=0.1:1.9:4 --y dimensionless.delta_a=0:0.5:4 --omega 1 --out m7"
# stability boundary, and what the issue found slow
"map --x dimensionless.z_a=-2:2:3 --y omega=0.05:4.5:3 --boundary --out mb1"
"map --x dimensionless.h_s=0.001:2:3 --y omega=0.05:10:3 --boundary --out mb2"
"map --x dimensionless.c_sigma=0.35:1.9:3 --y dimensionless.z_a=-3:3:3 --boundary --out mb3"
"campbell --points 10000000"
"campbell $DIM --set balancer.balls=100 --set balancer.ball_mass=0.001 --points 100000"
# simulation and sweeps (planar model, paper 004)
"simulate --set planar.m3=1e-9"
"simulate --set planar.m3=1e-6 --set integration.method=dop853"
"simulate --set drive.b=0.04"
"simulate --set planar.n=100000 --set drive.t_end=1 --set integration.dt=0.5"
"simulate --set planar.n=100001"
"simulate --set drive.xy0=[1e308,0]"
"simulate --set integration.max_steps=0"
"simulate --set integration.max_wall_s=-1"
"simulate --set integration.max_steps=1000"
"simulate --set integration.max_wall_s=0.01"
"sweep --x drive.b=0.5:12.5:5 --set drive.t_end=60 --out sw6"
"sweep --x planar.gamma=1e300:1e301:2 --out sw7"
"simulate --set planar.gamma=1e308"
"simulate --set planar.k=1e308"
"simulate --set planar.k=1e-300 --set drive.t_end=1"
"simulate --set planar.k=1e13 --set planar.m1=1e-9 --set planar.m2=0 --set planar.m3=1e-9"
"simulate --set drive.psi0=1e-300"
"simulate --set planar.m3=-2721377940563434500000000"
"simulate --set planar.m3=1e308"
"simulate --set planar.m3=-1"
"simulate --set planar.n=10"
"simulate --set planar.i_g=1e308"
"simulate --set drive.kind=torque --set drive.torque=1e308"
"simulate --set drive.b=0"
"simulate --set drive.b=1e308"
"simulate --set drive.t_end=1e308"
"simulate --set drive.t_end=1e7 --set integration.dt=1e-6"
"simulate --set drive.psi0=[1e308,0]"
"simulate --set drive.psi0=[1,2,3]"
"simulate --set drive.kind=schedule --set drive.schedule=[[0,0],[0,1]]"
"simulate --set drive.kind=schedule --set drive.schedule=[[0,0],[1,1e308]]"
"simulate --set integration.rtol=1"
"simulate --set integration.rtol=1e-300"
"simulate --set integration.atol=0"
"simulate --set integration.method=euler"
"simulate --dt -1"
"simulate --dt 1e-300"
"simulate --set drive.t_end=1 --out /dev/null/s.csv"
"simulate --set drive.b=0.04 --set drive.t_end=10"
"sweep --x drive.b=1:2:2 --y drive.b=3:4:2 --out sw1"
"sweep --x drive.b=1e308:1e308:2 --out sw2"
"sweep --x planar.c_psi=0.01:0.4:2 --set drive.t_end=2 --out sw3"
"sweep --x nonsense=1:2:2 --out sw4"
"sweep --x drive.b=1:2:100000 --out sw5"
# spatial rotor in time (000/003) and its basins
"simulate $SP --set dimensionless.h_s=1e308"
"simulate $SP --set drive.t_end=1e308"
"simulate $SP --set drive.psi0=[1,2,3]"
"simulate $SP --set spatial.gravity=[0,1e308,0]"
"simulate $SP --set dimensionless.m=1e-9 --set drive.t_end=100"
"simulate $SP --set initial.position=[nan,0]"
"simulate $SP --set drive.t_end=1e7"
"basins $SP --n 0"
"basins $SP --n 100000"
"basins $SP --n 4 --set drive.t_end=100"
# config files
"critical --config /dev/zero"
"critical --config /nonexistent.toml"
"critical --config adir"
"critical --config binary.toml"
"critical --config deep.toml"
"critical --config planar-only.toml"
"critical --config partial.toml"
"simulate --config $EX/default.toml"
# --set syntax
"critical --set nonsense"
"critical --set =1"
"critical --set dimensionless=1"
"critical --set dimensionless.c_sigma.x=1"
"critical --set dimensionless.c_sigma={a=1}"
"critical --set dimensionless.c_sigma=[1,2]"
"critical --set dimensionless.c_sigma=0x10"
"critical --set dimensionless.c_sigma=1_0"
"critical --set dimensionless.c_sigma=9223372036854775807"
# report
"report --quick --out rep --set dimensionless.rho_s=1e-308"
"report --quick --out /dev/null/rep"
# --out: a folder (with and without the slash), an input, an unusable or unwritable place
"simulate --set drive.t_end=1 --out outdir/"
"simulate --set drive.t_end=1 --out adir"
"map --x dimensionless.z_a=-2:2:3 --y omega=0.1:2:3 --out adir/"
"stability --svg adir/"
"simulate --config inputs/cfg.csv --out inputs/cfg.csv"
"sweep --config sw.json --x drive.b=1:2:2 --out ./sw"
"merge $SH/s1.csv $SH/s2.csv --out $SH/s1"
"basins $SP --n 1000 --out /dev/null/basins.csv"
"basins $SP --n 1000 --out /dev/null"
"map --x dimensionless.z_a=-2:2:3 --y omega=0.1:2:3 --boundary --out /proc/m"
"sweep --x drive.b=1:2:2 --out /proc/sw"
"report --quick --out inputs/cfg.csv"
# merges: whole, then damaged shards
"merge $SH/s2.csv $SH/s1.csv --parquet --out merged"
"merge $SH/s1.csv $SH/cut.csv --out m1"
"merge $SH/s1.csv $SH/short.csv --out m2"
"merge $SH/s1.csv $SH/nan.csv --out m3"
"merge $SH/s1.csv $SH/other.csv --out m4"
"merge $SH/s1.csv $SH/sum.csv --out m5"
"merge $SH/s1.csv $SH/dup.csv $SH/s2.csv --out m6"
"merge $SH/s1.csv --out m7"
"merge /dev/zero --out m8"
"merge $SH/empty.csv --out m9"
"merge adir --out m10"
# Ctrl-C at a random time: whatever the command has written must be whole
"INT:simulate --parquet --set drive.t_end=2000 --set integration.dt=0.0005 --out sim"
"INT:simulate --parquet --set drive.t_end=2000 --set integration.dt=0.0005 --out sim"
"INT:simulate $SP --set drive.t_end=1e6 --out spatial"
"INT:sweep --parquet --threads 2 --x drive.b=1:2:4000 --out sw"
"INT:sweep --parquet --threads 2 --x drive.b=1:2:4000 --shard 2/3 --out sw"
"INT:map --x dimensionless.z_a=-2:2:2000 --y omega=0.1:3:2000 --out map"
"INT:map --x dimensionless.z_a=-2:2:400 --y omega=0.05:4.5:400 --boundary --out mapb"
"INT:basins $SP --n 200 --out basins.csv"
"INT:basins $SP --n 200 --out basins.csv"
"INTFAST:merge $SH/s1.csv $SH/s2.csv --parquet --out merged"
"INTFAST:merge $SH/s1.csv $SH/s2.csv --parquet --out merged"
"INTFAST:merge $SH/s1.csv $SH/s2.csv --parquet --out merged"
# --set with a whole table as the value of a table
"critical --set dimensionless={c_sigma=1}"
# round 3 (issue 23). Entries the model that runs them does not have: the spatial rotor's on the
# planar one (simulate, sweep, stability, map), the planar rotor's on the spatial one (every command)
"simulate --set spatial.gravity=[0,-9.81,0] --set drive.t_end=0.1"
"simulate --set initial.position=[0.001,0] --set drive.t_end=0.1"
"sweep --set couple.mass=0.01 --x drive.b=1:2:2 --out swc"
"stability --config $EX/planar.toml --set spatial.lock_tilt=true"
"map --config $EX/planar.toml --set balancer2.balls=2 --x planar.c_psi=0.1:0.2:3 --y omega=100:300:3 --out mp"
"simulate $SP --set drive.xy0=[0.001,0] --set drive.t_end=10"
"basins $SP --set drive.xy_rate0=[0.1,0] --n 2"
"sweep $SP --set planar.m1=1 --x drive.omega0=1.5:1.6:2 --out sws"
"critical $SP --set planar.k=1e5"
"report --quick --out rep2 $SP --set drive.xy0=[0.001,0]"
# entries moot with the rest of the config: a warning naming them
"simulate $TWO --set balancer2.balls=0 --set drive.t_end=0.1"
"simulate $TWO --set balancer2.balls=0 --set balancer2.ball_mass=0 --set drive.t_end=0.1"
"simulate --set planar.restitution=0.9 --set planar.slip_rate=1e-3 --set drive.t_end=0.1"
"critical $DIM --set balancer.balls=0 --set balancer.ball_mass=0"
"simulate $TWO --set rotor.axis_tilt_angle=1 --set drive.t_end=0.1"
# the spatial rotor with every optional table, real balls on two planes, in every command
"simulate $FULL --set drive.t_end=0.2"
"simulate $FULL --set drive.t_end=0.2 --parquet --out full"
"basins $FULL --set drive.t_end=0.05 --n 3"
"sweep $FULL --set drive.t_end=0.05 --x balancer2.balls=0:4:5 --set balancer2.ball_mass=0 --out swf"
"sweep $FULL --set drive.t_end=0.05 --x balancer.restitution=0:1:3 --y balancer2.ball_diameter=0.001:0.3:3 --out swf2"
"critical $FULL"
"ranges $FULL"
"inertia $FULL"
"stability $FULL --samples 10"
"campbell $FULL --points 5"
"map $FULL --x balancer.ball_mass=0.01:0.05:3 --y speed_rpm=100:3000:3 --out mf"
"report --quick --out repf $FULL"
"simulate $TWO --set balancer.balls=100 --set balancer2.balls=100 --set balancer.ball_mass=1e-4 --set balancer2.ball_mass=1e-4 --set balancer.contact=true --set balancer2.contact=true --set drive.t_end=0.02"
"simulate $TWO --set balancer.balls=101"
# planar real balls: the implicit limit, many balls in contact under the explicit method
"simulate --set planar.n=301 --set planar.m3=1e-4 --set planar.contact=true --set planar.ball_diameter=1e-3"
"simulate --set planar.n=300 --set planar.m3=1e-4 --set planar.contact=true --set planar.ball_diameter=1e-3 --set drive.t_end=0.01"
"simulate --set planar.n=100000 --set planar.m3=1e-3 --set planar.c_psi=0 --set planar.contact=true --set planar.ball_diameter=1e-6 --set integration.method=dop853 --set drive.t_end=1e-5 --set integration.dt=1e-5"
"simulate --set planar.n=20000 --set planar.contact=true --set planar.ball_diameter=1e-6 --set planar.m3=1e-6 --set integration.method=rodas"
# merges of more damaged shards
"merge $SH/s1.csv $SH/jcut.csv --out m11"
"merge $SH/s1.csv $SH/hdr.csv --out m12"
"merge $SH/s1.csv $SH/crlf.csv --out m13"
"merge $SH/s1.csv $SH/s1.csv $SH/s2.csv --out m14"
"merge $SH/s1.csv $SH/s2.csv --out $SH/s2.csv"
"merge $SH/s1.json $SH/s2.json --out m15"
# --out variants
"simulate --set drive.t_end=0.1 --out ''"
"simulate --set drive.t_end=0.1 --out ."
"simulate --set drive.t_end=0.1 --out /"
"simulate --set drive.t_end=0.1 --out adir/../adir/"
"sweep --config inputs/cfg.csv --x drive.b=1:2:2 --set drive.t_end=0.1 --out inputs/cfg"
"campbell --points 5 --svg adir/c.svg"
"stability --config inputs/d.toml --svg inputs/d.toml"
# Ctrl-C at a random time in every command
"INTFAST:critical $FULL"
"INTFAST:ranges"
"INTFAST:inertia"
"INT:stability $FULL --samples 200"
"INT:campbell --points 1000000 --svg camp"
"INT:report --quick --out repi"
"INT:report --quick --out repi2 $FULL"
"INT:simulate $FULL --set drive.t_end=1e6 --parquet --out fulli"
"INT:sweep $FULL --x drive.omega0=1:2:1000 --parquet --out swfi"
"INT:map $FULL --x balancer.ball_mass=0.01:0.05:100 --y speed_rpm=100:3000:100 --out mfi"
"INT:basins $FULL --n 100 --out bfi.csv"
)
# --boundary over each field's full range (generated, see boundary_axes)
while read -r ax; do
    case $ax in dimensionless.*) cases+=("map --x $ax --y omega=0.05:4.5:3 --boundary --out mb") ;;
    *) cases+=("map $DIM --x $ax --y speed_rpm=100:20000:3 --boundary --out mb") ;; esac
done < <(boundary_axes)

RANDOM=${HOSTILE_SEED:-23}

# Every file in folder $1 whole: CSV rows complete, Parquet with its footer, no *.part file.
# Prints the first damaged file, or nothing.
damaged() {
    local f
    for f in "$1"/*.part; do [ -e "$f" ] && { echo "temporary file left: $(basename "$f")"; return; }; done
    for f in "$1"/*.csv; do
        [ -e "$f" ] || continue
        [ -s "$f" ] || { echo "empty $(basename "$f")"; return; }
        [ -z "$(tail -c 1 "$f")" ] || { echo "$(basename "$f") ends mid-row"; return; }
        awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' "$f" || { echo "$(basename "$f") has a short row"; return; }
    done
    for f in "$1"/*.parquet; do
        [ -e "$f" ] || continue
        [ "$(tail -c 4 "$f")" = PAR1 ] || { echo "$(basename "$f") has no footer"; return; }
    done
}

echo "| # | command | exit | time (s) | outcome |"
echo "|---|---|---|---|---|"
i=0
for c in "${cases[@]}"; do
    i=$((i + 1))
    # one draw per Ctrl-C row before the HOSTILE_ONLY skip, so that a subset repeats the whole
    # table's times (review 24c). ($RANDOM drawn in this shell: expanded inside a command
    # substitution it came from a subshell, which bash reseeds, so HOSTILE_SEED did not make
    # the times repeat)
    case $c in INT*:*) r=$RANDOM ;; esac
    # HOSTILE_ONLY="3 71": run only these rows (numbers as in the table)
    if [ -n "${HOSTILE_ONLY:-}" ] && ! printf ' %s ' "$HOSTILE_ONLY" | grep -q " $i "; then continue; fi
    limit=$LIMIT_S
    run_dir=.
    interrupt=""
    case $c in INT*:*)
        # a random time between 0.1 and 3 s (INTFAST: 0.01 to 0.3 s, for quick commands), in a
        # folder of its own
        span=2.9; lo=0.1
        case $c in INTFAST:*) span=0.29; lo=0.01 ;; esac
        c=${c#*:}
        limit=$(awk "BEGIN { printf \"%.2f\", $lo + $span * $r / 32767 }")
        interrupt=$limit
        run_dir=int$i
        mkdir -p "$run_dir" ;;
    esac
    start=$(date +%s%N)
    # shellcheck disable=SC2086
    # at the limit: SIGINT (Ctrl-C), then SIGKILL 10 s later if it is ignored. One SIGINT, as
    # a terminal's Ctrl-C sends: without --foreground, timeout sends it to the command and then
    # to its whole process group, the command included, a second Ctrl-C, which autobal's
    # handler rightly takes as "stop at once" (exit 130: rows 54, 124 and 178 of session 24's
    # first run, where the two came far enough apart not to merge)
    out=$( (cd "$run_dir" && ulimit -v "$LIMIT_KB" && timeout --foreground --preserve-status -s INT -k 10 "$limit" "$BIN" $c) 2>&1 >/dev/null)
    code=$?
    secs=$(awk "BEGIN { printf \"%.2f\", ($(date +%s%N) - $start) / 1e9 }")
    long=$(awk "BEGIN { print ($secs >= $limit) ? 1 : 0 }")
    first=$(printf '%s' "$out" | grep -v '^warning\|^boundary:\|^wrote\|^[0-9]* rows' | head -1 | cut -c1-160 | sed 's/|/\\|/g')
    warn=$(printf '%s' "$out" | grep '^warning' | head -1 | cut -c1-160 | sed 's/|/\\|/g')
    lines=$(printf '%s' "$out" | grep -vc '^warning\|^wrote\|^simulating\|^report written\|^boundary:\|^[0-9]* rows')
    case $code in
        0) verdict="ok"; [ -n "$warn" ] && first=$warn ;;
        2) if [ "$long" = 1 ] && printf '%s' "$out" | grep -q 'interrupted'; then verdict="long run, stopped by Ctrl-C at the limit";
           elif [ "$lines" -le 1 ]; then verdict="error (one line)"; else verdict="error ($lines lines)"; fi ;;
        130) if [ "$long" = 1 ]; then verdict="long run, ended by Ctrl-C at the limit (writes nothing before its end)"; else verdict="**exit 130**"; fi ;;
        137) verdict="**HANG (ignored Ctrl-C)**" ;;
        101) verdict="**PANIC**" ;;
        *) verdict="**exit $code**" ;;
    esac
    if [ -n "$interrupt" ]; then
        bad=$(damaged "$run_dir")
        case $code in
            0) verdict="finished before Ctrl-C at $interrupt s" ;;
            2) if printf '%s' "$out" | grep -q 'interrupted\|stopped'; then verdict="stopped by Ctrl-C at $interrupt s"; else verdict="error (not Ctrl-C) at $interrupt s"; fi ;;
            130) verdict="ended by Ctrl-C at $interrupt s before its handler was set" ;;
        esac
        first=$(printf '%s' "$out" | grep 'interrupted\|stopped\|^error' | head -1 | cut -c1-160 | sed 's/|/\\|/g')
        if [ -n "$bad" ]; then verdict="**TRUNCATED ($bad)**, $verdict"; else verdict="$verdict, files whole ($(cd "$run_dir" && ls | tr '\n' ' ' | cut -c1-80 | sed 's/ *$//'))"; fi
        c="$c  # Ctrl-C at $interrupt s"
    fi
    bad=$(damaged .)
    [ -n "$bad" ] && verdict="**TRUNCATED ($bad)**, $verdict"
    shown=$(echo "$c" | sed "s|$EX/|examples/|g; s|$WORK/||g")
    first=$(printf '%s' "$first" | sed "s|$WORK/||g")
    printf '| %d | `autobal %s` | %d | %s | %s: %s |\n' "$i" "$shown" "$code" "$secs" "$verdict" "${first:-}"
done
