//! Firmware that counts: a period of a core whose only change is a count, and how far that
//! count can be moved on without simulating it.
//!
//! PicoBlaze programs wait in loops that only count: a software delay (`SUB s0, 01` /
//! `SUBCY s1, 00` / `SUBCY s2, 00` / `JUMP NZ`), nested delays that reload an inner counter
//! per turn of an outer one, a countdown kept in the scratch pad, a busy-wait with a timeout.
//! A board's fast-forward repeats a period whose state comes back exactly; in such a loop the
//! state comes back but for the count. [`CountingPeriod::find`] proves, from one period the
//! core has just run (the core at its start, at its end, and what it read from its pins), that
//! the next periods do the same thing but for the count, and for how many (its
//! [`CountingPeriod::room`]); [`CountingPeriod::state_after`] is the core after any number of
//! them, exactly as simulating them would leave it.
//!
//! **The proof.** Each byte of the core's state (registers, scratch pad, the ALU result in
//! flight) and each flag (C, Z, those in flight, those in the stack RAM) is abstracted as
//! - *invariant*: the same at this point of every period;
//! - a *view* of a count: byte `i` of `W + c`, where `W` is a wide counter (its *home* bytes,
//!   little-endian, anywhere in the registers or the scratch pad) that moves by `d` per period
//!   (`W(j) = W(0) + j d`, modulo its width), and `c` a constant;
//! - a flag of a *chain* on a count: the carry or zero of `ADD`/`SUB`/`COMPARE` and their `CY`
//!   forms over bytes `s..m` of a view, with constants (or invariant registers) as operands,
//!   which is true exactly when `W mod 2^8m` lies in an interval.
//!
//! The period is executed twice, cycle by cycle as the core does (D and F, the stack RAM
//! written in every D, results in flight), beside a re-run of the ISS from its start with the
//! same pins and inputs: once to find the counts' homes (the bytes a chain starts on), once to
//! prove, with every home a view of its own count and every other byte and flag as the first
//! run ended it (one period earlier), that every byte ends as it started one period on
//! (homes moved by `d`, the rest invariant or the same view or chain). A count may only be
//! counted: shown on `port_id` (sY of a word without a constant), written by `OUTPUT`, used
//! as an address, shifted, tested or masked, it is refused. On `out_port` (sX, shown in every
//! cycle without an OUTPUT) it is allowed only where the design reads `out_port` under a write
//! strobe alone (the caller says). (A word without a constant shows sY in every cycle: a
//! `JUMP NZ, 1D9` shows sD, bits 7:4 of its address, and a loop whose count is there is
//! refused.) Every branch on a chain's flag must go as it went: each
//! such flag's interval bounds the periods in which `W` keeps to the same side of it
//! ([`CountingPeriod::room`]). By induction over the periods, the next `room` do what the
//! first did: the same instructions, the same inputs and outputs, the same state but for the
//! count.
//!
//! ```
//! use kcpsm6::asm::assemble_str;
//! use kcpsm6::counting::CountingPeriod;
//! use kcpsm6::iss::{Config, Cpu, NullBus, Pins};
//! // A 24-bit software delay of 0x010203 turns, 8 cycles each. (Its JUMP NZ, 003 shows s0 on
//! // port_id, bits 7:4 of the address: the count is kept in s5-s7.)
//! let p = assemble_str(
//!     "LOAD s7, 01\nLOAD s6, 02\nLOAD s5, 03\n\
//!      delay: SUB s5, 01\nSUBCY s6, 00\nSUBCY s7, 00\nJUMP NZ, delay\nOUTPUT s5, 07\nhalt: JUMP halt\n",
//! ).unwrap();
//! let mut cpu = Cpu::new(Config::default(), &p.image.words[..]);
//! let mut bus = NullBus::default();
//! cpu.run_instructions(10, &mut bus).unwrap(); // into the loop
//! let mark = cpu.clone();
//! for _ in 0..8 {
//!     cpu.tick(Pins::default(), &mut bus); // one turn
//! }
//! let found = CountingPeriod::find(&mark, &cpu, Pins::default(), &[], true).unwrap();
//! // The turns left, but for the last (whose JUMP NZ falls through).
//! let room = found.room();
//! assert!(room > 60_000);
//! let skipped = found.state_after(room);
//! let mut simulated = cpu.clone();
//! for _ in 0..8 * room {
//!     simulated.tick(Pins::default(), &mut bus);
//! }
//! assert!(skipped == simulated);
//! ```

use crate::isa::{Cond, Opcode};
use crate::iss::{Bus, Cpu, Phase, Pins, RetireKind};

/// The abstract bytes: 32 registers, 256 scratch-pad bytes, the ALU result in flight.
const BYTES: usize = 289;
const SPM: usize = 32;
const RESULT: usize = 288;
/// The abstract flags: C, Z, the carry and zero in flight, the stack RAM's 32 carries and 32
/// zeros.
const FLAGS: usize = 68;
const C: usize = 0;
const Z: usize = 1;
const CARRY_IN_FLIGHT: usize = 2;
const ZERO_IN_FLIGHT: usize = 3;
const STACK_C: usize = 4;
const STACK_Z: usize = 36;
/// The widest count, in bytes (its arithmetic stays within u128 with a period count).
const MAX_WIDTH: usize = 8;

/// The refusal of a moment that is not the end of a period at all (the core's control state,
/// or all its bytes, differ from the mark's): it says nothing of the periods from the mark.
pub const NOT_A_PERIOD: &str = "not the end of a period";

/// The refusal of a period in which a count is set to something else (its homes in
/// [`Refusal::count`]).
pub const RELOADED: &str = "a count's byte ends as something else";

