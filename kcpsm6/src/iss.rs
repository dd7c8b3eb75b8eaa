//! A cycle-exact KCPSM6 instruction-set simulator.
//!
//! The simulator is the RTL core's flops in Rust, one for one (spec §2): each instruction takes
//! a **D** cycle (operands read and the ALU result registered; PC, call-stack depth, IE and bank
//! update at its end) and a second cycle (normally **F**, which fetches the next word) in which
//! the register, flag and scratch-pad writes and the port strobes happen. Reset, sleep and
//! interrupt are sampled per clock, so every port of every cycle matches `rtl/kcpsm6.v`; the
//! lock-step tests compare the two cycle by cycle.
//!
//! Peripherals are modelled by a [`Bus`]; each completed instruction yields a [`Retired`]
//! record for lock-step comparison.
//!
//! ```
//! use kcpsm6::iss::{Cpu, Config, NullBus};
//! use kcpsm6::asm::assemble_str;
//! let prog = assemble_str("LOAD s0, 41\nADD s0, 01\nOUTPUT s0, 07\nloop: JUMP loop\n").unwrap();
//! let mut cpu = Cpu::new(Config::default(), &prog.image.words[..]);
//! let mut bus = NullBus::default();
//! let r = cpu.run_instructions(3, &mut bus).unwrap();
//! assert_eq!(r.port.unwrap().value, 0x42);
//! // Self-start: the first D cycle is cycle 5, so the OUTPUT (third instruction) strobes in 10.
//! assert_eq!(r.port.unwrap().cycle, 10);
//! ```

use std::sync::Arc;

use crate::isa::{Cond, Opcode, ROM_WORDS, WORD_MASK};

mod routines;
pub use routines::Routines;

/// Usable call-stack depth (an interrupt uses one level). One more level leaves the wrapping
/// depth counter at [`STACK_ERROR_DEPTH`], as does a pop at depth 0.
pub const STACK_DEPTH: u8 = 30;
/// The depth that an F cycle recognises as a stack error (§2.5).
pub const STACK_ERROR_DEPTH: u8 = 31;

/// Core parameters, as on the Verilog module.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Config {
    /// Value loaded by `HWBUILD`.
    pub hwbuild: u8,
    /// Address jumped to on an interrupt (12 bits).
    pub interrupt_vector: u16,
    /// Scratch-pad size in bytes: 64, 128 or 256.
    pub scratch_pad_size: ScratchPad,
}

impl Default for Config {
    fn default() -> Self {
        Config { hwbuild: 0, interrupt_vector: 0x3FF, scratch_pad_size: ScratchPad::B64 }
    }
}

/// The legal scratch-pad sizes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScratchPad {
    B64,
    B128,
    B256,
}

impl ScratchPad {
    pub fn bytes(self) -> usize {
        match self {
            ScratchPad::B64 => 64,
            ScratchPad::B128 => 128,
            ScratchPad::B256 => 256,
        }
    }

    /// The size for a byte count, if it is one of 64, 128, 256.
    pub fn from_bytes(n: usize) -> Option<ScratchPad> {
        match n {
            64 => Some(ScratchPad::B64),
            128 => Some(ScratchPad::B128),
            256 => Some(ScratchPad::B256),
            _ => None,
        }
    }
}

/// Input pins sampled at the end of a cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pins {
    pub reset: bool,
    pub sleep: bool,
    pub interrupt: bool,
}

/// The peripherals on the port bus.
pub trait Bus {
    /// The value on `in_port` at the end of `cycle`, the strobe cycle of an INPUT whose
    /// `port_id` is `port`.
    fn input(&mut self, port: u8, cycle: u64) -> u8;
    /// An OUTPUT: `write_strobe` is high in `cycle` with `port_id` = `port`, `out_port` = `value`.
    fn output(&mut self, port: u8, value: u8, cycle: u64);
    /// An OUTPUTK (`k_write_strobe`).
    fn output_k(&mut self, port: u8, value: u8, cycle: u64);
}

/// A bus that reads 0 (or a fixed value) and ignores writes.
#[derive(Clone, Copy, Debug, Default)]
pub struct NullBus {
    pub input_value: u8,
}

impl Bus for NullBus {
    fn input(&mut self, _port: u8, _cycle: u64) -> u8 {
        self.input_value
    }
    fn output(&mut self, _port: u8, _value: u8, _cycle: u64) {}
    fn output_k(&mut self, _port: u8, _value: u8, _cycle: u64) {}
}

pub use crate::isa::PortKind;

/// One strobe on the port bus.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PortEvent {
    pub kind: PortKind,
    pub port: u8,
    pub value: u8,
    /// The cycle in which the strobe is high.
    pub cycle: u64,
}

