#!/usr/bin/env bash
# The CI gate for Verilog and firmware changes. Runs, in order, and stops at the first failure:
#   lint       verilator --lint-only -Wall on every RTL file and the whole `bot` (waivers: *.vlt)
#   icarus     Icarus Verilog runs rtl/sim/bot_tb.v; its register trace must equal Verilator's
#   yosys      synth of `bot` (and synth_xilinx): no latches, no multiple drivers, no loops
#   generated  rtl/bot_pgm.v and rtl/default_world.mem equal what the toolchain generates now
#   xinit      the lock-step and system tests again with random power-up values (--x-initial
#              unique, BOTSIM_X_SEED=1..4): the RTL needs no state the device does not set
#   coverage   line and toggle coverage per RTL module over the RTL tests, against floors
#   fuzz       a short cargo-fuzz run of every parser (when cargo-fuzz is installed)
#   rust       cargo fmt --check and cargo clippy --all-targets -- -D warnings
# Prints each stage's time. Needs scripts/setup.sh; builds what it needs.
# GATE_STAGES="lint yosys" runs only the named stages (in the order above).
set -uo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
botsim=target/release/botsim

. scripts/lib/rtl.sh
. scripts/lib/tests.sh
# The design's files, from its list (rtl/bot.f): all of them for Verilator, the Verilog alone
# for Yosys.
BOT=$(rtl_files rtl/bot.f | tr '\n' ' ')
RTL=$(rtl_files rtl/bot.f v | tr '\n' ' ')

fail() {
  echo "gate: FAILED in stage '$stage': $*" >&2
  exit 1
}

run_stage() {
  stage=$1
  shift
  if [ -n "${GATE_STAGES:-}" ] && [[ " $GATE_STAGES " != *" $stage "* ]]; then
    return 0
  fi
  local t0
  t0=$(date +%s.%N)
  echo "gate: $stage ..."
  "$@" || fail "see the messages above"
  printf 'gate: %-10s ok (%.1f s)\n' "$stage" "$(echo "$(date +%s.%N) - $t0" | bc -l)"
}

lint_one() {
  local out
  if ! out=$(verilator --lint-only -Wall "$@" 2>&1); then
    echo "$out" >&2
    echo "gate: lint warnings in: $*" >&2
    return 1
  fi
}

lint() {
  lint_one rtl/kcpsm6.vlt rtl/kcpsm6.v &&
    lint_one rtl/world_if.v &&
    lint_one rtl/world_map.v &&
    lint_one --top-module map rtl/map.v rtl/world_map.v &&
    lint_one rtl/bot_pgm.v &&
    lint_one --top-module kcpsm6_harness $(rtl_files rtl/sim/cpu.f) &&
    lint_one --top-module bot $BOT rtl/bot_pgm.v &&
    lint_one --top-module bot +define+BOTSIM_LOC_Y_REG $BOT rtl/bot_pgm.v
}

icarus() {
  local samples=12
  BOTSIM=$botsim bash scripts/lib/icarus-bot.sh $samples > "$work/icarus.txt" || return 1
  printf 'forward %d\n' $samples > "$work/motors.txt"
  "$botsim" run --timing fast --motors "$work/motors.txt" --trace-csv "$work/verilator.csv" --quiet || return 1
  tail -n +2 "$work/verilator.csv" > "$work/verilator.txt"
  if ! diff -u "$work/verilator.txt" "$work/icarus.txt" >&2; then
    echo "gate: Icarus and Verilator disagree (- Verilator, + Icarus)" >&2
    return 1
  fi
  echo "gate: $(wc -l < "$work/icarus.txt") snapshots agree between Icarus and Verilator"
}

yosys_synth() {
  local log="$work/yosys.log" script xilinx=0
  # The world ROM gets the built-in world so that it is a real ROM, not an empty memory.
  # Both syntheses at once (Yosys is one thread).
  yosys -q -p "read_verilog -defer $RTL rtl/bot_pgm.v
chparam -set WORLD_FILE \"rtl/default_world.mem\" bot
synth_xilinx -top bot -family xc7
check -assert
tee -o $work/xstat.txt stat" > "$work/xilinx.log" 2>&1 &
  local xpid=$!
  script="read_verilog -defer $RTL rtl/bot_pgm.v
chparam -set WORLD_FILE \"rtl/default_world.mem\" bot
hierarchy -top bot
synth -top bot
check -assert
select -assert-none t:\$dlatch t:\$adlatch t:\$_DLATCH_* t:\$_DLATCHSR_*
tee -o $work/stat.txt stat"
  if ! yosys -q -p "$script" > "$log" 2>&1; then
    wait $xpid
    cat "$log" >&2
    echo "gate: yosys found a problem (latch, multiple drivers, logic loop or a synthesis error)" >&2
    return 1
  fi
  grep -E "Number of cells|Number of wires" "$work/stat.txt" | tail -2 | sed 's/^ */gate: synth: /'
  wait $xpid || xilinx=$?
  if [ "$xilinx" = 0 ]; then
    grep -E "RAMB|LUT6 |FDRE|Number of cells" "$work/xstat.txt" | tail -6 | sed 's/^ */gate: synth_xilinx: /'
  else
    cat "$work/xilinx.log" >&2
    return 1
  fi
}

generated() {
  cargo test --workspace --release -q --test generated 2>&1 | tail -3
  test "${PIPESTATUS[0]}" -eq 0
}

xinit() {
  xinit_check "$work"
}

coverage() {
  bash scripts/ci/coverage.sh --check
}

fuzz() {
  if ! command -v cargo-fuzz >/dev/null; then
    echo "gate: cargo-fuzz not installed; skipping the fuzz smoke run"
    return 0
  fi
  bash scripts/dev/fuzz.sh "${FUZZ_SECONDS:-20}"
}

rust() {
  cargo fmt --all -- --check || { echo "gate: run cargo fmt --all" >&2; return 1; }
  cargo clippy --workspace --all-targets --release -q -- -D warnings
}

total0=$(date +%s)
# Every cargo command here uses --workspace, as the README's test command does: Cargo resolves
# features differently for one package, or without dev-dependencies (`cargo build`), and would
# compile the models again.
run_stage build cargo test --workspace --release --no-run
run_stage lint lint
run_stage icarus icarus
run_stage yosys yosys_synth
run_stage generated generated
run_stage xinit xinit
run_stage coverage coverage
run_stage fuzz fuzz
run_stage rust rust
echo "gate: all stages passed in $(( $(date +%s) - total0 )) s"
