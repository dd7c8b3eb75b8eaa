#!/usr/bin/env bash
# Mutation check of the BotSim testbench: apply one deliberate bug at a time to
# rtl/bot_pgm.psm, run the system tests, and report which test caught it. Restores the file.
# Usage: scripts/dev/mutate-firmware.sh [NAME-PATTERN]   (all mutations by default; several minutes)
set -uo pipefail
cd "$(dirname "$0")/../.."
src=rtl/bot_pgm.psm

# name | sed expression (applied to rtl/bot_pgm.psm)
mutations=(
  "rm_dist not cleared on a threshold event|/^        LOAD rm_dist, 00$/d"
  "line sensors active high|s/^        LOAD sensors, 00$/        LOAD sensors, 01/"
  "front obstruction sets only ProxL|s/OR sensors, PROX_BOTH/OR sensors, PROX_L/"
  "SW quirk always on|s/LOAD s7, compat_botsim20/LOAD s7, 01/"
  "no wait before the map read|/LOAD s5, s5                   ; one instruction/d"
  "upd_sysregs written once|0,/OUTPUT s0, PRW_UPDSYSREGS/{/OUTPUT s0, PRW_UPDSYSREGS/d}"
  "reverse moves forward|s/^        ADD s6, 04$/        ADD s6, 00/"
  "speed bits switch the left motor|s/TEST motctl, LM_ON/TEST motctl, E0/"
  "slow left turns right|s/^        SUB orient, 01$/        ADD orient, 01/"
  "right counter ignored in the threshold test|/^        COMPARE rm_dist, threshold$/d"
  "no initial register dump|s/^        CALL publish_snapshot         ; sample 0.*$/        LOAD s0, s0/"
  "obstruction rule also blocks line cells|s/^        RETURN Z                      ; blocked: stay$/        RETURN NC/"
  "diagonal L/R use the 90-degree step|s/^        LOAD s0, 01                   ; ... or 45 degrees on a diagonal$/        LOAD s0, 02/"
)

. scripts/dev/mutate-lib.sh
mutate "$src" "${1:-}" --test bot_spec --test scoreboard --test cli_run -- "${mutations[@]}"