impl std::fmt::Display for PortEvent {
    /// `cycle 10: OUTPUT port 07 value 42`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = match self.kind {
            PortKind::Read => "INPUT",
            PortKind::Write => "OUTPUT",
            PortKind::KWrite => "OUTPUTK",
        };
        write!(f, "cycle {}: {what} port {:02X} value {:02X}", self.cycle, self.port, self.value)
    }
}

/// What completed: an instruction, or the interrupt entry that cancelled one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RetireKind {
    Executed,
    /// The instruction at `pc` was cancelled; its address, flags and bank were pushed.
    Interrupt,
}

/// The record of one completed instruction, taken after its second cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Retired {
    pub kind: RetireKind,
    /// Cycle of the instruction's D (first) cycle.
    pub cycle: u64,
    pub pc: u16,
    pub word: u32,
    /// Register written: (bank B?, register index, value).
    pub reg_write: Option<(bool, u8, u8)>,
    /// Scratch-pad write: (address, value).
    pub spm_write: Option<(u8, u8)>,
    pub port: Option<PortEvent>,
    pub c: bool,
    pub z: bool,
    /// Active bank (false = A, true = B).
    pub bank: bool,
    pub ie: bool,
    /// Call-stack depth.
    pub depth: u8,
    /// PC after the instruction (the address of the next one).
    pub next_pc: u16,
}

/// The sequencer state (`t_state` in the spec).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// 00: reset sequence or sleep; no fetch.
    Idle,
    /// F (10): fetch the next word; second cycle of an instruction.
    Fetch,
    /// D (01): first cycle of an instruction.
    Decode,
}

/// One entry of the 32-entry stack RAM.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct StackEntry {
    pc: u16,
    c: bool,
    z: bool,
    bank: bool,
}

/// The flops loaded at the end of a D cycle for the second cycle: what to do (the action
/// flops, all clear when an interrupt pre-empted the instruction) and the ALU's registered
/// result, carry and zero (§2.8: computed from the operands as they were in D).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Pending {
    kind: RetireKind,
    /// The D cycle.
    cycle: u64,
    pc: u16,
    word: u32,
    op: Opcode,
    result: u8,
    carry: bool,
    zero: bool,
}

/// A failure to reach a retirement within a cycle budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("no instruction completed within {0} cycles")]
pub struct Timeout(pub u64);

/// The KCPSM6 core: the RTL's flops, named as there.
#[derive(Clone, PartialEq, Eq)]
pub struct Cpu {
    config: Config,
    /// The program, shared between copies of the core (copying a core does not copy it; a
    /// write does), so comparing copies compares it by identity first.
    rom: Arc<[u32; ROM_WORDS]>,
    /// s0..sF of bank A, then of bank B.
    regs: [u8; 32],
    spm: [u8; 256],
    stack: [StackEntry; 32],
    /// The wrapping call-stack depth counter (§2.5).
    depth: u8,
    pc: u16,
    c: bool,
    z: bool,
    ie: bool,
    /// The active bank: the sY read port's bank (§2.8).
    bank: bool,
    /// The bank of the sX read port and the write port, loaded every cycle with
    /// `F ? bank : bank ^ is_STAR` (§2.8).
    xb: bool,
    phase: Phase,
    run: bool,
    internal_reset: bool,
    sleep_reg: bool,
    irq_reg: bool,
    /// Loaded every cycle with `F & IE & irq_reg`, never reset: this D is an interrupt entry.
    active_interrupt: bool,
    interrupt_ack: bool,
    /// The word on `instruction` (the ROM's output register).
    instr: u32,
    pending: Option<Pending>,
    cycle: u64,
}

/// Register-file index of register `r` in bank `b`.
#[inline]
fn reg_index(b: bool, r: u32) -> usize {
    (b as usize) << 4 | (r & 15) as usize
}

impl Cpu {
    /// A core in its configuration state (cycle 0), self-starting from address 000.
    pub fn new(config: Config, rom: &[u32]) -> Cpu {
        let mut image = Box::new([0u32; ROM_WORDS]);
        for (dst, src) in image.iter_mut().zip(rom) {
            *dst = src & WORD_MASK;
        }
        Cpu {
            config,
            rom: Arc::from(image),
            regs: [0; 32],
            spm: [0; 256],
            stack: [StackEntry::default(); 32],
            depth: 0,
            pc: 0,
            c: false,
            z: false,
            ie: false,
            bank: false,
            xb: false,
            phase: Phase::Idle,
            run: false,
            internal_reset: false,
            sleep_reg: false,
            irq_reg: false,
            active_interrupt: false,
            interrupt_ack: false,
            instr: 0,
            pending: None,
            cycle: 0,
        }
    }