/// Why a period is not one that counts: what the proof met, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    pub what: &'static str,
    /// The address of the word on `instruction` when it was met (none: at the period's end).
    pub pc: Option<u16>,
    /// The homes of the count refused, when one is: set to something else within the period
    /// (an inner loop's count, reloaded at every turn of an outer one) or used otherwise than
    /// counted (shown on port_id, say). Taken as state, it may show a longer period that
    /// counts.
    pub count: Option<Vec<usize>>,
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.pc {
            Some(pc) => write!(f, "{} (at {pc:03X})", self.what),
            None => f.write_str(self.what),
        }
    }
}

/// A byte of the state, as the proof sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Byte {
    Invariant,
    /// Its value at the period's start (the first run, which finds the homes).
    Start(u16),
    /// Byte `i` of `W_g + c` (`c` modulo 2^(8(i+1)): the bytes above do not matter).
    View {
        g: u8,
        i: u8,
        c: u128,
    },
}

/// A flag of a chain on count `g`: the carry (`carry`) or the zero of `V + k` (`add`) or
/// `V - k` over bytes `s..m` of `V = W_g + c`, with `c` and `k` modulo 2^8m.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Chain {
    g: u8,
    c: u128,
    add: bool,
    k: u128,
    s: u8,
    m: u8,
    carry: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Flag {
    Invariant,
    Chain(Chain),
}

/// `W mod 2^bits` lies in `[lo, lo + len)` (modulo 2^bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Interval {
    bits: u32,
    lo: u128,
    len: u128,
}

fn mask(bits: u32) -> u128 {
    if bits >= 128 {
        u128::MAX
    } else {
        (1u128 << bits) - 1
    }
}

impl Chain {
    /// The interval of `W_g` in which the flag is set.
    fn interval(&self) -> Interval {
        let bits = 8 * self.m as u32;
        let m = mask(bits);
        let (k, c) = (self.k & m, self.c & m);
        let zeros = 1u128 << (8 * self.s as u32); // bytes below s are not in the chain's zero
        let (lo, len) = match (self.add, self.carry) {
            (false, true) => (0u128.wrapping_sub(c), k),                     // V < k
            (false, false) => (k.wrapping_sub(c), zeros),                    // V - k in [0, 2^8s)
            (true, true) => (0u128.wrapping_sub(k).wrapping_sub(c), k),      // V >= 2^8m - k
            (true, false) => (0u128.wrapping_sub(k).wrapping_sub(c), zeros), // V + k in [0, 2^8s)
        };
        Interval { bits, lo: lo & m, len }
    }

    /// The same flag one period earlier, in terms of the count now.
    fn earlier(self, d: u128) -> Chain {
        Chain { c: self.c.wrapping_sub(d) & mask(8 * self.m as u32), ..self }
    }
}

impl Interval {
    fn holds(&self, w: u128) -> bool {
        let m = mask(self.bits);
        (w.wrapping_sub(self.lo) & m) < self.len
    }

    /// How many steps of `d` from `w` keep the same side of the interval: the steps before
    /// the first that may cross one of its ends (one step over both is taken as crossing).
    fn room(&self, w: u128, d: u128) -> u64 {
        let m = mask(self.bits);
        let (w, d) = (w & m, d & m);
        if d == 0 || self.len == 0 || self.len > m {
            return u64::MAX;
        }
        let half = m / 2 + 1;
        let mut room = u64::MAX;
        for b in [self.lo, self.lo.wrapping_add(self.len) & m] {
            let steps = if d < half {
                // Up by d: crossing b when a step ends at or past it.
                let dist = (b.wrapping_sub(w).wrapping_sub(1) & m) + 1;
                dist.div_ceil(d) - 1
            } else {
                // Down by m + 1 - d: crossing b when a step ends below it.
                let down = (m - d) + 1;
                (w.wrapping_sub(b) & m) / down
            };
            room = room.min(u64::try_from(steps).unwrap_or(u64::MAX));
        }
        room
    }
}

/// A count: its home bytes (low first), each with its offset at the period's start (byte `i`
/// of `W + c_i`: a period that starts within a chain has the low bytes counted and the rest
/// not yet), its value at the start of the period the proof ran (in the frame of
/// [`CountingPeriod::advance`]), and its move per period.
#[derive(Clone, Debug)]
struct Count {
    homes: Vec<(usize, u128)>,
    w: u128,
    d: u128,
}

impl Count {
    fn bits(&self) -> u32 {
        8 * self.homes.len() as u32
    }
}

/// A period of a core in which it only counts (see the module's documentation): the core at
/// the period's end, and how every byte and flag that differs between periods follows the
/// counts.
#[derive(Clone)]
pub struct CountingPeriod {
    /// The core at the end of the period (cycle count and all).
    end: Cpu,
    /// Cycles per period.
    cycles: u64,
    counts: Vec<Count>,
    /// Every byte and flag that is not invariant, as the period leaves it.
    bytes: Vec<(usize, Byte)>,
    flags: Vec<(usize, Chain)>,
    /// Further periods proven to do what this one did.
    room: u64,
}

impl std::fmt::Debug for CountingPeriod {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CountingPeriod")
            .field("cycles", &self.cycles)
            .field("counts", &self.counts)
            .field("room", &self.room)
            .finish_non_exhaustive()
    }
}

