//! Subroutines that only compute: a call is run once and replayed from then on.
//!
//! Firmware spends most of its time in a few subroutines that touch nothing but registers: a
//! software delay (`LOAD s0, 18` / `SUB s0, 01` / `JUMP NZ`) called by a delay that counts
//! its calls (`LOAD s1, 28` / `CALL delay` / `SUB s1, 01` / `JUMP NZ`), called by another, and
//! so on; BotSim's firmware waits out its 50 ms main loop in four such levels. A subroutine
//! whose every instruction (and every callee's) is an ALU, `LOAD`, `JUMP`, `CALL` or `RETURN`
//! (no port, no scratch pad, no bank switch, no interrupt, no computed jump) runs the same
//! instructions, in the same cycles, to the same result, every time it is called with the
//! same flags, the same stack depth and the same values in the registers it reads before it
//! writes them (its *inputs*, found by a must-be-written dataflow over its code). So the first
//! call with each such key is simulated, instruction by instruction, and its effect recorded:
//! the cycles it took, the registers it wrote and their last values, the flags, and the stack
//! RAM entries its D cycles wrote (every D writes the entry at the depth counter). A later call
//! with the same key applies that effect at once, exactly as simulating it would leave the
//! core (tested against cycle-by-cycle simulation on random programs).
//!
//! ```
//! use kcpsm6::asm::assemble_str;
//! use kcpsm6::iss::{Config, Cpu, NullBus, Routines};
//! let p = assemble_str(
//!     "main: CALL wait\nADD s5, 01\nJUMP main\n\
//!      wait: LOAD s1, 28\nouter: CALL inner\nSUB s1, 01\nJUMP NZ, outer\nRETURN\n\
//!      inner: LOAD s0, 18\nspin: SUB s0, 01\nJUMP NZ, spin\nRETURN\n",
//! )
//! .unwrap();
//! let mut fast = Cpu::new(Config::default(), &p.image.words[..]);
//! let mut routines = Routines::default();
//! let mut bus = NullBus::default();
//! fast.run_with(&mut bus, 1_000_000, |_| false, &mut routines);
//! assert!(routines.replayed() > 0);
//! // The same cycles without replaying: every flop equal.
//! let mut slow = Cpu::new(Config::default(), &p.image.words[..]);
//! slow.run_fast(&mut bus, fast.cycle(), |_| false);
//! assert!(slow == fast);
//! ```

use std::collections::HashMap;
use std::sync::Arc;

use super::{reg_index, Cpu, StackEntry};
use crate::isa::{Cond, Opcode, ROM_WORDS};

/// The most call keys remembered (a program whose calls never repeat stops recording there).
const KEYS: usize = 4096;
/// The most subroutine levels recorded at once.
const LEVELS: usize = 8;

/// What is known of the subroutines of one program, and the effects of the calls recorded so
/// far. Used with [`Cpu::run_with`]; a `Routines` follows the program of the core it is used
/// with (a core with another program, or a written ROM, starts it afresh).
#[derive(Default)]
pub struct Routines {
    rom: Option<Arc<[u32; ROM_WORDS]>>,
    /// Per address: the subroutine starting there, once analysed (`None`: it is not one that
    /// only computes).
    analysed: Vec<Option<Option<Routine>>>,
    calls: HashMap<Key, Effect>,
    /// The calls being recorded, innermost last.
    recording: Vec<Recording>,
    replayed: u64,
}

/// A subroutine that only computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Routine {
    /// The registers (bank-relative) it may read before writing them.
    inputs: u16,
    /// The registers written on every path to its return.
    written: u16,
}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct Key {
    call_pc: u16,
    depth: u8,
    c: bool,
    z: bool,
    bank: bool,
    /// The inputs' values (0 for a register that is not one).
    inputs: [u8; 16],
}