    pub fn config(&self) -> Config {
        self.config
    }

    /// The number of the cycle that the next [`Cpu::tick`] simulates.
    pub fn cycle(&self) -> u64 {
        self.cycle
    }

    /// Everything that decides what the core does next is as in `other`, whatever their
    /// cycle counts: with the same pins from now on, both do the same thing. A board's
    /// fast-forward takes a core whose state repeats as repeating ([`Cpu::skip_period`]).
    /// Cheap: copies of a core share its ROM, which is compared by identity first.
    ///
    /// ```
    /// use kcpsm6::iss::{Config, Cpu, NullBus, Pins};
    /// let program = kcpsm6::asm::assemble_str("top: ADD s0, 00\nJUMP top\n").unwrap();
    /// let mut cpu = Cpu::new(Config::default(), &program.image.words[..]);
    /// let mut bus = NullBus::default();
    /// cpu.run_instructions(10, &mut bus).unwrap();
    /// let before = cpu.clone();
    /// cpu.run_instructions(2, &mut bus).unwrap(); // once around the loop: s0 stays 0
    /// assert!(cpu.same_state_as(&before) && cpu.cycle() == before.cycle() + 4);
    /// cpu.tick(Pins::default(), &mut bus);
    /// assert!(!cpu.same_state_as(&before));
    /// ```
    pub fn same_state_as(&self, other: &Cpu) -> bool {
        // The one behind, moved on to the other's cycle count, equal in every flop: a field
        // added to the core is compared without anyone remembering to.
        let (ahead, behind) = if self.cycle >= other.cycle { (self, other) } else { (other, self) };
        let mut moved = behind.clone();
        moved.skip_period(ahead.cycle - behind.cycle);
        moved == *ahead
    }

    /// Count `cycles` more without simulating them: only for a core whose state repeats
    /// every `cycles` cycles with its pins held ([`Cpu::same_state_as`] an earlier copy of
    /// itself), when what it would do in them is what it has just done.
    pub fn skip_period(&mut self, cycles: u64) {
        self.cycle += cycles;
        if let Some(p) = &mut self.pending {
            p.cycle += cycles;
        }
    }

    pub fn pc(&self) -> u16 {
        self.pc
    }

    /// Held in reset (by the pin, or by the internal reset after power-up or a stack error).
    pub fn in_reset(&self) -> bool {
        self.internal_reset
    }

    /// The `run` flop: clear from configuration, a reset or a stack error until the reset
    /// sequence has passed it (§2.4).
    pub fn running(&self) -> bool {
        self.run
    }

    pub fn phase(&self) -> Phase {
        self.phase
    }

    pub fn carry(&self) -> bool {
        self.c
    }

    pub fn zero(&self) -> bool {
        self.z
    }

    pub fn interrupt_enabled(&self) -> bool {
        self.ie
    }

    /// Active bank: false = A, true = B.
    pub fn bank(&self) -> bool {
        self.bank
    }

    /// The bank the sX read port and the write port address in this cycle (§2.8).
    pub fn sx_bank(&self) -> bool {
        self.xb
    }

    /// True in a D cycle that enters the interrupt (the request was recognised in the F
    /// before it; the flop that also times `interrupt_ack`).
    pub fn interrupt_entry(&self) -> bool {
        self.active_interrupt
    }

    /// The registered `interrupt` pin: the request an F cycle would recognise now.
    pub fn interrupt_registered(&self) -> bool {
        self.irq_reg
    }

    /// Call-stack depth (0..=31; 31 only transiently, as a stack error, §2.5).
    pub fn depth(&self) -> u8 {
        self.depth
    }

    /// Register `r` (0..15) of bank A (`bank_b` false) or B.
    pub fn reg(&self, bank_b: bool, r: u8) -> u8 {
        self.regs[reg_index(bank_b, r as u32)]
    }

    pub fn set_reg(&mut self, bank_b: bool, r: u8, v: u8) {
        self.regs[reg_index(bank_b, r as u32)] = v;
    }

    /// Both banks: A's s0..sF then B's.
    pub fn regs(&self) -> &[u8; 32] {
        &self.regs
    }

    /// The scratch pad (only the first `scratch_pad_size` bytes are addressable).
    pub fn scratch_pad(&self) -> &[u8] {
        &self.spm[..self.config.scratch_pad_size.bytes()]
    }

    pub fn rom(&self) -> &[u32; ROM_WORDS] {
        &self.rom
    }

