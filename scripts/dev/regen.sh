#!/usr/bin/env bash
# Regenerate the files kept in rtl/ for FPGA users from their sources:
#   rtl/bot_pgm.v          from rtl/bot_pgm.psm (the firmware with its default constants)
#   rtl/default_world.mem  from the built-in world (core/src/world.rs)
#   examples/common/proj2demo.v  from its proj2demo.psm
#   examples/nexys4_vga/icon.v   from the display icon (core/src/render.rs)
set -euo pipefail
cd "$(dirname "$0")/../.."
BOTSIM_BLESS=1 cargo test --workspace --release --test generated -q
git status --short rtl/bot_pgm.v rtl/default_world.mem examples/common/proj2demo.v examples/nexys4_vga/icon.v