/// What a recorded call did.
#[derive(Clone, Debug)]
struct Effect {
    cycles: u64,
    c: bool,
    z: bool,
    /// Register-file index and last value of every register it wrote.
    regs: Vec<(u8, u8)>,
    /// The stack RAM entries from the call's depth up.
    stack: Vec<StackEntry>,
}

struct Recording {
    key: Key,
    start: u64,
    /// Register-file indices written so far (a bit each).
    written: u32,
    /// The deepest depth counter seen at an instruction's start.
    deepest: u8,
}

impl Routines {
    /// How many calls were applied from a recording.
    pub fn replayed(&self) -> u64 {
        self.replayed
    }

    /// Make sure this follows `cpu`'s program.
    fn follow(&mut self, cpu: &Cpu) {
        if !self.rom.as_ref().is_some_and(|r| Arc::ptr_eq(r, &cpu.rom)) {
            *self = Routines { rom: Some(cpu.rom.clone()), analysed: vec![None; ROM_WORDS], ..Routines::default() };
        }
    }

    /// At an instruction's start in the steady state: when it is a call of a subroutine that
    /// only computes, recorded with this key and ending by `until`, apply it and say so;
    /// otherwise start recording it (when it is one).
    pub(super) fn at_instruction(&mut self, cpu: &mut Cpu, until: u64) -> bool {
        let w = cpu.instr;
        if Opcode::of(w) != Opcode::Call || !Cond::taken(w, cpu.c, cpu.z) {
            self.note_step(cpu);
            return false;
        }
        self.follow(cpu);
        let target = (w & 0xFFF) as u16;
        let Some(routine) = self.routine(&cpu.rom, target) else {
            self.note_step(cpu);
            return false;
        };
        let mut inputs = [0u8; 16];
        for (r, v) in inputs.iter_mut().enumerate() {
            if routine.inputs >> r & 1 == 1 {
                *v = cpu.regs[reg_index(cpu.bank, r as u32)];
            }
        }
        let key = Key { call_pc: cpu.pc, depth: cpu.depth, c: cpu.c, z: cpu.z, bank: cpu.bank, inputs };
        if let Some(e) = self.calls.get(&key) {
            if cpu.cycle + e.cycles <= until {
                let (d, span) = (cpu.depth, e.stack.len() as u8);
                for &(i, v) in &e.regs {
                    cpu.regs[i as usize] = v;
                }
                cpu.stack[d as usize..(d + span) as usize].copy_from_slice(&e.stack);
                (cpu.c, cpu.z) = (e.c, e.z);
                cpu.pc = (cpu.pc + 1) & 0xFFF;
                cpu.instr = cpu.rom[cpu.pc as usize];
                cpu.cycle += e.cycles;
                self.replayed += 1;
                let regs = e.regs.iter().fold(0u32, |m, &(i, _)| m | 1 << i);
                for r in &mut self.recording {
                    r.written |= regs;
                    r.deepest = r.deepest.max(d + span - 1);
                }
                return true;
            }
            self.note_step(cpu);
            return false;
        }
        self.note_step(cpu);
        if self.recording.len() < LEVELS && self.calls.len() < KEYS {
            self.recording.push(Recording { key, start: cpu.cycle, written: 0, deepest: cpu.depth });
        }
        false
    }

    /// Before an instruction that is simulated: what the calls being recorded must know of it
    /// (the depth its D writes the stack at, the register it writes).
    #[inline]
    fn note_step(&mut self, cpu: &Cpu) {
        if self.recording.is_empty() {
            return;
        }
        let w = cpu.instr;
        let op = Opcode::of(w);
        let reg = if op.writes_register() { 1u32 << reg_index(cpu.bank, w >> 8) } else { 0 };
        for r in &mut self.recording {
            r.written |= reg;
            r.deepest = r.deepest.max(cpu.depth);
        }
    }

