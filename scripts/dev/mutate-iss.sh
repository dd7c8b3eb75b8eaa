#!/usr/bin/env bash
# Mutation check of the ISS against the same tests as the RTL: apply one deliberate bug at a
# time to kcpsm6/src/iss.rs, run the CPU spec and lock-step tests (they run every spec rule on
# the ISS as well as on the RTL) and the ISS's own tests, and report which test caught it.
# The "old:" entries put back what the ISS did before the spec's §2.4-§2.8 corrections.
# Usage: scripts/dev/mutate-iss.sh [NAME-PATTERN]
set -uo pipefail
cd "$(dirname "$0")/../.."
src=kcpsm6/src/iss.rs

# name | sed expression (applied to kcpsm6/src/iss.rs)
mutations=(
  "old: stack error checked in D too (2.5)|s/let stack_error = in_fetch \&\& self.depth == STACK_ERROR_DEPTH;/let stack_error = phase != Phase::Idle \&\& self.depth == STACK_ERROR_DEPTH;/"
  "stack error checked while asleep too (2.5)|s/let stack_error = in_fetch \&\& self.depth == STACK_ERROR_DEPTH;/let stack_error = phase != Phase::Decode \&\& self.depth == STACK_ERROR_DEPTH;/"
  "old: a pre-empted REGBANK keeps the bank (2.6)|s/Opcode::RegBank => self.bank = w \& 1 == 1,/Opcode::RegBank if !entry => self.bank = w \& 1 == 1,/"
  "old: a pre-empted RETURNI keeps the bank (2.6)|s/Opcode::ReturnI => self.bank = top.bank,/Opcode::ReturnI if !entry => self.bank = top.bank,/"
  "old: the internal reset clears interrupt recognition (2.6)|s/let active_next = in_fetch \&\& self.ie \&\& self.irq_reg;/let active_next = in_fetch \&\& self.ie \&\& self.irq_reg \&\& !self.internal_reset;/"
  "old: sY reads the registered bank too (2.8)|s/self.regs\[reg_index(self.bank, self.instr >> 4)\]/self.regs[reg_index(self.xb, self.instr >> 4)]/"
  "xb ignores STAR (2.8)|s/let xb_next = if in_fetch { self.bank } else { self.bank ^ (Opcode::of(self.instr) == Opcode::Star) };/let xb_next = self.bank;/"
  "old: the ALU result is taken in the second cycle (2.8)|s/let v = if p.op == Opcode::Input { input } else { p.result };/let v = if p.op == Opcode::Input { input } else { self.alu(p.op, StackEntry::default()).0 };/"
  "interrupt does not cancel the write|s/if p.kind == RetireKind::Interrupt {/if false {/"
  "fast path: STAR's D not seen by xb|s/^            self.xb = self.bank ^ (Opcode::of(self.instr) == Opcode::Star);/            self.xb = self.bank;/"
  "fast path: no countdown fast-forward end state|s/^        self.z = true;$/        self.z = false;/"
  "RETURN resumes at the CALL|s/Opcode::Return | Opcode::LoadReturn if taken => (top.pc + 1) \& 0xFFF,/Opcode::Return | Opcode::LoadReturn if taken => top.pc,/"
)

. scripts/dev/mutate-lib.sh
mutate "$src" "${1:-}" --test cpu_lockstep --test cpu_timing --test iss -- "${mutations[@]}"