    /// Replace one program word (for self-modifying test set-ups and ROM loading).
    pub fn write_rom(&mut self, addr: u16, word: u32) {
        Arc::make_mut(&mut self.rom)[addr as usize & 0xFFF] = word & WORD_MASK;
    }

    /// The `interrupt_ack` output in the current cycle.
    pub fn interrupt_ack(&self) -> bool {
        self.interrupt_ack
    }

    /// The `bram_enable` output in the current cycle.
    pub fn bram_enable(&self) -> bool {
        self.phase == Phase::Fetch
    }

    /// The word on `instruction` in the current cycle.
    pub fn instruction(&self) -> u32 {
        self.instr
    }

    /// sX of the word on `instruction`, through the `xb` port.
    #[inline]
    fn sx(&self) -> u8 {
        self.regs[reg_index(self.xb, self.instr >> 8)]
    }

    /// sY of the word on `instruction`, through the live-bank port.
    #[inline]
    fn sy(&self) -> u8 {
        self.regs[reg_index(self.bank, self.instr >> 4)]
    }

    /// The second operand: the constant of an odd opcode, else sY.
    #[inline]
    fn operand(&self) -> u8 {
        if self.instr & 1 << 12 != 0 {
            self.instr as u8
        } else {
            self.sy()
        }
    }

    #[inline]
    fn spm_addr(&self) -> usize {
        self.operand() as usize & (self.config.scratch_pad_size.bytes() - 1)
    }

    /// `out_port` in the current cycle: `instruction[13] ? instruction[11:4] : sX`.
    pub fn out_port(&self) -> u8 {
        if self.instr & 1 << 13 != 0 {
            (self.instr >> 4) as u8
        } else {
            self.sx()
        }
    }

    /// `port_id` in the current cycle: `instruction[12] ? instruction[7:0] : sY`.
    pub fn port_id(&self) -> u8 {
        if self.instr & 1 << 12 != 0 {
            self.instr as u8
        } else {
            self.sy()
        }
    }

    /// The strobe kind high in the current cycle, if any.
    pub fn strobe(&self) -> Option<PortKind> {
        let p = self.pending.as_ref()?;
        if p.kind != RetireKind::Executed {
            return None;
        }
        p.op.strobe()
    }

    /// Simulate one clock cycle: the state during cycle [`Cpu::cycle`] and the rising edge
    /// at its end, with `pins` sampled at that edge. Returns the record of an instruction
    /// whose second cycle this was (inlined: a caller that drops it does not build it).
    #[inline(always)]
    pub fn tick<B: Bus>(&mut self, pins: Pins, bus: &mut B) -> Option<Retired> {
        let cycle = self.cycle;
        let phase = self.phase;
        let in_fetch = phase == Phase::Fetch;

        // Flops loaded from this cycle's values, taken before anything below changes them.
        let xb_next = if in_fetch { self.bank } else { self.bank ^ (Opcode::of(self.instr) == Opcode::Star) };
        let active_next = in_fetch && self.ie && self.irq_reg;
        let stack_error = in_fetch && self.depth == STACK_ERROR_DEPTH;

        // The second cycle of the instruction decoded in the previous cycle (never a D).
        let mut retired = self.pending.take().map(|p| self.second_cycle(p, bus, cycle));
        match phase {
            Phase::Decode => self.pending = Some(self.decode(cycle)),
            Phase::Fetch => self.instr = self.rom[self.pc as usize],
            Phase::Idle => {}
        }

        if self.internal_reset {
            self.pc = 0;
            self.c = false;
            self.z = false;
            self.bank = false;
            self.ie = false;
            self.depth = 0;
        }
        self.xb = xb_next;
        self.interrupt_ack = self.active_interrupt;
        self.active_interrupt = active_next;
        self.phase = if self.internal_reset {
            Phase::Idle
        } else {
            match phase {
                Phase::Fetch => Phase::Decode,
                Phase::Idle | Phase::Decode if self.sleep_reg => Phase::Idle,
                Phase::Idle | Phase::Decode => Phase::Fetch,
            }
        };
        let run = !pins.reset && (self.run || self.internal_reset) && !stack_error;
        self.internal_reset = pins.reset || !self.run || stack_error;
        self.run = run;
        self.sleep_reg = pins.sleep;
        self.irq_reg = pins.interrupt;
        self.cycle += 1;

        if let Some(r) = retired.as_mut() {
            r.c = self.c;
            r.z = self.z;
            r.bank = self.bank;
            r.ie = self.ie;
            r.depth = self.depth;
            r.next_pc = self.pc;
        }
        retired
    }

