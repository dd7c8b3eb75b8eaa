#!/usr/bin/env bash
# RTL coverage of the testbench: builds the models with Verilator line and toggle coverage (in
# the main target dir, so the dependencies built for the tests are reused: only botsim and its
# models are rebuilt, and again by the next build without coverage; nothing is rebuilt when
# BOTSIM_COVERAGE=1 was set for the build before, as .ci/run does), runs the RTL tests, merges
# the per-model files and prints line and toggle coverage per RTL module. With --check, fails when a module is under its floor
# (scripts/ci/coverage_floors.txt).
# Usage: scripts/ci/coverage.sh [--check]
set -euo pipefail
cd "$(dirname "$0")/../.."
out=target/coverage-dat
rm -rf "$out"
mkdir -p "$out"
export BOTSIM_COVERAGE=1 BOTSIM_COVERAGE_DIR=$PWD/$out
. scripts/lib/tests.sh
load_test_binaries cpu_lockstep cpu_timing bot_spec scoreboard line_follow
# Two lanes: cpu_lockstep's longest test is one thread.
run_lanes "$out/tests" "cpu_lockstep" "line_follow bot_spec scoreboard cpu_timing"
verilator_coverage --write "$out/merged.dat" "$out"/cov-*.dat
python3 scripts/ci/coverage_report.py "$out/merged.dat" scripts/ci/coverage_floors.txt "$@"
