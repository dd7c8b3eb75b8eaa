#!/usr/bin/env bash
# Mutation check of the CPU testbench: apply one deliberate bug at a time to rtl/kcpsm6.v,
# run the CPU tests, and report which test caught it. Restores the file afterwards.
# Usage: scripts/mutate-cpu.sh [NAME-PATTERN]   (all mutations by default; several minutes)
set -uo pipefail
cd "$(dirname "$0")/.."
src=rtl/kcpsm6.v

# name | sed expression (applied to rtl/kcpsm6.v)
mutations=(
  "no Z chaining|s/wire       z_chain     = with_carry \& (op_test | op_add | op_sub | op_compare);/wire       z_chain     = 1'b0;/"
  "COMPARE writes its result|s/op_star | op_sub | op_load_return;/op_star | op_sub | op_compare | op_load_return;/"
  "OUTPUTK also raises write_strobe|s/write_strobe_q      <= in_decode \& ~take_interrupt \& op_output;/write_strobe_q      <= in_decode \& ~take_interrupt \& (op_output | op_outputk);/"
  "TEST carry ignores parity|s/op_test  ? (^test_result) ^ carry_in :/op_test  ? carry_in :/"
  "SUBCY borrow-in ignored|s/wire \[8:0\] diff      = {1'b0, sx} - {1'b0, operand} - {8'd0, carry_in};/wire [8:0] diff      = {1'b0, sx} - {1'b0, operand};/"
  "HWBUILD clears carry|s/wire       shift_carry  = hwbuild_op | (shift_right ? sx\[0\] : sx\[7\]);/wire       shift_carry  = ~hwbuild_op \& (shift_right ? sx[0] : sx[7]);/"
  "bank copy not registered|s/wire \[ 7:0\] sx = registers\[{bank_rd, sx_addr}\];/wire [ 7:0] sx = registers[{bank, sx_addr}];/"
  "no self-start (run ignored)|s/internal_reset <= reset | ~run;/internal_reset <= reset;/"
  "reset one cycle shorter|s/run            <= ~reset \& (run | internal_reset) \& ~stack_error;/run            <= ~reset \& ~stack_error;/"
  "stack depth 31|s/localparam \[4:0\] STACK_DEPTH = 5'd30;/localparam [4:0] STACK_DEPTH = 5'd31;/"
  "interrupt does not cancel the write|s/register_write_q    <= in_decode \& ~take_interrupt \& writes_register;/register_write_q    <= in_decode \& writes_register;/"
  "interrupt recognised in D cycles too|s/else if (in_fetch \&\& interrupt_enable \&\& interrupt_q)/else if (~in_decode \&\& interrupt_enable \&\& interrupt_q)/"
  "RETURNI does not restore flags|s/else if (flag_restore_q)/else if (1'b0)/"
  "RETURN resumes at the CALL|s/do_return ? stack_top\[11:0\] + 12'd1 :/do_return ? stack_top[11:0] :/"
  "sleep ignored in D|s/default: t_state <= sleep_q ? T_IDLE : T_FETCH;/default: t_state <= (t_state == T_IDLE \&\& sleep_q) ? T_IDLE : T_FETCH;/"
  "out-of-range scratch-pad stores dropped, not aliased|s/            scratch_pad\[operand\[SPM_BITS-1:0\]\] <= sx;/            if ({24'd0, operand} < scratch_pad_memory_size) scratch_pad[operand[SPM_BITS-1:0]] <= sx;/"
  "interrupt_ack one cycle late|s/interrupt_ack_q <= in_decode \& take_interrupt;/interrupt_ack_q <= in_fetch \& (pc == interrupt_vector);/"
  "strobe ignores a pending interrupt (in D)|s/read_strobe_q       <= in_decode \& ~take_interrupt \& op_input;/read_strobe_q       <= in_decode \& op_input;/"
)

. scripts/mutate-lib.sh
mutate "$src" "${1:-}" --test cpu_lockstep --test cpu_timing -- "${mutations[@]}"