/// Are the bytes at `homes` (numbered as [`CountingPeriod::homes`]) the same in both cores?
///
/// ```
/// use kcpsm6::counting::same_bytes;
/// use kcpsm6::iss::Cpu;
/// let cpu = Cpu::new(Default::default(), &[0; 4096]);
/// assert!(same_bytes(&cpu, &cpu.clone(), &[0, 5, 32]));
/// ```
pub fn same_bytes(a: &Cpu, b: &Cpu, homes: &[usize]) -> bool {
    homes.iter().all(|&at| a.byte_at(at) == b.byte_at(at))
}

impl CountingPeriod {
    /// Prove that the period the core ran from `mark` to `now` only counts, with its pins
    /// held at `pins` and `inputs` read by its INPUTs in order; `out_port_free`: the design
    /// reads `out_port` only under a write strobe.
    pub fn find(mark: &Cpu, now: &Cpu, pins: Pins, inputs: &[u8], out_port_free: bool) -> Result<Self, Refusal> {
        Self::find_seen(mark, now, pins, inputs, Seen { out_port: !out_port_free, port_id: true })
    }

    /// As [`CountingPeriod::find`] for a core that nothing sees between its port accesses (run
    /// on its own, its pins low, reading nothing): a count may be shown on `out_port` and
    /// `port_id`.
    pub fn find_alone(mark: &Cpu, now: &Cpu) -> Result<Self, Refusal> {
        Self::find_seen(mark, now, Pins::default(), &[], Seen { out_port: false, port_id: false })
    }

    fn find_seen(mark: &Cpu, now: &Cpu, pins: Pins, inputs: &[u8], seen: Seen) -> Result<Self, Refusal> {
        let refuse = |what| Err(Refusal { what, pc: None, count: None });
        if now.cycle() <= mark.cycle() || mark.config() != now.config() {
            return refuse(NOT_A_PERIOD);
        }
        // Only bytes and flags may differ.
        let mut same = now.clone();
        for at in 0..BYTES {
            same.set_byte_at(at, mark.byte_at(at));
        }
        for at in 0..FLAGS {
            same.set_flag_at(at, mark.flag_at(at));
        }
        let differs = |at: usize| mark.byte_at(at) != now.byte_at(at);
        if !same.same_state_as(mark) || !(0..BYTES).any(differs) {
            return refuse(NOT_A_PERIOD);
        }

        // The first runs find the homes and how the period leaves every byte and flag: each
        // starts from where the one before left them one period earlier (a chain that spans
        // the period's start is found whole by the second), until the homes stay.
        let seeds: Vec<bool> = (0..BYTES).map(differs).collect();
        let mut first = Proof::new(seen, None, seeds.clone());
        first.run(mark, now, pins, inputs)?;
        let mut counts = first.counts_found(mark)?;
        for _ in 0..MAX_WIDTH {
            let mut again = Proof::new(seen, None, seeds.clone());
            again.homes = first.homes.clone();
            again.start_from(&first, &counts);
            again.run(mark, now, pins, inputs)?;
            let found = again.counts_found(mark)?;
            let settled = again.homes == first.homes;
            first = again;
            counts = found;
            if settled {
                break;
            }
        }

        // The second run, from every byte and flag as the first left it one period earlier.
        let mut second = Proof::new(seen, Some(&counts), Vec::new());
        second.start_from(&first, &counts);
        let start = (second.bytes, second.flags);
        second.run(mark, now, pins, inputs)?;

        // It ends as the first did, and both ends are what the abstraction says.
        let ws: Vec<u128> = counts.iter().map(|c| c.w).collect();
        let mut bytes = Vec::new();
        for at in 0..BYTES {
            let end = second.bytes[at];
            let expected = match first.bytes[at] {
                Byte::Start(_) => Byte::Invariant,
                b => b,
            };
            if end != expected {
                return refuse("a byte does not end as it starts one period on");
            }
            if value(start.0[at], &ws, mark.byte_at(at)) != mark.byte_at(at)
                || value(end, &ws, mark.byte_at(at)) != now.byte_at(at)
            {
                return refuse("a byte is not what the count makes it");
            }
            if end != Byte::Invariant {
                bytes.push((at, end));
            }
        }
        let mut flags = Vec::new();
        for at in 0..FLAGS {
            let end = second.flags[at];
            if end != first.flags[at] {
                return refuse("a flag does not end as it starts one period on");
            }
            let holds = |f: Flag, w: bool| match f {
                Flag::Invariant => w,
                Flag::Chain(ch) => ch.interval().holds(ws[ch.g as usize]),
            };
            if holds(start.1[at], mark.flag_at(at)) != mark.flag_at(at)
                || holds(end, mark.flag_at(at)) != now.flag_at(at)
            {
                return refuse("a flag is not what the count makes it");
            }
            if let Flag::Chain(ch) = end {
                flags.push((at, ch));
            }
        }
        let room = second.room;
        Ok(CountingPeriod { end: now.clone(), cycles: now.cycle() - mark.cycle(), counts, bytes, flags, room })
    }

    /// How many more periods do what this one did.
    pub fn room(&self) -> u64 {
        self.room
    }

    /// Cycles per period.
    pub fn cycles(&self) -> u64 {
        self.cycles
    }

    /// Where the counts live: their home bytes (numbered as the core's bytes: 0-31 the
    /// registers, 32-287 the scratch pad, 288 the result in flight), low byte first.
    pub fn homes(&self) -> Vec<usize> {
        self.counts.iter().flat_map(|c| c.homes.iter().map(|&(at, _)| at)).collect()
    }