    /// The D cycle (§2.2, §2.5, §2.6, §2.8): the stack RAM write, the next PC, depth, IE and
    /// bank, and the second-cycle flops with the ALU result computed from this cycle's
    /// operands. The internal reset, if active, clears PC, depth, IE and bank afterwards.
    #[inline(always)]
    fn decode(&mut self, cycle: u64) -> Pending {
        let w = self.instr;
        let op = Opcode::of(w);
        let entry = self.active_interrupt;
        let top = self.stack[self.depth.wrapping_sub(1) as usize & 31];
        // The stack RAM is written in every D at the depth counter's entry.
        self.stack[self.depth as usize] = StackEntry { pc: self.pc, c: self.c, z: self.z, bank: self.bank };

        let taken = Cond::taken(w, self.c, self.z);
        let push = entry || (taken && op.pushes());
        let pop = !entry && taken && op.pops();
        let next_pc = if entry {
            self.config.interrupt_vector & 0xFFF
        } else {
            match op {
                Opcode::Call | Opcode::Jump if taken => (w & 0xFFF) as u16,
                Opcode::CallAt | Opcode::JumpAt => (self.sx() as u16 & 15) << 8 | self.sy() as u16,
                Opcode::Return | Opcode::LoadReturn if taken => (top.pc + 1) & 0xFFF,
                Opcode::ReturnI => top.pc,
                _ => (self.pc + 1) & 0xFFF,
            }
        };

        let (result, carry, zero) = self.alu(op, top);
        let pending = Pending {
            kind: if entry { RetireKind::Interrupt } else { RetireKind::Executed },
            cycle,
            pc: self.pc,
            word: w,
            op,
            result,
            carry,
            zero,
        };

        self.pc = next_pc;
        self.depth = (self.depth + push as u8).wrapping_sub(pop as u8) & 31;
        if entry {
            self.ie = false;
        } else if matches!(op, Opcode::Interrupt | Opcode::ReturnI) {
            self.ie = w & 1 == 1;
        }
        // The bank has no interrupt input: a pre-empted REGBANK or RETURNI still switches it.
        match op {
            Opcode::RegBank => self.bank = w & 1 == 1,
            Opcode::ReturnI => self.bank = top.bank,
            _ => {}
        }
        pending
    }

    /// The ALU in D: the value the second cycle writes, its carry and zero (§1.2-§1.4; RETURNI:
    /// the flags of the stack's top entry).
    #[inline(always)]
    fn alu(&self, op: Opcode, top: StackEntry) -> (u8, bool, bool) {
        let sx = self.sx();
        let k = self.operand();
        let cin = op.carry_form() && self.c;
        let zero = |v: u8| v == 0 && (!op.carry_form() || self.z);
        match op {
            Opcode::And | Opcode::Or | Opcode::Xor => {
                let v = match op {
                    Opcode::And => sx & k,
                    Opcode::Or => sx | k,
                    _ => sx ^ k,
                };
                (v, false, v == 0)
            }
            Opcode::Test | Opcode::TestCy => {
                let t = sx & k;
                (t, (t.count_ones() & 1 == 1) ^ cin, zero(t))
            }
            Opcode::Add | Opcode::AddCy => {
                let t = sx as u16 + k as u16 + cin as u16;
                (t as u8, t > 0xFF, zero(t as u8))
            }
            Opcode::Sub | Opcode::SubCy | Opcode::Compare | Opcode::CompareCy => {
                let t = (sx as i16) - (k as i16) - cin as i16;
                (t as u8, t < 0, zero(t as u8))
            }
            Opcode::Shift => self.shift(self.instr as u8, sx),
            Opcode::Fetch => (self.spm[self.spm_addr()], false, false),
            Opcode::LoadReturn => (self.instr as u8, false, false),
            Opcode::ReturnI => (0, top.c, top.z),
            _ => (k, false, false), // LOAD, STAR
        }
    }

