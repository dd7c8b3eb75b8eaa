//! A KCPSM6 run on its own, its reset, sleep and interrupt low, as fast as its firmware
//! allows: what a core apart from the board does over a skip (see [`super::apart`]), and how
//! far it stays quiet.
//!
//! Three things make it fast, each exact (the core ends as ticking it would leave it):
//! subroutines that only compute are applied from their first call's recording
//! ([`Routines`]); a loop whose trip only counts (a software delay, at any depth: an outer
//! trip reloads the inner counts) is moved on by whole trips as its proof says
//! ([`CountingPeriod`]); a loop that comes back to the same flops is counted by whole trips.
//! Loops are found where the program jumps back: the core at each such address is kept, and
//! the next visit is compared with it.
//!
//! ```
//! use botsim::fastforward::solo::Solo;
//! use kcpsm6::iss::{Config, Cpu, NullBus};
//! // A one-second delay as the KCPSM6 package writes it: three registers counted down.
//! let p = kcpsm6::asm::assemble_str(
//!     "LOAD s2, 5F\nLOAD s1, 5E\nLOAD s0, 10\nwait: SUB s0, 01\nSUBCY s1, 00\nSUBCY s2, 00\n\
//!      JUMP NC, wait\nOUTPUT s0, 01\nend: JUMP end\n",
//! )
//! .unwrap();
//! let mut cpu = Cpu::new(Config::default(), &p.image.words[..]);
//! let mut solo = Solo::default();
//! let access = solo.run(&mut cpu, u64::MAX / 2, &mut NullBus::default());
//! // Its OUTPUT, after 6.2 M trips of 8 cycles: found without simulating them.
//! assert!(access.is_some_and(|c| c > 50_000_000));
//! assert!(solo.skipped() > 49_000_000);
//! ```

use kcpsm6::counting::CountingPeriod;
use kcpsm6::iss::{Bus, Cpu, Phase, Pins, Routines};

/// How many loop heads are kept, and how many failed proofs at one head before it is left
/// alone (then for twice as many visits each time).
const HEADS: usize = 8;
const TRIES: u32 = 4;
/// The longest trip a proof is tried on: a proof re-runs its trip cycle by cycle, while a
/// longer trip's instructions are few when its inner loops are skipped or its calls applied
/// from their recordings (the outer loops of BotSim's delay, 4,250 and 106,260 cycles).
const LONGEST_TRIP: u64 = 2048;

/// A core's accelerators: the subroutines' recordings, kept from run to run (one pays at its
/// next call), and the loop heads of the run.
#[derive(Default)]
pub struct Solo {
    routines: Routines,
    heads: Vec<Head>,
    skipped: u64,
}

/// The core the last time it came back to `pc`.
struct Head {
    pc: u16,
    cpu: Cpu,
    /// Proofs that failed here, and visits to skip before the next.
    failed: u32,
    wait: u32,
}

/// A bus that notes the first port access and hands it on.
struct Watched<'a, B: Bus> {
    bus: &'a mut B,
    at: Option<u64>,
}

impl<B: Bus> Bus for Watched<'_, B> {
    fn input(&mut self, port: u8, cycle: u64) -> u8 {
        self.at.get_or_insert(cycle);
        self.bus.input(port, cycle)
    }
    fn output(&mut self, port: u8, value: u8, cycle: u64) {
        self.at.get_or_insert(cycle);
        self.bus.output(port, value, cycle)
    }
    fn output_k(&mut self, port: u8, value: u8, cycle: u64) {
        self.at.get_or_insert(cycle);
        self.bus.output_k(port, value, cycle)
    }
}

/// A loop found: the whole trips it may be moved on by.
enum Found {
    Counting(Box<CountingPeriod>),
    Same(u64),
}

impl Solo {
    /// The cycles moved on by loops' trips so far (not simulated; subroutines' calls applied
    /// aside).
    pub fn skipped(&self) -> u64 {
        self.skipped
    }

