//! A cycle-exact KCPSM6 instruction-set simulator.
//!
//! The simulator follows the hardware's sequencing (spec §2): each instruction takes a **D**
//! cycle (decode; PC, stack, IE and bank update at its end) and a second cycle (normally **F**,
//! which fetches the next word) in which the register, flag and scratch-pad writes and the port
//! strobes happen. Reset, sleep and interrupt are sampled per clock, so the cycle numbers of
//! every port event match the RTL core, which is built from the same description.
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

use crate::isa::ROM_WORDS;

/// Usable call-stack depth (an interrupt uses one level).
pub const STACK_DEPTH: u8 = 30;

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

/// Which strobe a port event raised.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PortKind {
    /// `read_strobe` (INPUT): `value` is what was read.
    Read,
    /// `write_strobe` (OUTPUT).
    Write,
    /// `k_write_strobe` (OUTPUTK and the undocumented opcode 2A).
    KWrite,
}

/// One strobe on the port bus.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PortEvent {
    pub kind: PortKind,
    pub port: u8,
    pub value: u8,
    /// The cycle in which the strobe is high.
    pub cycle: u64,
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

/// Second-cycle work loaded at the end of a D cycle.
#[derive(Clone, Copy, Debug)]
struct Pending {
    kind: RetireKind,
    cycle: u64,
    pc: u16,
    word: u32,
    /// Flags popped by RETURNI, written at the end of the second cycle.
    restore: Option<(bool, bool)>,
}

/// A failure to reach a retirement within a cycle budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("no instruction completed within {0} cycles")]
pub struct Timeout(pub u64);

/// The KCPSM6 core.
#[derive(Clone)]
pub struct Cpu {
    config: Config,
    rom: Box<[u32; ROM_WORDS]>,
    /// s0..sF of bank A, then of bank B.
    regs: [u8; 32],
    spm: [u8; 256],
    stack: [StackEntry; 32],
    sp: u8,
    pc: u16,
    c: bool,
    z: bool,
    ie: bool,
    bank: bool,
    /// Registered copy of `bank` used to address the register file (§2.8).
    bank_rd: bool,
    phase: Phase,
    run: bool,
    internal_reset: bool,
    sleep_reg: bool,
    irq_reg: bool,
    take_interrupt: bool,
    interrupt_ack: bool,
    /// The word on `instruction` (the ROM's output register).
    instr: u32,
    pending: Option<Pending>,
    cycle: u64,
}

