#!/usr/bin/env bash
# Mutation check of the CPU testbench: apply one deliberate bug at a time to rtl/kcpsm6.v,
# run the CPU tests, and report which test caught it. Restores the file afterwards.
# The "old:" entries put back what the core did before the spec's §2.2/§2.4-§2.8 corrections.
# Usage: scripts/dev/mutate-cpu.sh [NAME-PATTERN]   (all mutations by default; several minutes)
set -uo pipefail
cd "$(dirname "$0")/../.."
src=rtl/kcpsm6.v

# name | sed expression (applied to rtl/kcpsm6.v)
mutations=(
  "no Z chaining|s/wire       z_chain     = with_carry \& (op_test | op_add | op_sub | op_compare);/wire       z_chain     = 1'b0;/"
  "COMPARE writes its result|s/op_star | op_sub | op_load_return;/op_star | op_sub | op_compare | op_load_return;/"
  "OUTPUTK also raises write_strobe|s/write_strobe_q      <= in_decode \& ~active_interrupt \& op_output;/write_strobe_q      <= in_decode \& ~active_interrupt \& (op_output | op_outputk);/"
  "TEST carry ignores parity|s/op_test  ? (^test_result) ^ carry_in :/op_test  ? carry_in :/"
  "SUBCY borrow-in ignored|s/wire \[8:0\] diff      = {1'b0, sx} - {1'b0, operand} - {8'd0, carry_in};/wire [8:0] diff      = {1'b0, sx} - {1'b0, operand};/"
  "HWBUILD clears carry|s/wire       shift_carry  = hwbuild_op | (shift_right ? sx\[0\] : sx\[7\]);/wire       shift_carry  = ~hwbuild_op \& (shift_right ? sx[0] : sx[7]);/"
  "sX reads the live bank (no xb)|s/wire \[ 7:0\] sx = registers\[{xb, sx_addr}\];/wire [ 7:0] sx = registers[{bank, sx_addr}];/"
  "xb ignores STAR|s/xb             <= in_fetch ? bank : bank ^ op_star;/xb             <= bank;/"
  "no self-start (run ignored)|s/internal_reset <= reset | ~run | stack_error;/internal_reset <= reset | stack_error;/"
  "reset one cycle shorter|s/run            <= ~reset \& (run | internal_reset) \& ~stack_error;/run            <= ~reset \& ~stack_error;/"
  "stack error one level early|s/wire        stack_error = in_fetch \& (depth == 5'd31);/wire        stack_error = in_fetch \& (depth >= 5'd30);/"
  "interrupt does not cancel the write|s/register_write_q    <= in_decode \& ~active_interrupt \& writes_register;/register_write_q    <= in_decode \& writes_register;/"
  "interrupt recognised in idle cycles too|s/active_interrupt <= in_fetch \& interrupt_enable \& interrupt_q;/active_interrupt <= ~in_decode \& interrupt_enable \& interrupt_q;/"
  "RETURNI does not restore flags|s/                           op_returni;  \/\/ RETURNI: the flags saved on the stack/                           1'b0;/"
  "RETURN resumes at the CALL|s/do_return ? stack_top\[11:0\] + 12'd1 :/do_return ? stack_top[11:0] :/"
  "sleep ignored in D|s/default: t_state <= sleep_q ? T_IDLE : T_FETCH;/default: t_state <= (t_state == T_IDLE \&\& sleep_q) ? T_IDLE : T_FETCH;/"
  "out-of-range scratch-pad stores dropped, not aliased|s/            scratch_pad\[spm_addr\] <= sx;/            if ({24'd0, operand} < scratch_pad_memory_size) scratch_pad[spm_addr] <= sx;/"
  "interrupt_ack one cycle late|s/interrupt_ack_q  <= active_interrupt;/interrupt_ack_q  <= in_fetch \& (pc == interrupt_vector);/"
  "strobe ignores a pending interrupt|s/read_strobe_q       <= in_decode \& ~active_interrupt \& op_input;/read_strobe_q       <= in_decode \& op_input;/"
  # The behaviour before the spec corrections, one mechanism at a time (spec kcpsm6.md):
  "old: stack error from the push or pop in D (2.5)|s/wire        stack_error = in_fetch \& (depth == 5'd31);/wire        stack_error = in_decode \& ((stack_push \& (depth >= 5'd30)) | (stack_pop \& (depth == 5'd0)));/;s/internal_reset <= reset | ~run | stack_error;/internal_reset <= reset | ~run;/"
  "old: a pre-empted REGBANK keeps the bank (2.6)|s/if (op_regbank) bank <= instruction\[0\];/if (op_regbank \& ~active_interrupt) bank <= instruction[0];/"
  "old: a pre-empted RETURNI keeps the bank (2.6)|s/if (op_returni) bank <= stack_top\[14\];/if (op_returni \& ~active_interrupt) bank <= stack_top[14];/"
  "old: the internal reset clears interrupt recognition (2.6)|s/active_interrupt <= in_fetch \& interrupt_enable \& interrupt_q;/active_interrupt <= ~internal_reset \& in_fetch \& interrupt_enable \& interrupt_q;/"
  "old: ack only after an entry D (2.6)|s/interrupt_ack_q  <= active_interrupt;/interrupt_ack_q  <= active_interrupt \& in_decode;/"
  "old: sY reads the registered bank too (2.8)|s/wire \[ 7:0\] sy = registers\[{bank, sy_addr}\];/wire [ 7:0] sy = registers[{xb, sy_addr}];/"
  "old: the ALU result is taken in the second cycle (2.8)|s/registers\[{xb, sx_addr}\] <= op_input ? in_port : result_q;/registers[{xb, sx_addr}] <= op_input ? in_port : alu_result;/"
)

. scripts/dev/mutate-lib.sh
mutate "$src" "${1:-}" --test cpu_lockstep --test cpu_timing -- "${mutations[@]}"