    /// After an instruction (or a countdown fast-forward): a recorded call that has returned
    /// is kept.
    pub(super) fn after_instruction(&mut self, cpu: &Cpu) {
        while let Some(r) = self.recording.last() {
            if !(cpu.depth == r.key.depth && cpu.pc == (r.key.call_pc + 1) & 0xFFF) {
                return;
            }
            let r = self.recording.pop().expect("a recording");
            let d = r.key.depth as usize;
            let effect = Effect {
                cycles: cpu.cycle - r.start,
                c: cpu.c,
                z: cpu.z,
                regs: (0..32).filter(|i| r.written >> i & 1 == 1).map(|i| (i as u8, cpu.regs[i])).collect(),
                stack: cpu.stack[d..=r.deepest as usize].to_vec(),
            };
            self.calls.insert(r.key, effect);
        }
    }

    /// The core left the steady state, or the run stopped: what is being recorded is dropped.
    pub fn interrupted(&mut self) {
        self.recording.clear();
    }

    /// The subroutine at `target`, if it only computes.
    fn routine(&mut self, rom: &[u32; ROM_WORDS], target: u16) -> Option<Routine> {
        if let Some(r) = self.analysed[target as usize] {
            return r;
        }
        // A recursive call while analysing: not one (a guard entry until the answer is known).
        self.analysed[target as usize] = Some(None);
        let r = self.analyse(rom, target);
        self.analysed[target as usize] = Some(r);
        r
    }

    /// The must-be-written dataflow over the subroutine's code (bank-relative registers): the
    /// registers written on every path to each instruction; an instruction reading one that
    /// is not makes it an input.
    fn analyse(&mut self, rom: &[u32; ROM_WORDS], entry: u16) -> Option<Routine> {
        // Written on every path to the instruction, for those reached so far.
        let mut written: HashMap<u16, u16> = HashMap::new();
        let mut work = vec![(entry, 0u16)];
        let (mut inputs, mut at_return, mut returns) = (0u16, u16::MAX, false);
        while let Some((pc, into)) = work.pop() {
            let now = match written.get(&pc) {
                Some(&w) if w & into == w => continue,
                Some(&w) => w & into,
                None => into,
            };
            written.insert(pc, now);
            if written.len() > 1024 {
                return None;
            }
            let w = rom[pc as usize];
            let op = Opcode::of(w);
            let (x, y) = (1u16 << (w >> 8 & 15), 1u16 << (w >> 4 & 15));
            let constant = w >> 12 & 1 == 1;
            let next = (pc + 1) & 0xFFF;
            let conditional = Cond::of(w).is_some();
            let mut read = |mask: u16| inputs |= mask & !now;
            use Opcode::*;
            match op {
                Load => {
                    if !constant {
                        read(y);
                    }
                    work.push((next, now | x));
                }
                And | Or | Xor | Test | TestCy | Add | AddCy | Sub | SubCy | Compare | CompareCy => {
                    read(x | if constant { 0 } else { y });
                    work.push((next, if op.writes_register() { now | x } else { now }));
                }
                Shift => {
                    if w & 0x80 == 0 {
                        read(x);
                    }
                    work.push((next, now | x));
                }
                Jump => {
                    work.push(((w & 0xFFF) as u16, now));
                    if conditional {
                        work.push((next, now));
                    }
                }
                Call => {
                    let callee = self.routine(rom, (w & 0xFFF) as u16)?;
                    inputs |= callee.inputs & !now;
                    work.push((next, now | callee.written));
                    if conditional {
                        work.push((next, now));
                    }
                }
                Return | LoadReturn => {
                    let out = if op == LoadReturn { now | x } else { now };
                    at_return &= out;
                    returns = true;
                    if conditional {
                        work.push((next, now));
                    }
                }
                Input | Fetch | Star | CallAt | JumpAt | Interrupt | ReturnI | OutputK | Output | Store | RegBank
                | Nop => return None,
            }
        }
        // A subroutine that never returns is no call to replay.
        returns.then_some(Routine { inputs, written: at_return })
    }
}