    /// The core `periods` periods after the end of this one (within [`CountingPeriod::room`]):
    /// as simulating them leaves it.
    pub fn state_after(&self, periods: u64) -> Cpu {
        let mut cpu = self.end.clone();
        cpu.skip_period(periods * self.cycles);
        // The counts at the start of the period that ends then.
        let ws: Vec<u128> =
            self.counts.iter().map(|c| c.w.wrapping_add(c.d.wrapping_mul(periods as u128)) & mask(c.bits())).collect();
        for &(at, b) in &self.bytes {
            cpu.set_byte_at(at, value(b, &ws, 0));
        }
        for &(at, ch) in &self.flags {
            cpu.set_flag_at(at, ch.interval().holds(ws[ch.g as usize]));
        }
        cpu
    }

    /// Take the end of the period `periods` on as this one's (within the room).
    pub fn advance(&mut self, periods: u64) {
        self.end = self.state_after(periods);
        for c in &mut self.counts {
            c.w = c.w.wrapping_add(c.d.wrapping_mul(periods as u128)) & mask(c.bits());
        }
        self.room = self.room.saturating_sub(periods);
    }

    /// Whether `cpu` is this core some whole number of periods on (at most its room): the
    /// count of them.
    pub fn periods_to(&self, cpu: &Cpu) -> Option<u64> {
        let gone = cpu.cycle().checked_sub(self.end.cycle())?;
        let n = gone / self.cycles;
        (n * self.cycles == gone && n <= self.room && self.state_after(n) == *cpu).then_some(n)
    }
}

impl Byte {
    /// A start value of a byte that differs between the period's ends (else invariant).
    fn filter_seed(self, seeds: &[bool]) -> Byte {
        match self {
            Byte::Start(at) if !seeds.get(at as usize).copied().unwrap_or(false) => Byte::Invariant,
            b => b,
        }
    }
}

fn view(g: u8, i: u8, c: u128) -> Byte {
    Byte::View { g, i, c: c & mask(8 * (i as u32 + 1)) }
}

/// A byte's value with the counts at `ws` (an invariant one: `own`).
fn value(b: Byte, ws: &[u128], own: u8) -> u8 {
    match b {
        Byte::View { g, i, c } => (ws[g as usize].wrapping_add(c) >> (8 * i as u32)) as u8,
        _ => own,
    }
}

/// The core's inputs as the period read them.
struct Inputs<'a> {
    values: &'a [u8],
    next: usize,
    short: bool,
}

impl Bus for Inputs<'_> {
    fn input(&mut self, _port: u8, _cycle: u64) -> u8 {
        let v = self.values.get(self.next).copied();
        self.next += 1;
        self.short |= v.is_none();
        v.unwrap_or(0)
    }
    fn output(&mut self, _port: u8, _value: u8, _cycle: u64) {}
    fn output_k(&mut self, _port: u8, _value: u8, _cycle: u64) {}
}

/// One run of the proof over the period.
struct Proof<'a> {
    bytes: [Byte; BYTES],
    flags: [Flag; FLAGS],
    /// The first runs: the homes found so far (and their offsets at the start), one list per
    /// count. The second: none (its counts are fixed).
    homes: Vec<Vec<(usize, u128)>>,
    counts: Option<&'a [Count]>,
    /// The bytes that differ between the period's ends: a chain starts a count only there
    /// (the first run).
    seeds: Vec<bool>,
    seen: Seen,
    room: u64,
    pc: u16,
}

/// What the design sees of the core in every cycle: `out_port`, `port_id`.
#[derive(Clone, Copy)]
struct Seen {
    out_port: bool,
    port_id: bool,
}

impl<'a> Proof<'a> {
    fn new(seen: Seen, counts: Option<&'a [Count]>, seeds: Vec<bool>) -> Self {
        let mut bytes = [Byte::Invariant; BYTES];
        if counts.is_none() {
            for (at, b) in bytes.iter_mut().enumerate() {
                *b = Byte::Start(at as u16);
            }
        }
        Proof { bytes, flags: [Flag::Invariant; FLAGS], homes: Vec::new(), counts, seeds, seen, room: u64::MAX, pc: 0 }
    }

    /// The counts this run found: their homes, their values at the period's start (from
    /// `mark`) and their moves (the top byte's offset at the end).
    fn counts_found(&self, mark: &Cpu) -> Result<Vec<Count>, Refusal> {
        let refuse = |what| Err(Refusal { what, pc: None, count: None });
        let mut counts = Vec::new();
        for (g, homes) in self.homes.iter().enumerate() {
            let (top, c_top) = homes[homes.len() - 1];
            let Byte::View { c: end, .. } = self.bytes[top] else {
                return Err(Refusal {
                    what: RELOADED,
                    pc: None,
                    count: Some(homes.iter().map(|&(at, _)| at).collect()),
                });
            };
            let d = end.wrapping_sub(c_top) & mask(8 * homes.len() as u32);
            // W from the bytes at the start: byte i of W + c_i is home i's, low byte first.
            let mut w = 0u128;
            for (i, &(at, c)) in homes.iter().enumerate() {
                let shift = 8 * i as u32;
                let q = (w.wrapping_add(c) >> shift) as u8;
                w |= (mark.byte_at(at).wrapping_sub(q) as u128) << shift;
                if self.bytes[at] != view(g as u8, i as u8, c.wrapping_add(d)) {
                    return refuse("a count's bytes move apart");
                }
            }
            counts.push(Count { homes: homes.clone(), w, d });
        }
        Ok(counts)
    }

