//! Functional coverage and aimed stimulus for the CPU lock-step: which pin events landed on
//! which cycle of which instruction class (spec kcpsm6.md §2.4-§2.8), and a stimulus that aims
//! resets, interrupts and sleep at the instruction in flight so every bin is reached.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::fmt;

use kcpsm6::isa::Opcode;
use kcpsm6::iss::{Cpu, Phase, Pins, STACK_DEPTH, STACK_ERROR_DEPTH};

/// The instruction classes whose port-level behaviour depends on when a pin event lands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Class {
    RegBank,
    ReturnI,
    Star,
    CallAt,
    JumpAt,
    /// STORE sX, (sY)
    StoreSy,
    /// FETCH sX, (sY)
    FetchSy,
    /// OUTPUT sX, (sY)
    OutputSy,
    /// INPUT sX, (sY)
    InputSy,
    AddCy,
    SubCy,
    /// SLA, SRA (and the undocumented sub-codes that shift the carry in).
    ShiftThroughCarry,
    Other,
}

impl Class {
    pub fn of(word: u32) -> Class {
        let reg_form = word & 1 << 12 == 0;
        match Opcode::of(word) {
            Opcode::RegBank => Class::RegBank,
            Opcode::ReturnI => Class::ReturnI,
            Opcode::Star => Class::Star,
            Opcode::CallAt => Class::CallAt,
            Opcode::JumpAt => Class::JumpAt,
            Opcode::Store if reg_form => Class::StoreSy,
            Opcode::Fetch if reg_form => Class::FetchSy,
            Opcode::Output if reg_form => Class::OutputSy,
            Opcode::Input if reg_form => Class::InputSy,
            Opcode::AddCy => Class::AddCy,
            Opcode::SubCy => Class::SubCy,
            Opcode::Shift if word & 0x86 == 0 => Class::ShiftThroughCarry,
            _ => Class::Other,
        }
    }

    /// The classes every event must reach.
    pub const TARGETS: [Class; 12] = [
        Class::RegBank,
        Class::ReturnI,
        Class::Star,
        Class::CallAt,
        Class::JumpAt,
        Class::StoreSy,
        Class::FetchSy,
        Class::OutputSy,
        Class::InputSy,
        Class::AddCy,
        Class::SubCy,
        Class::ShiftThroughCarry,
    ];
}

/// Where an event landed relative to an instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Event {
    /// The instruction's D is the first cycle of a reset (internal_reset = 1).
    ResetInD,
    /// ... and the carry was set (it is cleared at the end of that D, §2.8).
    ResetInDWithCarry,
    /// Its second cycle is the first cycle of a reset.
    ResetInSecond,
    /// An interrupt pre-empted it (its D is an entry D).
    Preempted,
    /// ... and the bank changed at the end of that D (a pre-empted REGBANK to the other bank,
    /// a pre-empted RETURNI whose saved bank differs, §2.6).
    PreemptedSwitchingBank,
    /// Its second cycle is an F that recognises an interrupt.
    InterruptInSecond,
    /// Sleep made its second cycle an idle one.
    SleepInSecond,
    /// The depth counter holds a stack error while the core sleeps (§2.5).
    StackErrorAsleep,
}

/// Counts of (class, event) seen.
#[derive(Default)]
pub struct Coverage {
    bins: BTreeMap<(Class, Event), u64>,
    /// The class of the instruction whose D was the previous cycle.
    after_d: Option<Class>,
    /// The class and bank of an entry D in the previous cycle.
    after_entry: Option<(Class, bool)>,
}

impl Coverage {
    /// Record the state of `cpu` at the start of a cycle.
    pub fn sample(&mut self, cpu: &Cpu) {
        let class = Class::of(cpu.instruction());
        if let Some((c, bank)) = self.after_entry.take() {
            if cpu.bank() != bank && !cpu.in_reset() {
                *self.bins.entry((c, Event::PreemptedSwitchingBank)).or_default() += 1;
            }
        }
        if cpu.phase() == Phase::Decode && cpu.interrupt_entry() {
            self.after_entry = Some((class, cpu.bank()));
        }
        let mut hit = |e| *self.bins.entry((class, e)).or_default() += 1;
        match cpu.phase() {
            Phase::Decode if cpu.interrupt_entry() => hit(Event::Preempted),
            _ => {}
        }
        if cpu.phase() == Phase::Decode && cpu.in_reset() {
            hit(Event::ResetInD);
            if cpu.carry() {
                hit(Event::ResetInDWithCarry);
            }
        }
        if self.after_d == Some(class) {
            if cpu.in_reset() {
                hit(Event::ResetInSecond);
            }
            match cpu.phase() {
                Phase::Fetch if cpu.interrupt_enabled() && cpu.interrupt_registered() => hit(Event::InterruptInSecond),
                Phase::Idle if !cpu.in_reset() => hit(Event::SleepInSecond),
                _ => {}
            }
        }
        if cpu.depth() == STACK_ERROR_DEPTH && cpu.phase() == Phase::Idle && !cpu.in_reset() {
            *self.bins.entry((Class::Other, Event::StackErrorAsleep)).or_default() += 1;
        }
        self.after_d = (cpu.phase() == Phase::Decode).then_some(class);
    }

