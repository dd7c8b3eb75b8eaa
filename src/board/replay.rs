//! Loop replay for a KCPSM6 model on a board: a core that went once around a loop and came
//! back to the same flops goes around it again exactly as before as long as its pins are
//! the same, cycle for cycle, so its outputs can be played back instead of simulated.
//!
//! A team's firmware spends most of its time in such loops (polling the semaphore its
//! interrupt routine sets: `COMPARE sE, 00` / `JUMP Z, wait`, four cycles), and every cycle
//! of a board on the ISS calls the core. With the loop recorded, a cycle is one compare of
//! the pins and a table read.
//!
//! Exactness rests on the core being a function of its flops and its pins alone (its ROM is
//! fixed; the bus of a pin-level core is `in_port`, one of the pins): if the flops at a loop
//! head equal those one trip earlier ([`Cpu::same_state_as`], cycle count aside), the trip's
//! pins give the trip's outputs again and end in the same flops. A cycle whose pins differ
//! from the recorded ones ends the replay: the core is brought to where the replayed cycles
//! left it ([`Replay::catch_up`], by simulating the part trip from the head) and simulated.
//! Trips that acknowledge an interrupt are not replayed (the host counts those).
//!
//! ```text
//! cycle:    simulated ........ recorded trip ... | replayed: pins == recorded ? outputs
//! flops:    S0 -> ... -> H  -> ... -> H' == H    | (the core stays at H' until caught up)
//! ```

use kcpsm6::iss::{Cpu, Phase};

/// The longest trip replayed, in cycles (a trip that runs longer is simulated).
const MAX_TRIP: usize = 64;

/// The `interrupt_ack` bit of kcpsm6_iss.v's packed outputs.
const INTERRUPT_ACK: u64 = 1 << 32;

/// A debug build's view of a core after a cycle: its registers and flags (board_abi.h).
pub(crate) type DebugWords = [u32; 5];

/// One core's loop replay: a candidate loop head with the trip recorded since it, or a trip
/// being replayed.
pub(crate) struct Replay {
    /// The core at the candidate head (a copy shares the ROM: copying is cheap).
    head: Cpu,
    /// The candidate head's address; none: no candidate.
    head_pc: Option<u16>,
    /// The address of the previous instruction boundary (a jump back lands at or below it).
    last_pc: u16,
    /// The trip since the head: each cycle's pins and the outputs it gave.
    pins: [u64; MAX_TRIP],
    outs: [u64; MAX_TRIP],
    /// In a debug build, what the waveform shows after each cycle of the trip.
    debug: [DebugWords; MAX_TRIP],
    len: usize,
    /// Replaying: the next cycle's place in the trip, and the cycles replayed in all.
    active: bool,
    pos: usize,
    replayed: u64,
    /// Cycles played back since the core was made (tests).
    #[cfg(test)]
    pub total: u64,
}

impl Replay {
    /// A replay for `cpu`.
    pub fn new(cpu: &Cpu) -> Replay {
        Replay {
            head: cpu.clone(),
            head_pc: None,
            last_pc: 0,
            pins: [0; MAX_TRIP],
            outs: [0; MAX_TRIP],
            debug: [[0; 5]; MAX_TRIP],
            len: 0,
            active: false,
            pos: 0,
            replayed: 0,
            #[cfg(test)]
            total: 0,
        }
    }

    /// The outputs of a cycle with `pins`, played back, or none (not replaying, or the pins
    /// are not the trip's: [`Replay::catch_up`], then simulate the cycle).
    #[inline(always)]
    pub fn next(&mut self, pins: u64) -> Option<u64> {
        if !self.active || self.pins[self.pos] != pins {
            return None;
        }
        let out = self.outs[self.pos];
        self.pos += 1;
        if self.pos == self.len {
            self.pos = 0;
        }
        self.replayed += 1;
        #[cfg(test)]
        {
            self.total += 1;
        }
        Some(out)
    }

    /// The outputs of the last cycle played back (the core's outputs now; only while
    /// replaying).
    pub fn current(&self) -> u64 {
        self.outs[(self.pos + self.len - 1) % self.len]
    }

    /// A debug build's words of the last cycle played back, if replaying.
    pub fn debug(&self) -> Option<DebugWords> {
        self.active.then(|| self.debug[(self.pos + self.len - 1) % self.len])
    }

    /// Cycles are being played back: the core is behind.
    #[inline(always)]
    pub fn active(&self) -> bool {
        self.active
    }

    /// Bring `cpu`, held at the head since the replay began, to where the replayed cycles
    /// left it: whole trips counted, the part trip simulated by `tick` (one cycle with the
    /// given pins). The candidate is dropped either way: call it before anything else reads
    /// or changes the core.
    pub fn catch_up(&mut self, cpu: &mut Cpu, mut tick: impl FnMut(&mut Cpu, u64)) {
        if self.active {
            let len = self.len as u64;
            cpu.skip_period(len * (self.replayed / len));
            for &pins in &self.pins[..(self.replayed % len) as usize] {
                tick(cpu, pins);
            }
            self.active = false;
        }
        self.head_pc = None;
        self.len = 0;
    }

    /// After a simulated cycle with `pins` that gave `out` (and in a debug build `debug`),
    /// `cpu` as it left it: the cycle joins the trip; at a jump back to the candidate head
    /// with its flops unchanged, the replay starts; at another jump back, the candidate is
    /// the new place.
    #[inline(always)]
    pub fn observe(&mut self, cpu: &Cpu, pins: u64, out: u64, debug: Option<DebugWords>) {
        if self.head_pc.is_some() {
            if self.len == MAX_TRIP || out & INTERRUPT_ACK != 0 {
                self.head_pc = None;
            } else {
                self.pins[self.len] = pins;
                self.outs[self.len] = out;
                if let Some(words) = debug {
                    self.debug[self.len] = words;
                }
                self.len += 1;
            }
        }
        // An instruction boundary: the next cycle decodes the word at `pc`.
        if cpu.phase() != Phase::Decode {
            return;
        }
        let pc = cpu.pc();
        let back = pc <= self.last_pc;
        self.last_pc = pc;
        if !back {
            return;
        }
        if self.head_pc == Some(pc) && self.len > 0 && cpu.same_state_as(&self.head) {
            self.active = true;
            self.pos = 0;
            self.replayed = 0;
            return;
        }
        self.head.clone_from(cpu);
        self.head_pc = Some(pc);
        self.len = 0;
    }
}