    /// The second cycle: register, flag and scratch-pad writes and the strobe of the
    /// instruction decoded in the cycle before (through the live ports of this cycle).
    #[inline(always)]
    fn second_cycle<B: Bus>(&mut self, p: Pending, bus: &mut B, cycle: u64) -> Retired {
        let mut r = Retired {
            kind: p.kind,
            cycle: p.cycle,
            pc: p.pc,
            word: p.word,
            reg_write: None,
            spm_write: None,
            port: None,
            c: false,
            z: false,
            bank: false,
            ie: false,
            depth: 0,
            next_pc: 0,
        };
        if p.kind == RetireKind::Interrupt {
            return r;
        }
        let mut input = 0;
        if let Some(kind) = p.op.strobe() {
            let (port, out) = (self.port_id(), self.out_port());
            let value = match kind {
                PortKind::Read => {
                    input = bus.input(port, cycle); // in_port, live at the end of this cycle
                    input
                }
                PortKind::Write => {
                    bus.output(port, out, cycle);
                    out
                }
                PortKind::KWrite => {
                    bus.output_k(port, out, cycle);
                    out
                }
            };
            r.port = Some(PortEvent { kind, port, value, cycle });
        }
        if p.op == Opcode::Store {
            let (addr, v) = (self.spm_addr(), self.sx());
            self.spm[addr] = v;
            r.spm_write = Some((addr as u8, v));
        }
        if p.op.writes_register() {
            let v = if p.op == Opcode::Input { input } else { p.result };
            let x = self.instr >> 8 & 15;
            self.regs[reg_index(self.xb, x)] = v;
            r.reg_write = Some((self.xb, x as u8, v));
        }
        if p.op.writes_flags() {
            self.c = p.carry;
            self.z = p.zero;
        }
        r
    }

    /// Shift, rotate and HWBUILD (§1.3): result, C, Z.
    fn shift(&self, code: u8, sx: u8) -> (u8, bool, bool) {
        if code & 0x80 != 0 {
            return (self.config.hwbuild, true, self.config.hwbuild == 0);
        }
        let right = code & 8 != 0;
        let fill = match code >> 1 & 3 {
            0 => self.c,
            1 => sx & 0x80 != 0,
            2 => sx & 1 != 0,
            _ => code & 1 != 0,
        };
        let (v, c) =
            if right { ((fill as u8) << 7 | sx >> 1, sx & 1 != 0) } else { (sx << 1 | fill as u8, sx & 0x80 != 0) };
        (v, c, v == 0)
    }

    /// The instruction in its second cycle now (decoded in the cycle before): whether an
    /// interrupt pre-empted it, and its opcode ([`crate::counting`] follows it).
    pub(crate) fn in_flight(&self) -> Option<(RetireKind, Opcode)> {
        self.pending.map(|p| (p.kind, p.op))
    }

    /// The second operand of the word on `instruction` (its constant, or sY), and the
    /// scratch-pad address it makes.
    pub(crate) fn operand_now(&self) -> u8 {
        self.operand()
    }
    pub(crate) fn spm_addr_now(&self) -> usize {
        self.spm_addr()
    }

    /// The bytes and flags a count may live in, by number (see [`crate::counting`]): bytes
    /// 0-31 the registers, 32-287 the scratch pad, 288 the ALU result in flight; flags 0 C,
    /// 1 Z, 2 and 3 the carry and zero in flight, 4 + k and 36 + k those of stack entry k.
    /// Nothing in flight reads as 0 and ignores writes.
    pub(crate) fn byte_at(&self, at: usize) -> u8 {
        match at {
            0..=31 => self.regs[at],
            32..=287 => self.spm[at - 32],
            _ => self.pending.map_or(0, |p| p.result),
        }
    }
    pub(crate) fn set_byte_at(&mut self, at: usize, v: u8) {
        match at {
            0..=31 => self.regs[at] = v,
            32..=287 => self.spm[at - 32] = v,
            _ => {
                if let Some(p) = &mut self.pending {
                    p.result = v;
                }
            }
        }
    }
    pub(crate) fn flag_at(&self, at: usize) -> bool {
        match at {
            0 => self.c,
            1 => self.z,
            2 => self.pending.is_some_and(|p| p.carry),
            3 => self.pending.is_some_and(|p| p.zero),
            4..=35 => self.stack[at - 4].c,
            _ => self.stack[at - 36].z,
        }
    }
    pub(crate) fn set_flag_at(&mut self, at: usize, v: bool) {
        match at {
            0 => self.c = v,
            1 => self.z = v,
            2 | 3 => {
                if let Some(p) = &mut self.pending {
                    if at == 2 {
                        p.carry = v;
                    } else {
                        p.zero = v;
                    }
                }
            }
            4..=35 => self.stack[at - 4].c = v,
            _ => self.stack[at - 36].z = v,
        }
    }

    /// Run with all pins low until `n` instructions have completed; returns the last record.
    pub fn run_instructions<B: Bus>(&mut self, n: u64, bus: &mut B) -> Result<Retired, Timeout> {
        let mut last = None;
        for _ in 0..n {
            last = Some(self.step(bus, 64)?);
        }
        last.ok_or(Timeout(0))
    }

    /// Run with all pins low until the next instruction completes, within `budget` cycles.
    pub fn step<B: Bus>(&mut self, bus: &mut B, budget: u64) -> Result<Retired, Timeout> {
        for _ in 0..budget {
            if let Some(r) = self.tick(Pins::default(), bus) {
                return Ok(r);
            }
        }
        Err(Timeout(budget))
    }

