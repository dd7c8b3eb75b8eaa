# rtl.sh: read a design's file list (rtl/bot.f, rtl/sim/cpu.f). Sourced, not run.
#   rtl_files LIST        every file, one per line (Verilator: waivers and Verilog)
#   rtl_files LIST v      only the Verilog (for Icarus, Yosys)
rtl_files() {
  grep -v '^[[:space:]]*#' "$1" | grep -v '^[[:space:]]*$' | if [ "${2:-}" = v ]; then grep '\.v$'; else cat; fi
}
