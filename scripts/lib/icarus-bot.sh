#!/usr/bin/env bash
# The one Icarus Verilog run of `bot`, used by the gate, scripts/dev/bench-icarus.sh and
# `botsim bench`: rtl/sim/bot_tb.v around the RTL of rtl/bot.f, the built-in firmware in `fast`
# timing, the built-in world (rtl/default_world.mem), MotCtl_in = 33 (forward) from the start,
# no reset. Prints the trace as `botsim run --trace-csv` rows (without the header) on stdout
# and `icarus: CYCLES cycles in SECONDS s` on stderr.
# Usage: scripts/lib/icarus-bot.sh SAMPLES   (BOTSIM: the botsim binary, default
# target/release/botsim)
set -euo pipefail
cd "$(dirname "$0")/../.."
samples=${1:?usage: icarus-bot.sh SAMPLES}
botsim=${BOTSIM:-target/release/botsim}
command -v iverilog >/dev/null || { echo "icarus-bot: iverilog not found: run scripts/setup.sh" >&2; exit 1; }
. scripts/lib/rtl.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$botsim" firmware --timing fast -o "$work/bot_pgm.v"
# shellcheck disable=SC2046
iverilog -g2005 -Wall -o "$work/tb.vvp" -s bot_tb -Pbot_tb.WORLD="\"$PWD/rtl/default_world.mem\"" \
  -Pbot_tb.SAMPLES="$samples" $(rtl_files rtl/bot.f v) "$work/bot_pgm.v" rtl/sim/bot_tb.v
t0=$(date +%s.%N)
vvp -N "$work/tb.vvp" >"$work/trace.csv"
t1=$(date +%s.%N)
if grep -q ERROR "$work/trace.csv"; then
  cat "$work/trace.csv" >&2
  exit 1
fi
cat "$work/trace.csv"
echo "icarus: $(tail -1 "$work/trace.csv" | cut -d, -f2) cycles in $(echo "$t1 - $t0" | bc -l) s" >&2