    /// Run `cpu` with its pins low to cycle `until`, or to the end of the instruction that
    /// first accesses a port: that access's strobe cycle.
    pub fn run<B: Bus>(&mut self, cpu: &mut Cpu, until: u64, bus: &mut B) -> Option<u64> {
        let mut bus = Watched { bus, at: None };
        // Heads of this run only: a period that held a port access (of a run before) is none.
        self.heads.clear();
        // (An instruction may end a cycle past its `until`: the last two are ticked.)
        let end = until.saturating_sub(2);
        while cpu.cycle() < end && bus.at.is_none() {
            let mut found = None;
            let mut last_pc = cpu.pc();
            let heads = &mut self.heads;
            cpu.run_watched(
                &mut bus,
                end,
                |b, c| {
                    if b.at.is_some() {
                        return true;
                    }
                    let pc = c.pc();
                    let back = c.phase() == Phase::Decode && pc <= last_pc;
                    last_pc = pc;
                    back && {
                        found = visit(heads, c);
                        found.is_some()
                    }
                },
                &mut self.routines,
            );
            let before = cpu.cycle();
            match found {
                // (Found by an instruction that may have ended past `end`.)
                Some(Found::Counting(p)) => {
                    let n = p.room().min(end.saturating_sub(cpu.cycle()) / p.cycles());
                    *cpu = p.state_after(n);
                }
                Some(Found::Same(trip)) => cpu.skip_period(end.saturating_sub(cpu.cycle()) / trip * trip),
                None => {}
            }
            self.skipped += cpu.cycle() - before;
            // The heads kept are of the core before the skip. (The calls being recorded go on:
            // the trips skipped write what the trip they repeat wrote.)
            self.heads.clear();
        }
        self.routines.interrupted();
        while cpu.cycle() < until && bus.at.is_none() {
            cpu.tick(Pins::default(), &mut bus);
        }
        bus.at
    }
}

