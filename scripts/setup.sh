#!/usr/bin/env bash
# Installs what botsim needs on a fresh Debian machine (bookworm): Verilator 5.006 to build the
# RTL model, libclang for bindgen, GHDL for board designs with VHDL modules, Icarus Verilog +
# Yosys for the CI gate, python3 for its coverage report, GTKWave and a virtual X server
# (Xvfb) for the test that opens a board waveform's save file in GTKWave, Chromium for the
# test that plays the live board's page in a real (headless) browser.
# Safe to run twice: it only installs what is missing.
set -euo pipefail

need=()
command -v verilator >/dev/null 2>&1 || need+=(verilator)
command -v iverilog  >/dev/null 2>&1 || need+=(iverilog)
command -v yosys     >/dev/null 2>&1 || need+=(yosys)
command -v ghdl      >/dev/null 2>&1 || need+=(ghdl)
command -v git       >/dev/null 2>&1 || need+=(git)
dpkg -s libclang-dev >/dev/null 2>&1 || need+=(libclang-dev)
command -v g++       >/dev/null 2>&1 || need+=(g++)
command -v make      >/dev/null 2>&1 || need+=(make)
command -v bc        >/dev/null 2>&1 || need+=(bc)
command -v python3   >/dev/null 2>&1 || need+=(python3)
command -v gtkwave   >/dev/null 2>&1 || need+=(gtkwave)
command -v xvfb-run  >/dev/null 2>&1 || need+=(xvfb xauth)
[ -x /usr/bin/chromium ]             || need+=(chromium)

if [ ${#need[@]} -gt 0 ]; then
  echo "setup: installing ${need[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

if ! command -v cargo >/dev/null 2>&1; then
  echo "setup: cargo not found; install Rust (rustup) first" >&2
  exit 1
fi
echo "setup: $(verilator --version | head -1); $(iverilog -V 2>&1 | head -1); $(yosys -V); $(ghdl --version | head -1)"
