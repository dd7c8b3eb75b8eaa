#!/usr/bin/env bash
# Measure FST against VCD for the whole `bot` design: the same RTL, firmware (fast timing)
# and stimulus (forward), the same number of cycles, one build per format (Verilator 5.006
# builds one trace format at a time). Prints size and speed of each. Needs zlib1g-dev.
# Usage: scripts/dev/measure-fst.sh [CYCLES]   (default 2,000,000)
set -euo pipefail
cd "$(dirname "$0")/../.."
cycles=${1:-2000000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
root=$(verilator --getenv VERILATOR_ROOT)
./target/release/botsim asm rtl/bot_pgm.psm -o "$work/bot_pgm.v" --rom-size 1K \
  -D delay_50ms=1\'d -D delay_1ms=1\'d -D delay_40us=16\'d
cat > "$work/main.cpp" <<CPP
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include "Vbot.h"
#include "verilated.h"
#include TRACE_H
int main(int argc, char** argv) {
    uint64_t n = strtoull(argv[1], 0, 10);
    VerilatedContext ctx; ctx.traceEverOn(true);
    Vbot top{&ctx, "TOP"};
    TRACE_T tf; top.trace(&tf, 99); tf.open(argv[2]);
    top.MotCtl_in = 0x33; top.clk = 0; top.eval();
    auto t0 = std::chrono::steady_clock::now();
    for (uint64_t i = 0; i < n; i++) {
        top.clk = 0; top.eval(); tf.dump(ctx.time()); ctx.timeInc(5000);
        top.clk = 1; top.eval(); tf.dump(ctx.time()); ctx.timeInc(5000);
    }
    tf.close();
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    printf("%.2f Mcycles/s\n", n / s / 1e6);
}
CPP
. scripts/lib/rtl.sh
rtl="$(rtl_files rtl/bot.f | tr '\n' ' ') $work/bot_pgm.v"
for fmt in vcd fst; do
  if [ $fmt = vcd ]; then flag=--trace; h='"verilated_vcd_c.h"'; t=VerilatedVcdC; rt=verilated_vcd_c.cpp; lib=
  else flag=--trace-fst; h='"verilated_fst_c.h"'; t=VerilatedFstC; rt=verilated_fst_c.cpp; lib=-lz; fi
  verilator --cc --no-timing -O3 --x-assign fast --x-initial fast $flag --top-module bot --Mdir "$work/$fmt" $rtl
  g++ -O2 -std=c++17 -faligned-new -DVM_TRACE=1 "-DTRACE_H=$h" -DTRACE_T=$t -I"$root/include" -I"$root/include/vltstd" \
    -I"$work/$fmt" "$work/main.cpp" "$work/$fmt"/Vbot*.cpp "$root/include/verilated.cpp" \
    "$root/include/verilated_threads.cpp" "$root/include/$rt" -o "$work/$fmt.bin" -lpthread $lib
  speed=$("$work/$fmt.bin" "$cycles" "$work/out.$fmt")
  printf '%s: %s cycles, %s bytes (%.1f bytes/cycle), %s\n' "$fmt" "$cycles" "$(stat -c %s "$work/out.$fmt")" \
    "$(echo "$(stat -c %s "$work/out.$fmt") / $cycles" | bc -l)" "$speed"
done