    /// Start where `run` ended one period earlier: the homes as their counts, every other
    /// byte and flag that follows a count as it ended less one period's move; the rest as
    /// this run starts them.
    fn start_from(&mut self, run: &Proof, counts: &[Count]) {
        for at in 0..BYTES {
            if let Byte::View { g, i, c } = run.bytes[at] {
                self.bytes[at] = view(g, i, c.wrapping_sub(counts[g as usize].d));
            } else if self.strict() {
                self.bytes[at] = Byte::Invariant;
            }
        }
        for (g, count) in counts.iter().enumerate() {
            for (i, &(at, c)) in count.homes.iter().enumerate() {
                self.bytes[at] = view(g as u8, i as u8, c);
            }
        }
        for at in 0..FLAGS {
            self.flags[at] = match run.flags[at] {
                Flag::Chain(ch) => Flag::Chain(ch.earlier(counts[ch.g as usize].d)),
                Flag::Invariant => Flag::Invariant,
            };
        }
    }

    fn refuse<T>(&self, what: &'static str) -> Result<T, Refusal> {
        Err(Refusal { what, pc: Some(self.pc), count: None })
    }

    /// The second run, which proves: a count is a count there.
    fn strict(&self) -> bool {
        self.counts.is_some()
    }

    fn varies(&self, b: Byte) -> bool {
        matches!(b, Byte::View { .. })
    }

    /// A byte read as a value (not counted): refused if it is a count's.
    fn plain(&self, b: Byte, what: &'static str) -> Result<(), Refusal> {
        match (b, self.counts) {
            (Byte::View { g, .. }, Some(counts)) => Err(Refusal {
                what,
                pc: Some(self.pc),
                count: Some(counts[g as usize].homes.iter().map(|&(at, _)| at).collect()),
            }),
            _ => Ok(()),
        }
    }

    fn plain_flag(&self, f: usize, what: &'static str) -> Result<(), Refusal> {
        if self.strict() && self.flags[f] != Flag::Invariant {
            return self.refuse(what);
        }
        Ok(())
    }

    /// Run the period from `mark` beside the ISS, which must end at `now`.
    fn run(&mut self, mark: &Cpu, now: &Cpu, pins: Pins, inputs: &[u8]) -> Result<(), Refusal> {
        let mut cpu = mark.clone();
        let mut bus = Inputs { values: inputs, next: 0, short: false };
        while cpu.cycle() < now.cycle() {
            self.cycle(&cpu)?;
            cpu.tick(pins, &mut bus);
        }
        if bus.short || bus.next != inputs.len() {
            return Err(Refusal { what: "the inputs are not the period's", pc: None, count: None });
        }
        if cpu != *now {
            return Err(Refusal { what: "the period does not run again as it ran", pc: None, count: None });
        }
        Ok(())
    }

    /// One cycle of the core `c` (before its tick), in the abstraction.
    fn cycle(&mut self, c: &Cpu) -> Result<(), Refusal> {
        let w = c.instruction();
        self.pc = c.pc();
        if c.phase() == Phase::Idle || c.in_reset() || !c.running() {
            return self.refuse("reset or sleep");
        }
        let (bank, xb) = (c.bank() as usize * 16, c.sx_bank() as usize * 16);
        let (x, y) = (xb + (w >> 8 & 15) as usize, bank + (w >> 4 & 15) as usize);
        // What the core shows in every cycle: port_id (sY unless the word has a constant) and
        // out_port (sX unless the word has one).
        if w & 1 << 12 == 0 && self.seen.port_id {
            self.plain(self.bytes[y], "a count on port_id")?;
        }
        if w & 1 << 13 == 0 && self.seen.out_port {
            self.plain(self.bytes[x], "a count on out_port, which the design reads")?;
        }

        // The second cycle of the instruction in flight.
        if let Some((kind, op)) = c.in_flight() {
            if kind == RetireKind::Interrupt {
                return self.refuse("an interrupt");
            }
            if op == Opcode::Output {
                self.plain(self.bytes[x], "a count written to a port")?;
            }
            if op == Opcode::Store {
                self.bytes[SPM + c.spm_addr_now()] = self.bytes[x];
            }
            if op.writes_register() {
                self.bytes[x] = if op == Opcode::Input { Byte::Invariant } else { self.bytes[RESULT] };
            }
            if op.writes_flags() {
                self.flags[C] = self.flags[CARRY_IN_FLIGHT];
                self.flags[Z] = self.flags[ZERO_IN_FLIGHT];
            }
            // Nothing is in flight after a second cycle (read as 0).
            self.bytes[RESULT] = Byte::Invariant;
            self.flags[CARRY_IN_FLIGHT] = Flag::Invariant;
            self.flags[ZERO_IN_FLIGHT] = Flag::Invariant;
        }
        if c.phase() != Phase::Decode {
            return Ok(());
        }

        // The D cycle: the stack RAM write, the branch, the ALU.
        let op = Opcode::of(w);
        if matches!(op, Opcode::RegBank | Opcode::Star | Opcode::ReturnI) || c.interrupt_entry() {
            return self.refuse("a bank switch or an interrupt");
        }
        let depth = c.depth() as usize;
        self.flags[STACK_C + depth] = self.flags[C];
        self.flags[STACK_Z + depth] = self.flags[Z];
        if matches!(op, Opcode::Call | Opcode::Jump | Opcode::Return) {
            if let Some(cond) = Cond::of(w) {
                let f = if matches!(cond, Cond::Z | Cond::NZ) { Z } else { C };
                if let Flag::Chain(ch) = self.flags[f] {
                    if let Some(counts) = self.counts {
                        let count = &counts[ch.g as usize];
                        let iv = ch.interval();
                        if iv.holds(count.w) != c.flag_at(f) {
                            return self.refuse("a branch the count does not explain");
                        }
                        self.room = self.room.min(iv.room(count.w, count.d));
                    }
                }
            }
        }
        if matches!(op, Opcode::CallAt | Opcode::JumpAt) {
            self.plain(self.bytes[x], "a count as a jump target")?;
        }
        let (result, carry, zero) = self.alu(c, op, w, x)?;
        self.bytes[RESULT] = result;
        self.flags[CARRY_IN_FLIGHT] = carry;
        self.flags[ZERO_IN_FLIGHT] = zero;
        Ok(())
    }

