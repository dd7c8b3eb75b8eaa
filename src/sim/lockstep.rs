//! The RTL and the ISS backend side by side on the same program, world and motor commands:
//! every upd_sysregs snapshot and every port access (kind, port, data and cycle) must agree.
//! A difference stops the run with both sides of the first one.
//!
//! ```
//! use botsim::sim::lockstep::Lockstep;
//! use botsim::{Firmware, MotCtl, Timing, World};
//! let fw = Firmware { timing: Timing::Fast, ..Firmware::default() };
//! let mut both = Lockstep::new(&fw.assemble().unwrap(), World::builtin()).unwrap();
//! both.wait_update().unwrap();
//! both.set_motors(MotCtl::FORWARD);
//! for _ in 0..16 {
//!     both.wait_update().unwrap();
//! }
//! assert!(both.events_compared() > 16 * 20); // about 25 accesses per main-loop iteration
//! ```

use kcpsm6::Image;

use super::iss::IssBot;
use super::rtl::RtlBot;
use super::{Backend, CpuAt, Error, PortEvent};
use crate::regs::{MotCtl, Snapshot};
use crate::world::World;

/// Both backends, stepped together.
pub struct Lockstep {
    rtl: RtlBot,
    iss: IssBot,
    compared: u64,
    /// Accesses not compared yet.
    rtl_events: Vec<PortEvent>,
    iss_events: Vec<PortEvent>,
}

/// How the two backends differed, or why the run stopped.
#[derive(Debug, thiserror::Error)]
pub enum Mismatch {
    #[error("port access {index} differs: RTL {rtl}, ISS {iss}")]
    Port { index: u64, rtl: String, iss: String },
    #[error("snapshots differ: RTL {rtl:?}, ISS {iss:?}")]
    Snapshot { rtl: Box<Snapshot>, iss: Box<Snapshot> },
    #[error("RTL: {0}")]
    Rtl(Error),
    #[error("ISS: {0}")]
    Iss(Error),
}

impl Lockstep {
    /// Both backends with `program` in `world`, at configuration.
    pub fn new(program: &Image, world: World) -> Result<Lockstep, Error> {
        let rtl = RtlBot::builder().program(program.clone()).world(world.clone()).build()?;
        Ok(Lockstep::pair(rtl, IssBot::new(program, world)?))
    }

    /// Two backends built separately (say, with a firmware or world of your own each); the
    /// RTL's update budget is the pair's.
    pub fn pair(rtl: RtlBot, mut iss: IssBot) -> Lockstep {
        iss.record_ports(true);
        Lockstep { rtl, iss, compared: 0, rtl_events: Vec::new(), iss_events: Vec::new() }
    }

    /// MotCtl_in of both, from the next cycle on.
    pub fn set_motors(&mut self, m: MotCtl) {
        self.rtl.set_motors(m);
        self.iss.set_motors(m);
    }

    /// Port accesses compared so far.
    pub fn events_compared(&self) -> u64 {
        self.compared
    }

    /// The next snapshot of both, after comparing every port access on the way.
    pub fn wait_update(&mut self) -> Result<Snapshot, Mismatch> {
        self.wait_update_within(self.rtl.update_budget())
    }

    /// As [`Lockstep::wait_update`], within `budget` cycles.
    pub fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Mismatch> {
        let mut rtl = self.rtl.wait_update_recording_within(budget, &mut self.rtl_events);
        let iss = self.iss.wait_update_within(budget);
        // The ISS runs whole instructions and may pass the budget by a cycle or two: when that
        // found the pulse, give the RTL the same reach.
        if let (Err(Error::Timeout { .. }), Ok(s)) = (&rtl, &iss) {
            let reach = (s.cycle + 1).saturating_sub(self.rtl.cycle());
            rtl = self.rtl.wait_update_recording_within(reach, &mut self.rtl_events);
        }
        self.compare()?;
        match (rtl, iss) {
            (Ok(a), Ok(b)) if a == b => Ok(a),
            (Ok(a), Ok(b)) => Err(Mismatch::Snapshot { rtl: Box::new(a), iss: Box::new(b) }),
            (Err(e), _) => Err(Mismatch::Rtl(e)),
            (_, Err(e)) => Err(Mismatch::Iss(e)),
        }
    }

    /// Run both for `cycles` cycles (pulses are not samples), comparing every port access.
    pub fn run(&mut self, cycles: u64) -> Result<(), Mismatch> {
        self.rtl.run_recording(cycles, &mut self.rtl_events).map_err(Mismatch::Rtl)?;
        self.iss.run(cycles);
        self.compare()
    }

    /// Compare the accesses both sides made up to the cycle both have reached (one side may
    /// have run a cycle further: its later accesses wait for the next comparison).
    fn compare(&mut self) -> Result<(), Mismatch> {
        self.iss_events.extend(self.iss.take_events());
        let upto = self.rtl.cycle().min(self.iss.cycle());
        let n_rtl = self.rtl_events.iter().take_while(|e| e.cycle < upto).count();
        let n_iss = self.iss_events.iter().take_while(|e| e.cycle < upto).count();
        for i in 0..n_rtl.max(n_iss) {
            let (a, b) = (self.rtl_events[..n_rtl].get(i), self.iss_events[..n_iss].get(i));
            if a != b {
                let show = |e: Option<&PortEvent>| e.map_or("nothing".to_string(), |e| e.to_string());
                return Err(Mismatch::Port { index: self.compared + i as u64, rtl: show(a), iss: show(b) });
            }
        }
        self.rtl_events.drain(..n_rtl);
        self.iss_events.drain(..n_iss);
        self.compared += n_rtl as u64;
        Ok(())
    }
}

impl Backend for Lockstep {
    /// The common snapshot; a difference is [`Error::Mismatch`] with its description.
    fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error> {
        Lockstep::wait_update_within(self, budget).map_err(|m| match m {
            Mismatch::Rtl(e) | Mismatch::Iss(e) => e,
            m => Error::Mismatch(m.to_string()),
        })
    }
    fn update_budget(&self) -> u64 {
        self.rtl.update_budget()
    }
    fn set_update_budget(&mut self, cycles: u64) {
        Backend::set_update_budget(&mut self.rtl, cycles);
        Backend::set_update_budget(&mut self.iss, cycles);
    }
    fn set_motors(&mut self, m: MotCtl) {
        Lockstep::set_motors(self, m)
    }
    fn cycle(&self) -> u64 {
        self.rtl.cycle()
    }
    fn cpu_at(&self) -> CpuAt {
        self.rtl.cpu_at()
    }
}
