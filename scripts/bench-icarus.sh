#!/usr/bin/env bash
# Icarus Verilog against Verilator on the same RTL and stimulus: the whole `bot` (rtl/*.v), the
# built-in firmware in `fast` timing, the built-in world, MotCtl_in = 33 (forward) from the
# start, no reset. Icarus runs rtl/sim/bot_tb.v; Verilator runs `botsim run` (tracing compiled
# in, off). Both traces must agree line for line over the Icarus run; then each simulator's
# rate is measured and the ratio printed.
# Usage: scripts/bench-icarus.sh [ICARUS-SAMPLES]   (default 40, ~80 k cycles, ~1-2 s of Icarus)
set -euo pipefail
cd "$(dirname "$0")/.."
samples=${1:-40}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
command -v iverilog >/dev/null || { echo "bench-icarus: iverilog not found: run scripts/setup.sh" >&2; exit 1; }
cargo build --release -q
botsim=target/release/botsim
$botsim firmware --timing fast -o "$work/bot_pgm.v"
iverilog -g2005 -o "$work/tb.vvp" -s bot_tb -Pbot_tb.WORLD="\"$PWD/rtl/default_world.mem\"" \
    -Pbot_tb.SAMPLES="$samples" rtl/kcpsm6.v rtl/world_if.v rtl/map.v rtl/world_map.v rtl/bot.v \
    "$work/bot_pgm.v" rtl/sim/bot_tb.v
t0=$(date +%s.%N)
vvp -N "$work/tb.vvp" >"$work/icarus.csv"
t1=$(date +%s.%N)
icarus_cycles=$(tail -1 "$work/icarus.csv" | cut -d, -f2)
printf 'sample,cycle,loc_x,loc_y,bot_info,sensors,lm_dist,rm_dist\n' >"$work/want.csv"
cat "$work/icarus.csv" >>"$work/want.csv"
# The same stimulus under Verilator: equal traces first, then a run long enough to time.
printf '33 %d\n' "$samples" >"$work/fwd.txt"
$botsim run --timing fast --motors "$work/fwd.txt" --trace-csv "$work/verilator.csv" --quiet
diff -q "$work/want.csv" "$work/verilator.csv" >/dev/null \
    || { echo "bench-icarus: the traces differ:"; diff "$work/want.csv" "$work/verilator.csv" | head; exit 1; }
long=$((samples * 500))
printf '33 %d\n' "$long" >"$work/fwd.txt"
json=$($botsim run --timing fast --motors "$work/fwd.txt" --json)
verilator_rate=$(echo "$json" | grep -o '"mcycles_per_second":[0-9.e+-]*' | cut -d: -f2)
icarus_rate=$(echo "$icarus_cycles / ($t1 - $t0) / 1000000" | bc -l)
printf 'Icarus Verilog %s   %8d cycles  %8.3f Mcycles/s\n' "$(iverilog -V 2>&1 | head -1 | awk '{print $4}')" \
    "$icarus_cycles" "$icarus_rate"
printf 'Verilator %s     %8d samples %8.2f Mcycles/s\n' "$(verilator --version | awk '{print $2}')" "$long" \
    "$verilator_rate"
printf 'ratio            %.0fx (traces equal over the first %d samples)\n' \
    "$(echo "$verilator_rate / $icarus_rate" | bc -l)" "$samples"