impl Cpu {
    /// A core in its configuration state (cycle 0), self-starting from address 000.
    pub fn new(config: Config, rom: &[u32]) -> Cpu {
        let mut image = Box::new([0u32; ROM_WORDS]);
        for (dst, src) in image.iter_mut().zip(rom) {
            *dst = src & crate::isa::WORD_MASK;
        }
        Cpu {
            config,
            rom: image,
            regs: [0; 32],
            spm: [0; 256],
            stack: [StackEntry::default(); 32],
            sp: 0,
            pc: 0,
            c: false,
            z: false,
            ie: false,
            bank: false,
            bank_rd: false,
            phase: Phase::Idle,
            run: false,
            internal_reset: false,
            sleep_reg: false,
            irq_reg: false,
            take_interrupt: false,
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

    pub fn pc(&self) -> u16 {
        self.pc
    }

    /// Held in reset (by the pin, or by the internal reset after power-up or a stack error).
    pub fn in_reset(&self) -> bool {
        self.internal_reset
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

    /// Call-stack depth (0..=31; 31 only transiently after an underflow).
    pub fn depth(&self) -> u8 {
        self.sp
    }

    /// Register `r` (0..15) of bank A (`bank_b` false) or B.
    pub fn reg(&self, bank_b: bool, r: u8) -> u8 {
        self.regs[(bank_b as usize) << 4 | (r & 15) as usize]
    }

    pub fn set_reg(&mut self, bank_b: bool, r: u8, v: u8) {
        self.regs[(bank_b as usize) << 4 | (r & 15) as usize] = v;
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
        self.rom[addr as usize & 0xFFF] = word & crate::isa::WORD_MASK;
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

    fn rd(&self, r: u32) -> u8 {
        self.regs[(self.bank_rd as usize) << 4 | (r & 15) as usize]
    }

    /// `out_port` in the current cycle: `instruction[13] ? instruction[11:4] : sX`.
    pub fn out_port(&self) -> u8 {
        if self.instr & 1 << 13 != 0 {
            (self.instr >> 4) as u8
        } else {
            self.rd(self.instr >> 8)
        }
    }

    /// `port_id` in the current cycle: `instruction[12] ? instruction[7:0] : sY`.
    pub fn port_id(&self) -> u8 {
        if self.instr & 1 << 12 != 0 {
            self.instr as u8
        } else {
            self.rd(self.instr >> 4)
        }
    }

    /// The strobe kind high in the current cycle, if any.
    pub fn strobe(&self) -> Option<PortKind> {
        let p = self.pending.as_ref()?;
        if p.kind != RetireKind::Executed {
            return None;
        }
        match p.word >> 12 {
            0x08 | 0x09 => Some(PortKind::Read),
            0x2C | 0x2D => Some(PortKind::Write),
            0x2A | 0x2B => Some(PortKind::KWrite),
            _ => None,
        }
    }

    /// Simulate one clock cycle: the state during cycle [`Cpu::cycle`] and the rising edge
    /// at its end, with `pins` sampled at that edge. Returns the record of an instruction
    /// whose second cycle this was.
    pub fn tick<B: Bus>(&mut self, pins: Pins, bus: &mut B) -> Option<Retired> {
        let cycle = self.cycle;
        let phase = self.phase;
        let bank_before = self.bank;
        let mut stack_error = false;
        let mut retired = None;

        // Second-cycle actions of the instruction decoded in the previous cycle.
        if let Some(p) = self.pending.take() {
            retired = Some(self.second_cycle(p, bus, cycle));
        }
        let entering_interrupt = phase == Phase::Decode && self.take_interrupt;

        match phase {
            Phase::Fetch => {
                // Interrupt recognition samples the registered request in F cycles only.
                if self.ie && self.irq_reg && !self.internal_reset {
                    self.take_interrupt = true;
                }
                self.instr = self.rom[self.pc as usize];
            }
            Phase::Decode => {
                // The stack RAM is written in every D cycle at the pointer's entry.
                self.stack[self.sp as usize] = StackEntry { pc: self.pc, c: self.c, z: self.z, bank: self.bank };
                let p = Pending { kind: RetireKind::Executed, cycle, pc: self.pc, word: self.instr, restore: None };
                if entering_interrupt {
                    self.take_interrupt = false;
                    stack_error = self.push();
                    self.pc = self.config.interrupt_vector & 0xFFF;
                    self.ie = false;
                    self.pending = Some(Pending { kind: RetireKind::Interrupt, ..p });
                } else {
                    let (restore, err) = self.decode();
                    stack_error = err;
                    self.pending = Some(Pending { restore, ..p });
                }
            }
            Phase::Idle => {}
        }
        self.interrupt_ack = entering_interrupt;
        self.bank_rd = bank_before;

        if self.internal_reset {
            self.pc = 0;
            self.c = false;
            self.z = false;
            self.bank = false;
            self.ie = false;
            self.sp = 0;
            self.take_interrupt = false;
        }

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
        self.internal_reset = pins.reset || !self.run;
        self.run = run;
        self.sleep_reg = pins.sleep;
        self.irq_reg = pins.interrupt;
        self.cycle += 1;

        if let Some(r) = retired.as_mut() {
            r.c = self.c;
            r.z = self.z;
            r.bank = self.bank;
            r.ie = self.ie;
            r.depth = self.sp;
            r.next_pc = self.pc;
        }
        retired
    }

    /// Push: returns true on overflow (the 31st level).
    fn push(&mut self) -> bool {
        let overflow = self.sp >= STACK_DEPTH;
        self.sp = (self.sp + 1) & 31;
        overflow
    }

    /// Pop: returns the popped entry and true on underflow.
    fn pop(&mut self) -> (StackEntry, bool) {
        let underflow = self.sp == 0;
        self.sp = self.sp.wrapping_sub(1) & 31;
        (self.stack[self.sp as usize], underflow)
    }

    /// Whether control-flow opcode `op` acts: unconditional forms always, conditional ones
    /// (bit 16 set) when their condition (bits 15:14: Z, NZ, C, NC) holds.
    fn taken(&self, op: u32) -> bool {
        op & 0x10 == 0
            || match op >> 2 & 3 {
                0 => self.z,
                1 => !self.z,
                2 => self.c,
                _ => !self.c,
            }
    }

    /// D-cycle work: next PC, stack, IE and bank. Returns RETURNI's flags and a stack error.
    fn decode(&mut self) -> (Option<(bool, bool)>, bool) {
        let w = self.instr;
        let op = w >> 12;
        let aaa = (w & 0xFFF) as u16;
        let next = (self.pc + 1) & 0xFFF;
        let at_target = ((self.rd(w >> 8) as u16 & 15) << 8 | self.rd(w >> 4) as u16) & 0xFFF;
        self.pc = next;
        if op < 0x20 {
            return (None, false);
        }
        let taken = self.taken(op);
        match op {
            0x24 => {
                self.pc = at_target;
                return (None, self.push());
            }
            0x26 => self.pc = at_target,
            0x28 => self.ie = w & 1 == 1,
            0x29 => {
                let (e, err) = self.pop();
                self.pc = e.pc;
                self.bank = e.bank;
                self.ie = w & 1 == 1;
                return (Some((e.c, e.z)), err);
            }
            0x37 => self.bank = w & 1 == 1,
            0x20..=0x22 | 0x25 | 0x30..=0x3F if taken => match op & 3 {
                0 => {
                    // CALL: the pushed entry (written this cycle) holds the CALL's address.
                    self.pc = aaa;
                    return (None, self.push());
                }
                1 => {
                    // RETURN and LOAD&RETURN resume after the CALL.
                    let (e, err) = self.pop();
                    self.pc = (e.pc + 1) & 0xFFF;
                    return (None, err);
                }
                2 => self.pc = aaa,
                _ => {}
            },
            _ => {}
        }
        (None, false)
    }

    /// Second-cycle work: register, flag and scratch-pad writes, strobes.
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
        let w = p.word;
        let op = w >> 12;
        let x = w >> 8 & 15;
        let sx = self.rd(x);
        let operand = if op & 1 == 1 { w as u8 } else { self.rd(w >> 4) };
        let spm_addr = (operand as usize) & (self.config.scratch_pad_size.bytes() - 1);
        let mut write = |cpu: &mut Cpu, bank_b: bool, v: u8| {
            cpu.regs[(bank_b as usize) << 4 | x as usize] = v;
            r.reg_write = Some((bank_b, x as u8, v));
        };
        let bank = self.bank_rd;
        match op {
            0x00 | 0x01 => write(self, bank, operand),
            0x02..=0x07 => {
                let v = match op >> 1 {
                    1 => sx & operand,
                    2 => sx | operand,
                    _ => sx ^ operand,
                };
                write(self, bank, v);
                self.c = false;
                self.z = v == 0;
            }
            0x08 | 0x09 => {
                let port = self.port_id();
                let v = bus.input(port, cycle);
                write(self, bank, v);
                r.port = Some(PortEvent { kind: PortKind::Read, port, value: v, cycle });
            }
            0x0A | 0x0B => write(self, bank, self.spm[spm_addr]),
            0x0C..=0x0F => {
                let t = sx & operand;
                let parity = t.count_ones() & 1 == 1;
                if op & 2 == 0 {
                    self.c = parity;
                    self.z = t == 0;
                } else {
                    self.c ^= parity;
                    self.z = t == 0 && self.z;
                }
            }
            0x10..=0x13 => {
                let cy = op & 2 != 0;
                let t = sx as u16 + operand as u16 + (cy && self.c) as u16;
                let v = t as u8;
                write(self, bank, v);
                self.c = t > 0xFF;
                self.z = v == 0 && (!cy || self.z);
            }
            0x14 | 0x15 => {
                let (v, c, z) = self.shift(w as u8, sx);
                write(self, bank, v);
                self.c = c;
                self.z = z;
            }
            0x16 | 0x17 => write(self, !bank, operand),
            0x18..=0x1F => {
                let cy = op & 2 != 0;
                let t = (sx as i16) - (operand as i16) - (cy && self.c) as i16;
                let v = t as u8;
                if op & 4 == 0 {
                    write(self, bank, v);
                }
                self.c = t < 0;
                self.z = v == 0 && (!cy || self.z);
            }
            0x21 => write(self, bank, w as u8),
            0x29 => {
                if let Some((c, z)) = p.restore {
                    self.c = c;
                    self.z = z;
                }
            }
            0x2A | 0x2B => {
                let (port, value) = (self.port_id(), self.out_port());
                bus.output_k(port, value, cycle);
                r.port = Some(PortEvent { kind: PortKind::KWrite, port, value, cycle });
            }
            0x2C | 0x2D => {
                let (port, value) = (self.port_id(), self.out_port());
                bus.output(port, value, cycle);
                r.port = Some(PortEvent { kind: PortKind::Write, port, value, cycle });
            }
            0x2E | 0x2F => {
                self.spm[spm_addr] = sx;
                r.spm_write = Some((spm_addr as u8, sx));
            }
            _ => {}
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
    /// nothing in flight, no reset sequence, no registered sleep or interrupt request. There,
    /// with all pins low, instructions can be executed whole ([`Cpu::run_fast`]).
    fn steady(&self) -> bool {
        self.phase == Phase::Decode
            && self.pending.is_none()
            && self.run
            && !self.internal_reset
            && !self.sleep_reg
            && !self.irq_reg
            && !self.take_interrupt
            && self.bank_rd == self.bank
    }

    /// Would the instruction about to be decoded overflow or underflow the stack?
    fn stack_error_ahead(&self) -> bool {
        let op = self.instr >> 12;
        let taken = self.taken(op);
        let push = op == 0x24 || (taken && matches!(op, 0x20 | 0x30 | 0x34 | 0x38 | 0x3C));
        let pop = op == 0x29 || (taken && matches!(op, 0x21 | 0x25 | 0x31 | 0x35 | 0x39 | 0x3D));
        (push && self.sp >= STACK_DEPTH) || (pop && self.sp == 0)
    }

    /// Run with all pins low, a whole instruction at a time, until cycle `until` is reached or
    /// passed, or `stop(bus)` is true after an instruction. Equal, cycle for cycle and event for
    /// event, to calling [`Cpu::tick`] with low pins (tested): away from the steady state
    /// (reset sequence, stack errors) it ticks cycle by cycle. The busy-wait idiom
    /// `SUB sX, 01` / `JUMP NZ, <the SUB>` is fast-forwarded to its end in one step.
    pub fn run_fast<B: Bus>(&mut self, bus: &mut B, until: u64, mut stop: impl FnMut(&B) -> bool) {
        while self.cycle < until {
            if !self.steady() || self.stack_error_ahead() {
                self.tick(Pins::default(), bus);
                if stop(bus) {
                    return;
                }
                continue;
            }
            if self.fast_forward_countdown(until) {
                continue;
            }
            // D cycle: the stack RAM write, PC, stack, IE, bank; then the second cycle.
            let d = self.cycle;
            let bank_before = self.bank;
            self.stack[self.sp as usize] = StackEntry { pc: self.pc, c: self.c, z: self.z, bank: self.bank };
            let p = Pending { kind: RetireKind::Executed, cycle: d, pc: self.pc, word: self.instr, restore: None };
            let (restore, _) = self.decode();
            self.bank_rd = bank_before;
            self.second_cycle(Pending { restore, ..p }, bus, d + 1);
            self.instr = self.rom[self.pc as usize];
            self.bank_rd = self.bank;
            self.cycle = d + 2;
            if stop(bus) {
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
        if w & 0xFF0FF != 0x19001 || next != (0x36000 | pc as u32) {
            return false;
        }
        let x = (w >> 8 & 15) as usize;
        let i = (self.bank as usize) << 4 | x;
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
        self.stack[self.sp as usize] = StackEntry { pc: ((pc + 1) & 0xFFF) as u16, c: false, z: true, bank: self.bank };
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