    /// The ALU in D: the result, carry and zero in flight.
    fn alu(&mut self, c: &Cpu, op: Opcode, w: u32, x: usize) -> Result<(Byte, Flag, Flag), Refusal> {
        const FIXED: Flag = Flag::Invariant;
        let sx = self.bytes[x];
        match op {
            Opcode::And | Opcode::Or | Opcode::Xor | Opcode::Test | Opcode::TestCy | Opcode::Shift => {
                self.plain(sx, "a count masked, tested or shifted")?;
                if op == Opcode::TestCy || (op == Opcode::Shift && w & 0x80 == 0 && w >> 1 & 3 == 0) {
                    self.plain_flag(C, "a count's carry shifted or tested")?;
                    self.plain_flag(Z, "a count's zero tested")?;
                }
                Ok((Byte::Invariant, FIXED, FIXED))
            }
            Opcode::Add | Opcode::AddCy | Opcode::Sub | Opcode::SubCy | Opcode::Compare | Opcode::CompareCy => {
                self.arithmetic(c, op, sx)
            }
            Opcode::Fetch => Ok((self.bytes[SPM + c.spm_addr_now()], FIXED, FIXED)),
            Opcode::LoadReturn => Ok((Byte::Invariant, FIXED, FIXED)),
            // LOAD and the rest: the operand (a register operand is on port_id: no count).
            _ => {
                let y = c.bank() as usize * 16 + (w >> 4 & 15) as usize;
                Ok((if w & 1 << 12 == 0 { self.bytes[y] } else { Byte::Invariant }, FIXED, FIXED))
            }
        }
    }

    /// ADD, SUB, COMPARE and their CY forms: invariant on invariant operands, else a step of a
    /// chain on a count (with a constant or invariant second operand).
    fn arithmetic(&mut self, c: &Cpu, op: Opcode, mut sx: Byte) -> Result<(Byte, Flag, Flag), Refusal> {
        let add = matches!(op, Opcode::Add | Opcode::AddCy);
        let kb = c.operand_now() as u128;
        let (cin, zin) = (self.flags[C], self.flags[Z]);
        if !op.carry_form() {
            if let (Byte::Start(at), true) = (sx.filter_seed(&self.seeds), op != Opcode::Compare) {
                // The first runs: a chain that counts starts a count on a byte that differs.
                self.homes.push(vec![(at as usize, 0)]);
                sx = self.promote(at as usize, (self.homes.len() - 1) as u8, 0, 0);
            }
            let Byte::View { g, i, c: off } = sx else {
                return Ok((Byte::Invariant, Flag::Invariant, Flag::Invariant));
            };
            let k = kb << (8 * i as u32);
            let r = if add { off.wrapping_add(k) } else { off.wrapping_sub(k) };
            let chain = |carry| Chain { g, c: off, add, k, s: i, m: i + 1, carry };
            return Ok((view(g, i, r), Flag::Chain(chain(true)), Flag::Chain(chain(false))));
        }
        let Flag::Chain(ch) = cin else {
            if self.strict() && (self.varies(sx) || matches!(zin, Flag::Chain(_))) {
                return self.refuse("a count's CY step without its carry");
            }
            return Ok((Byte::Invariant, Flag::Invariant, Flag::Invariant));
        };
        if !self.strict() && !matches!(sx, Byte::Start(_) | Byte::View { .. }) {
            // The first runs: a chain into a byte the period sets (its count found later).
            return Ok((Byte::Invariant, Flag::Invariant, Flag::Invariant));
        }
        if !ch.carry {
            return self.refuse("a chain's zero as a carry");
        }
        if let (Byte::Start(at), false) = (sx, self.strict()) {
            let g = ch.g as usize;
            if self.homes.get(g).map(Vec::len) != Some(ch.m as usize) || self.homes[g].len() == MAX_WIDTH {
                return self.refuse("a chain onto a byte that is not its count's next");
            }
            // Byte m of the chain's V = W + c (the chain says the low bytes; this one is W's).
            self.homes[g].push((at as usize, ch.c));
            sx = self.promote(at as usize, ch.g, ch.m, ch.c);
        }
        let Byte::View { g, i, c: off } = sx else {
            return self.refuse("a chain's carry into a byte that does not count");
        };
        let low = mask(8 * ch.m as u32);
        if g != ch.g || i != ch.m || off & low != ch.c || add != ch.add {
            return self.refuse("a chain's carry into another count's byte");
        }
        let k = ch.k | kb << (8 * i as u32);
        let r = if add { off.wrapping_add(k) } else { off.wrapping_sub(k) };
        let next = |carry, s| Chain { g, c: off & mask(8 * (i as u32 + 1)), add, k, s, m: i + 1, carry };
        // Z = (this byte == 0) & Z before: the chain's zero goes on; a zero that was clear
        // stays clear; one that was set starts at this byte.
        let zero = match zin {
            Flag::Chain(z) if !z.carry && (z.g, z.c, z.add, z.k, z.m) == (ch.g, ch.c, ch.add, ch.k, ch.m) => {
                Flag::Chain(next(false, z.s))
            }
            Flag::Invariant if !c.zero() => Flag::Invariant,
            Flag::Invariant => Flag::Chain(next(false, i)),
            Flag::Chain(_) => return self.refuse("a chain's zero from another chain"),
        };
        Ok((view(g, i, r), Flag::Chain(next(true, ch.s)), zero))
    }