/// The core `c` came back to its address: a loop to skip, or none (the head kept).
fn visit(heads: &mut Vec<Head>, c: &Cpu) -> Option<Found> {
    let pc = c.pc();
    let Some(i) = heads.iter().position(|h| h.pc == pc) else {
        if heads.len() == HEADS {
            heads.remove(0);
        }
        heads.push(Head { pc, cpu: c.clone(), failed: 0, wait: 0 });
        return None;
    };
    let h = &mut heads[i];
    if h.wait > 0 {
        h.wait -= 1;
        h.cpu = c.clone();
        return None;
    }
    if c.same_state_as(&h.cpu) {
        return Some(Found::Same(c.cycle() - h.cpu.cycle()));
    }
    if c.cycle() - h.cpu.cycle() > LONGEST_TRIP {
        h.cpu = c.clone();
        return None;
    }
    match CountingPeriod::find_alone(&h.cpu, c) {
        Ok(p) if p.room() > 0 => Some(Found::Counting(Box::new(p))),
        _ => {
            h.failed += 1;
            if h.failed >= TRIES {
                h.wait = 1 << (h.failed - TRIES).min(16);
            }
            h.cpu = c.clone();
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kcpsm6::iss::{Config, NullBus};

    /// Tick `cpu` with its pins low to `until` or its first access, as [`Solo::run`] says.
    fn ticked(cpu: &mut Cpu, until: u64) -> Option<u64> {
        let mut bus = Watched { bus: &mut NullBus::default(), at: None };
        while cpu.cycle() < until && bus.at.is_none() {
            cpu.tick(Pins::default(), &mut bus);
        }
        bus.at
    }

    #[test]
    fn a_run_on_its_own_ends_as_ticking_does() {
        // Nested delays in a subroutine and inline, a count in the scratch pad, an idle loop.
        let p = kcpsm6::asm::assemble_str(
            "main: CALL wait\nADD s9, 01\nCOMPARE s9, 03\nJUMP NZ, main\n\
             LOAD s0, 30\nSTORE s0, 10\nspad: FETCH s0, 10\nSUB s0, 01\nSTORE s0, 10\nJUMP NZ, spad\n\
             OUTPUT s9, 05\nidle: ADD sA, 00\nJUMP idle\n\
             wait: LOAD s4, 03\nw3: LOAD s5, 07\nw2: LOAD s6, 0B\nw1: LOAD s7, 28\nw0: SUB s7, 01\nJUMP NZ, w0\n\
             SUB s6, 01\nJUMP NZ, w1\nSUB s5, 01\nJUMP NZ, w2\nSUB s4, 01\nJUMP NZ, w3\nRETURN\n",
        )
        .unwrap();
        let start = Cpu::new(Config::default(), &p.image.words[..]);
        let mut solo = Solo::default();
        let mut fast = start.clone();
        let access = solo.run(&mut fast, u64::MAX / 2, &mut NullBus::default()).unwrap();
        // The delays' outer loops and the scratch pad's count were skipped, not simulated (the
        // second and third calls of `wait` applied from the first's recording).
        assert!(solo.skipped() > access / 3, "{} of {access}", solo.skipped());
        let mut slow = start.clone();
        assert_eq!(ticked(&mut slow, u64::MAX / 2), Some(access));
        assert!(fast == slow, "at the access");
        // Any cycle on: the same as ticking there (the idle loop counted by whole trips; a
        // loop found by an instruction that ends past `until`).
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        let untils = (0..60).map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % (access + 2_000_000)
        });
        for until in untils.chain([5_000, 123_457, access - 3, access + 1_000_003]) {
            let (mut fast, mut slow) = (start.clone(), start.clone());
            let mut solo = Solo::default();
            let a = solo.run(&mut fast, until, &mut NullBus::default());
            assert_eq!(a, ticked(&mut slow, until), "{until}");
            if a.is_none() {
                assert!(fast == slow && fast.cycle() == until, "{until}");
            }
        }
        // After the access, to a far cycle: the idle loop.
        let (mut fast, mut slow) = (start.clone(), start.clone());
        solo.run(&mut fast, access + 1, &mut NullBus::default());
        ticked(&mut slow, access + 1);
        assert_eq!(solo.run(&mut fast, access + 9_000_001, &mut NullBus::default()), None);
        ticked(&mut slow, access + 9_000_001);
        assert!(fast == slow);
    }

    #[test]
    fn a_loop_found_by_the_instruction_that_ends_the_run_lands_where_ticking_does() {
        // BotSim's shape: a counted loop calling an inner delay. Every cycle of a stretch of
        // the loop as the end: some end with the instruction that finds the loop's period.
        let p = kcpsm6::asm::assemble_str(
            "main: CALL wait\nOUTPUT s0, 01\nJUMP main\nADDRESS 100\nwait: LOAD s1, 28\nloop: CALL inner\n\
             SUB s1, 01\nJUMP NZ, loop\nRETURN\ninner: LOAD s0, 18\nspin: SUB s0, 01\nJUMP NZ, spin\nRETURN\n",
        )
        .unwrap();
        let start = Cpu::new(Config::default(), &p.image.words[..]);
        let mut slow = start.clone();
        let mut calls = 0;
        while calls < 3 {
            slow.tick(Pins::default(), &mut NullBus::default());
            calls += (slow.pc() == 0x105 && slow.phase() == Phase::Decode) as u32;
        }
        let from = slow.cycle();
        for until in from..from + 250 {
            ticked(&mut slow, until);
            let mut fast = start.clone();
            assert_eq!(Solo::default().run(&mut fast, until, &mut NullBus::default()), None);
            assert!(fast == slow, "{until}: fast at {} (pc {:03X})", fast.cycle(), fast.pc());
        }
    }
}
