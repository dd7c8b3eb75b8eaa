#!/usr/bin/env bash
# Icarus Verilog against Verilator on the same RTL and stimulus: the whole `bot` (rtl/bot.f),
# the built-in firmware in `fast` timing, the built-in world, MotCtl_in = 33 (forward) from
# the start, no reset. Icarus runs through scripts/lib/icarus-bot.sh; Verilator runs
# `botsim run` (tracing compiled in, off). Both traces must agree line for line over the Icarus run; then each simulator's
# rate is measured and the ratio printed.
# Usage: scripts/dev/bench-icarus.sh [ICARUS-SAMPLES]   (default 40, ~80 k cycles, ~1-2 s of Icarus)
set -euo pipefail
cd "$(dirname "$0")/../.."
samples=${1:-40}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cargo build --workspace --release -q
botsim=target/release/botsim
BOTSIM=$botsim bash scripts/lib/icarus-bot.sh "$samples" >"$work/icarus.csv" 2>"$work/icarus.time"
icarus_cycles=$(awk '{print $2}' "$work/icarus.time")
icarus_seconds=$(awk '{print $5}' "$work/icarus.time")
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
icarus_rate=$(echo "$icarus_cycles / $icarus_seconds / 1000000" | bc -l)
printf 'Icarus Verilog %s   %8d cycles  %8.3f Mcycles/s\n' "$(iverilog -V 2>&1 | head -1 | awk '{print $4}')" \
    "$icarus_cycles" "$icarus_rate"
printf 'Verilator %s     %8d samples %8.2f Mcycles/s\n' "$(verilator --version | awk '{print $2}')" "$long" \
    "$verilator_rate"
printf 'ratio            %.0fx (traces equal over the first %d samples)\n' \
    "$(echo "$verilator_rate / $icarus_rate" | bc -l)" "$samples"