    /// The first runs: byte `at` becomes byte `i` of count `g` plus `c` (wherever its start
    /// value is).
    fn promote(&mut self, at: usize, g: u8, i: u8, c: u128) -> Byte {
        let b = view(g, i, c);
        for x in self.bytes.iter_mut() {
            if *x == Byte::Start(at as u16) {
                *x = b;
            }
        }
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asm::assemble_str;
    use crate::iss::{Config, NullBus};

    /// `src` placed at 0F0 (its jumps show sF on port_id, which it does not use).
    fn program(src: &str) -> Vec<u32> {
        let p = assemble_str(&format!("JUMP start\nADDRESS 0F0\nstart: {src}")).unwrap();
        p.image.words.to_vec()
    }

    /// A core running `src` after `warm` instructions (and the jump to it), and one period of
    /// `cycles` on.
    fn period(src: &str, warm: u64, cycles: u64) -> (Cpu, Cpu) {
        let p = program(src);
        let mut cpu = Cpu::new(Config::default(), &p);
        let mut bus = NullBus::default();
        cpu.run_instructions(warm + 1, &mut bus).unwrap();
        let mark = cpu.clone();
        for _ in 0..cycles {
            cpu.tick(Pins::default(), &mut bus);
        }
        (mark, cpu)
    }

    /// Every skip within the room equals the simulation, and the period after the room
    /// does something else.
    fn check(found: &CountingPeriod, from: &Cpu) {
        let mut sim = from.clone();
        let mut bus = NullBus::default();
        let room = found.room();
        assert!(room < 1 << 24, "room {room}");
        for n in 0..=room {
            if n % 97 == 0 || n + 2 > room {
                assert!(found.state_after(n) == sim, "period {n} of {room}");
                assert_eq!(found.periods_to(&sim), Some(n));
            }
            for _ in 0..found.cycles() {
                sim.tick(Pins::default(), &mut bus);
            }
        }
        // The period after the room is not one more of the same.
        assert!(found.state_after(room + 1) != sim, "the room ends too early");
    }

    #[test]
    fn a_24_bit_software_delay_counts_to_its_end() {
        let src = "LOAD s2, 00\nLOAD s1, 03\nLOAD s0, 10\n\
                   delay: SUB s0, 1'd\nSUBCY s1, 0'd\nSUBCY s2, 0'd\nJUMP NZ, delay\nRETURN\n";
        // Marks at each cycle of the 8-cycle turn: any phase of the period.
        for warm in 0..8 {
            let mut cpu = Cpu::new(Config::default(), &program(src));
            let mut bus = NullBus::default();
            cpu.run_instructions(9, &mut bus).unwrap();
            for _ in 0..warm {
                cpu.tick(Pins::default(), &mut bus);
            }
            let mark = cpu.clone();
            for _ in 0..8 {
                cpu.tick(Pins::default(), &mut bus);
            }
            let found = CountingPeriod::find(&mark, &cpu, Pins::default(), &[], true).unwrap();
            assert!(found.room() > 700, "{warm}: {}", found.room());
            check(&found, &cpu);
        }
    }

    #[test]
    fn nested_delays_count_at_every_level() {
        // The inner loop reloads s0 each turn of s1: a period of the outer loop counts s1.
        let src = "LOAD s1, 20\nouter: LOAD s0, 05\ninner: SUB s0, 01\nJUMP NZ, inner\n\
                   SUB s1, 01\nJUMP NZ, outer\nOUTPUT s1, 00\nh: JUMP h\n";
        let turn = 2 + 5 * 4 + 4; // LOAD, five inner turns, SUB + JUMP
        let (mark, now) = period(src, 3, 2 * turn);
        let found = CountingPeriod::find(&mark, &now, Pins::default(), &[], true).unwrap();
        check(&found, &now);
        // The inner loop alone.
        let (mark, now) = period(src, 3, 4);
        let found = CountingPeriod::find(&mark, &now, Pins::default(), &[], true).unwrap();
        check(&found, &now);
    }

    #[test]
    fn a_count_in_the_scratch_pad_counts() {
        let src = "LOAD s0, 40\nSTORE s0, 05\n\
                   again: FETCH s3, 05\nADD s3, 03\nSTORE s3, 05\nCOMPARE s3, F0\nJUMP C, again\nhalt: JUMP halt\n";
        let (mark, now) = period(src, 5, 10);
        let found = CountingPeriod::find(&mark, &now, Pins::default(), &[], true).unwrap();
        check(&found, &now);
    }

    #[test]
    fn a_timeout_that_polls_an_input_counts() {
        // INPUT, TEST the input (invariant), count down a timeout (the package's UART_RX).
        let src = "LOAD s1, A7\nrx: INPUT s0, 02\nTEST s0, 10\nJUMP NZ, got\nSUB s1, 01\nRETURN Z\nJUMP rx\n\
                   got: JUMP got\n";
        let mut cpu = Cpu::new(Config::default(), &program(src));
        let mut bus = NullBus { input_value: 0x01 };
        cpu.run_instructions(5, &mut bus).unwrap();
        let mark = cpu.clone();
        for _ in 0..12 {
            cpu.tick(Pins::default(), &mut bus);
        }
        let found = CountingPeriod::find(&mark, &cpu, Pins::default(), &[0x01], true).unwrap();
        assert!(found.room() > 100);
        let mut sim = cpu.clone();
        for _ in 0..12 * found.room() {
            sim.tick(Pins::default(), &mut bus);
        }
        assert!(found.state_after(found.room()) == sim);
        // The inputs must be the period's.
        assert!(CountingPeriod::find(&mark, &cpu, Pins::default(), &[], true).is_err());
    }

    #[test]
    fn what_is_not_a_count_is_refused() {
        let cases = [
            // The count is written to a port.
            (
                "LOAD s0, 50\nloop: SUB s0, 01\nOUTPUT s0, 03\nJUMP NZ, loop\nhalt: JUMP halt\n",
                6,
                "a count written to a port",
            ),
            // Copied through a register: port_id shows it.
            ("LOAD s0, 50\nloop: ADD s0, 01\nLOAD s4, s0\nAND s4, 01\nJUMP loop\n", 8, "a count on port_id"),
            // Shifted (SR0's code shows s0 on port_id first: shift s1): no longer a count.
            (
                "LOAD s1, 50\nloop: ADD s1, 02\nLOAD s5, 00\nSR0 s1\nJUMP loop\n",
                8,
                "a count's byte ends as something else",
            ),
            // Masked.
            ("LOAD s1, 50\nloop: ADD s1, 02\nTEST s1, 80\nJUMP loop\n", 6, "a count masked, tested or shifted"),
        ];
        for (src, cycles, what) in cases {
            // Marked after one turn (the stack RAM's entry as the turn leaves it).
            let (mark, now) = period(src, 1 + cycles / 2, cycles);
            let e = CountingPeriod::find(&mark, &now, Pins::default(), &[], true).unwrap_err();
            assert_eq!(e.what, what, "{src}");
        }
        // On out_port, where the design reads it: refused.
        let (mark, now) = period("LOAD s0, 50\nloop: SUB s0, 01\nJUMP NZ, loop\nhalt: JUMP halt\n", 3, 4);
        let e = CountingPeriod::find(&mark, &now, Pins::default(), &[], false).unwrap_err();
        assert_eq!(e.what, "a count on out_port, which the design reads");
        assert!(CountingPeriod::find(&mark, &now, Pins::default(), &[], true).is_ok());
        // A loop whose JUMP's address shows the count on port_id (bits 7:4 of 001: s0).
        let p = assemble_str("LOAD s0, 50\nloop: SUB s0, 01\nJUMP NZ, loop\nhalt: JUMP halt\n").unwrap();
        let mut cpu = Cpu::new(Config::default(), &p.image.words[..]);
        let mut bus = NullBus::default();
        cpu.run_instructions(3, &mut bus).unwrap();
        let mark = cpu.clone();
        for _ in 0..4 {
            cpu.tick(Pins::default(), &mut bus);
        }
        let e = CountingPeriod::find(&mark, &cpu, Pins::default(), &[], true).unwrap_err();
        assert_eq!(e.what, "a count on port_id");
    }

    #[test]
    fn an_inner_loop_reloaded_is_named_and_the_outer_period_counts() {
        // s1 counts down 3 turns inside each turn of s0 (a turn of the outer loop is
        // 2 (1 + 2 x 3 + 2) = 18 cycles).
        let src = "LOAD s0, 50\nouter: LOAD s1, 03\ninner: SUB s1, 01\nJUMP NZ, inner\nSUB s0, 01\nJUMP NZ, outer\nhalt: JUMP halt\n";
        // Marked in the inner loop after its first JUMP: a turn and one more inner one on
        // (22 cycles) is the same place with s1 one lower, but s1 was reloaded on the way.
        let (mark, now) = period(src, 4, 22);
        let e = CountingPeriod::find(&mark, &now, Pins::default(), &[], true).unwrap_err();
        assert_eq!((e.what, e.count), (RELOADED, Some(vec![1])));
        // Its inner count the same at both ends: one outer turn counts s0 down by one.
        let (mark, now) = period(src, 4, 18);
        assert!(same_bytes(&mark, &now, &[1]));
        let p = CountingPeriod::find(&mark, &now, Pins::default(), &[], true).unwrap();
        assert_eq!(p.homes(), vec![0]);
        assert_eq!(p.cycles(), 18);
        // s0 is 4F now: the next 4E turns leave it above zero.
        assert_eq!(p.room(), 0x4E);
        let mut sim = now.clone();
        let mut bus = NullBus::default();
        for _ in 0..18 * 5 {
            sim.tick(Pins::default(), &mut bus);
        }
        assert!(p.state_after(5).same_state_as(&sim));
        // A count shown on port_id is named too (it may be an inner one).
        let shown = "LOAD s0, 50\nloop: ADD s0, 01\nLOAD s4, s0\nAND s4, 01\nJUMP loop\n";
        let (mark, now) = period(shown, 5, 8);
        let e = CountingPeriod::find(&mark, &now, Pins::default(), &[], true).unwrap_err();
        assert_eq!((e.what, e.count), ("a count on port_id", Some(vec![0])));
    }

    #[test]
    fn intervals_bound_the_steps_that_keep_their_side() {
        let iv = Interval { bits: 8, lo: 1, len: 1 }; // Z of SUB 1 on a count going down
        assert_eq!(iv.room(100, 0xFF), 98); // 99 steps down to 1
        assert_eq!(iv.room(1, 0xFF), 0);
        assert_eq!(iv.room(0, 0xFF), 254); // down through the wrap to 2
        let up = Interval { bits: 16, lo: 0xF000, len: 0x1000 };
        assert_eq!(up.room(0xEFF0, 3), 5); // 0xEFF3 .. 0xEFFF, then 0xF002
        assert_eq!(up.room(0xF000, 0), u64::MAX);
    }
}