    /// The bins that must be reached, and how often they were.
    pub fn required(&self) -> Vec<((Class, Event), u64)> {
        let mut req = vec![];
        for c in Class::TARGETS {
            for e in [
                Event::ResetInD,
                Event::ResetInSecond,
                Event::Preempted,
                Event::InterruptInSecond,
                Event::SleepInSecond,
            ] {
                req.push((c, e));
            }
        }
        for c in [Class::AddCy, Class::SubCy, Class::ShiftThroughCarry] {
            req.push((c, Event::ResetInDWithCarry));
        }
        for c in [Class::RegBank, Class::ReturnI] {
            req.push((c, Event::PreemptedSwitchingBank));
        }
        req.push((Class::Other, Event::StackErrorAsleep));
        req.into_iter().map(|b| (b, self.bins.get(&b).copied().unwrap_or(0))).collect()
    }

    /// The required bins never reached.
    pub fn holes(&self) -> Vec<(Class, Event)> {
        self.required().into_iter().filter(|(_, n)| *n == 0).map(|(b, _)| b).collect()
    }
}

impl fmt::Display for Coverage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for ((c, e), n) in self.required() {
            writeln!(f, "  {c:?} / {e:?}: {n}")?;
        }
        Ok(())
    }
}

/// Pin stimulus from a seed: background noise (rare resets, sleep bursts, interrupt bursts at
/// the given rates per 10,000 cycles) plus events aimed at the instruction in flight: a reset
/// into the next cycle, an interrupt request for the next F, sleep for the next second cycle,
/// each with probability `aim` per 10,000 when the next instruction is a target class (or is
/// about to leave the depth counter at a stack error, for sleep).
pub struct Stimulus {
    x: u64,
    rates: (u32, u32, u32),
    aim: u32,
    sleep_left: u32,
    irq_left: u32,
}

impl Stimulus {
    pub fn new(seed: u64, rates: (u32, u32, u32), aim: u32) -> Stimulus {
        Stimulus { x: seed | 1, rates, aim, sleep_left: 0, irq_left: 0 }
    }

    fn next(&mut self) -> u32 {
        self.x ^= self.x << 13;
        self.x ^= self.x >> 7;
        self.x ^= self.x << 17;
        (self.x >> 16) as u32 % 10_000
    }

    pub fn pins(&mut self, cpu: &Cpu) -> Pins {
        // The word whose D is next: in F the one being fetched; in D (for its second cycle)
        // the word on the bus; in D straight-line code also tells the F after.
        let on_bus = cpu.instruction();
        let rom = cpu.rom();
        let (next_d, next_second) = match cpu.phase() {
            Phase::Fetch => (Some(rom[cpu.pc() as usize]), None),
            Phase::Decode => (Some(rom[(cpu.pc() as usize + 1) & 0xFFF]), Some(on_bus)),
            Phase::Idle => (None, None),
        };
        let target = |w: Option<u32>| w.is_some_and(|w| Class::of(w) != Class::Other);
        let errs = next_d.is_some_and(|w| {
            let op = Opcode::of(w);
            (op.pushes() && cpu.depth() >= STACK_DEPTH) || (op.pops() && cpu.depth() == 0)
        });

        let (aim, (reset_rate, sleep_rate, irq_rate)) = (self.aim, self.rates);
        let reset = self.next() < reset_rate
            || (cpu.phase() == Phase::Fetch && target(next_d) && self.next() < aim)
            || (target(next_second) && self.next() < aim);
        if self.sleep_left == 0
            && (self.next() < sleep_rate
                || (cpu.phase() == Phase::Fetch && (target(next_d) || errs) && self.next() < aim * 2))
        {
            self.sleep_left = 1 + self.next() % 12;
        }
        if self.irq_left == 0
            && (self.next() < irq_rate
                || (cpu.interrupt_enabled() && (target(next_d) || target(next_second)) && self.next() < aim * 6))
        {
            self.irq_left = 1 + self.next() % 6;
        }
        let pins = Pins { reset, sleep: self.sleep_left > 0, interrupt: self.irq_left > 0 };
        self.sleep_left = self.sleep_left.saturating_sub(1);
        self.irq_left = self.irq_left.saturating_sub(1);
        pins
    }
}