    /// True at an instruction boundary of the steady state: the next cycle is a D cycle with
    /// nothing in flight, no reset sequence, no registered sleep or interrupt request, and the
    /// instruction about to be decoded leaves the stack depth legal. There, with all pins low,
    /// instructions can be executed whole ([`Cpu::run_fast`]).
    fn steady(&self) -> bool {
        self.phase == Phase::Decode
            && self.pending.is_none()
            && self.run
            && !self.internal_reset
            && !self.sleep_reg
            && !self.irq_reg
            && !self.active_interrupt
            && self.xb == self.bank
            && !self.stack_error_ahead()
    }

    /// Would the instruction about to be decoded leave the depth counter at the error value?
    fn stack_error_ahead(&self) -> bool {
        let op = Opcode::of(self.instr);
        let taken = Cond::taken(self.instr, self.c, self.z);
        taken && ((op.pushes() && self.depth >= STACK_DEPTH) || (op.pops() && self.depth == 0))
    }

    /// Run with all pins low, a whole instruction at a time, until cycle `until` is reached or
    /// passed, or `stop(bus)` is true after an instruction. Equal, cycle for cycle and event for
    /// event, to calling [`Cpu::tick`] with low pins (tested): away from the steady state
    /// (reset sequence, stack errors) it ticks cycle by cycle. The busy-wait idiom
    /// `SUB sX, 01` / `JUMP NZ, <the SUB>` is fast-forwarded to its end in one step.
    pub fn run_fast<B: Bus>(&mut self, bus: &mut B, until: u64, stop: impl FnMut(&B) -> bool) {
        let mut stop = stop;
        self.run_inner(bus, until, |b, _| stop(b), None);
    }

    /// As [`Cpu::run_fast`], and a call of a subroutine that only computes, made before with
    /// the same inputs, is applied at once from its recording in `routines` (see
    /// [`Routines`]). Equal, cycle for cycle and event for event, to [`Cpu::tick`] (tested).
    pub fn run_with<B: Bus>(&mut self, bus: &mut B, until: u64, stop: impl FnMut(&B) -> bool, routines: &mut Routines) {
        let mut stop = stop;
        self.run_inner(bus, until, |b, _| stop(b), Some(routines));
        routines.interrupted();
    }

    /// As [`Cpu::run_with`], `stop` also seeing the core after each instruction (or call
    /// applied from a recording, or countdown finished): where a caller that runs a core on its
    /// own looks for loops to skip. The calls being recorded stay open: a caller that moves
    /// the core along its own path between runs (whole trips of a loop, as simulating them
    /// would leave it) goes on with them; one that changes it otherwise, or ticks it, first
    /// calls [`Routines::interrupted`].
    pub fn run_watched<B: Bus>(
        &mut self,
        bus: &mut B,
        until: u64,
        stop: impl FnMut(&B, &Cpu) -> bool,
        routines: &mut Routines,
    ) {
        self.run_inner(bus, until, stop, Some(routines));
    }

    fn run_inner<B: Bus>(
        &mut self,
        bus: &mut B,
        until: u64,
        mut stop: impl FnMut(&B, &Cpu) -> bool,
        mut routines: Option<&mut Routines>,
    ) {
        while self.cycle < until {
            if !self.steady() {
                if let Some(r) = routines.as_deref_mut() {
                    r.interrupted();
                }
                self.tick(Pins::default(), bus);
                if stop(bus, self) {
                    return;
                }
                continue;
            }
            if let Some(r) = routines.as_deref_mut() {
                if r.at_instruction(self, until) {
                    r.after_instruction(self);
                    if stop(bus, self) {
                        return;
                    }
                    continue;
                }
            }
            if self.fast_forward_countdown(until) {
                if let Some(r) = routines.as_deref_mut() {
                    r.after_instruction(self);
                }
                continue;
            }
            // D, then its second cycle as an F that fetches the next word: what two ticks do
            // in the steady state, without the sequencer's bookkeeping.
            let d = self.cycle;
            self.xb = self.bank ^ (Opcode::of(self.instr) == Opcode::Star);
            let p = self.decode(d);
            self.second_cycle(p, bus, d + 1);
            self.instr = self.rom[self.pc as usize];
            self.xb = self.bank;
            self.cycle = d + 2;
            if let Some(r) = routines.as_deref_mut() {
                r.after_instruction(self);
            }
            if stop(bus, self) {
                return;
            }
        }
    }

