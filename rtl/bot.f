# The `bot` design (BotSim 2.0), one file per line, relative to the repository, in order.
# Read by build.rs, scripts/ci/gate.sh, scripts/lib/icarus-bot.sh, scripts/dev/measure-fst.sh.
# .vlt files are Verilator waivers (other tools skip them). bot_pgm.v is not listed: it is
# generated from rtl/bot_pgm.psm (build.rs, `botsim firmware`; rtl/bot_pgm.v is the kept copy).
rtl/kcpsm6.vlt
rtl/bot.vlt
rtl/kcpsm6.v
rtl/world_if.v
rtl/map.v
rtl/world_map.v
rtl/bot.v