    /// At `SUB sX, 01` followed by `JUMP NZ` back to it, in the steady state: finish the
    /// whole countdown at once (4 cycles per pass), if it ends before `until`.
    fn fast_forward_countdown(&mut self, until: u64) -> bool {
        let w = self.instr;
        let pc = self.pc as usize;
        let next = self.rom[(pc + 1) & 0xFFF];
        // SUB sX, 01 (the constant form: bit 12), then JUMP NZ back to it.
        let countdown = Opcode::of(w) == Opcode::Sub && w & 1 << 12 != 0 && w & 0xFF == 1;
        let loops_back =
            Opcode::of(next) == Opcode::Jump && Cond::of(next) == Some(Cond::NZ) && next & 0xFFF == pc as u32;
        if !(countdown && loops_back) {
            return false;
        }
        let i = reg_index(self.bank, w >> 8);
        let passes = if self.regs[i] == 0 { 256 } else { self.regs[i] as u64 };
        let end = self.cycle + 4 * passes;
        if end > until {
            return false;
        }
        // The last pass: SUB leaves 0 (Z = 1, C = 0); the JUMP NZ falls through; its D cycle
        // wrote the stack entry with its own address and those flags. (The next D rewrites
        // that entry before anything can pop it; it is kept so the state mirrors tick().)
        self.regs[i] = 0;
        self.z = true;
        self.c = false;
        self.stack[self.depth as usize] =
            StackEntry { pc: ((pc + 1) & 0xFFF) as u16, c: false, z: true, bank: self.bank };
        self.pc = ((pc + 2) & 0xFFF) as u16;
        self.instr = self.rom[self.pc as usize];
        self.cycle = end;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cpu(words: &[u32]) -> Cpu {
        Cpu::new(Config::default(), words)
    }

    #[test]
    fn a_core_whose_state_repeats_skips_a_period_as_if_it_had_run_it() {
        // A wait loop that polls a port: COMPARE s0, 00 / JUMP Z back to it.
        let words = [0x1D000, 0x32000];
        let mut bus = NullBus::default();
        let mut run = cpu(&words);
        for _ in 0..20 {
            run.tick(Pins::default(), &mut bus);
        }
        let mark = run.clone();
        for _ in 0..4 {
            run.tick(Pins::default(), &mut bus);
        }
        assert!(run.same_state_as(&mark) && run.cycle() == mark.cycle() + 4);
        let mut skipped = mark.clone();
        skipped.skip_period(4);
        // From here both run alike, cycle for cycle.
        for _ in 0..9 {
            assert_eq!(run.tick(Pins::default(), &mut bus), skipped.tick(Pins::default(), &mut bus));
            assert_eq!((run.cycle(), run.pc()), (skipped.cycle(), skipped.pc()));
        }
        // A cycle on is mid-instruction: not the same state.
        let mut half = run.clone();
        half.tick(Pins::default(), &mut bus);
        assert!(!half.same_state_as(&run));
        // Any other flop differing: a register, the scratch pad, a flag, the stack.
        for change in [
            |c: &mut Cpu| c.regs[3] = 1,
            |c: &mut Cpu| c.spm[9] = 1,
            |c: &mut Cpu| c.c = !c.c,
            |c: &mut Cpu| c.stack[5].pc = 7,
        ] {
            let mut other = run.clone();
            change(&mut other);
            assert!(!other.same_state_as(&run) && !run.same_state_as(&other));
        }
    }

    #[test]
    fn self_start_fetches_in_cycle_4_and_decodes_in_5() {
        let mut c = cpu(&[0x01042]);
        let mut bus = NullBus::default();
        let mut fetches = vec![];
        for _ in 0..8 {
            if c.bram_enable() {
                fetches.push(c.cycle());
            }
            c.tick(Pins::default(), &mut bus);
        }
        // One extra bram_enable pulse at power-up (cycle 1), then the self-start fetch.
        assert_eq!(fetches, vec![1, 4, 6]);
    }

    #[test]
    fn external_reset_in_21_22_decodes_000_in_27() {
        let mut c = cpu(&[0x22000]);
        let mut bus = NullBus::default();
        let mut d_at_000 = vec![];
        for _ in 0..32 {
            let cyc = c.cycle();
            if c.phase() == Phase::Decode && c.pc() == 0 {
                d_at_000.push(cyc);
            }
            let reset = cyc == 21 || cyc == 22;
            c.tick(Pins { reset, ..Pins::default() }, &mut bus);
        }
        assert!(d_at_000.contains(&27), "{d_at_000:?}");
        assert!(!d_at_000.iter().any(|&x| (22..27).contains(&x)));
    }
}
