//! What every way of simulating the bot offers: the RTL under Verilator ([`BotSim`]), the
//! instruction-set simulator with cycle-timed models ([`IssBot`]), and both in lock-step
//! ([`Lockstep`](crate::lockstep::Lockstep)). Drivers and scenarios written against
//! [`Backend`] run on any of them.
//!
//! ```
//! use botsim::backend::Backend;
//! use botsim::iss_backend::IssBot;
//! use botsim::{BotSim, Firmware, MotCtl, Timing, World};
//!
//! /// Drive forward for 16 samples; where does the bot end up?
//! fn forward(bot: &mut dyn Backend) -> (u8, u8) {
//!     bot.wait_update().unwrap();
//!     bot.set_motors(MotCtl::FORWARD);
//!     (0..16).map(|_| bot.wait_update().unwrap()).last().unwrap().location()
//! }
//! let fw = Firmware { timing: Timing::Fast, ..Firmware::default() };
//! let mut rtl = BotSim::builder().firmware(fw).build().unwrap();
//! let mut iss = IssBot::new(&fw.assemble().unwrap(), World::builtin());
//! assert_eq!(forward(&mut rtl), (65, 64));
//! assert_eq!(forward(&mut iss), (65, 64));
//! ```

use crate::botsim::{BotSim, CpuAt, Error};
use crate::iss_backend::IssBot;
use crate::regs::{MotCtl, Snapshot};

/// How the CPU used the port bus.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PortAccess {
    /// INPUT: `read_strobe`; the value is `in_port`.
    Read,
    /// OUTPUT: `write_strobe`; the value is `out_port`.
    Write,
    /// OUTPUTK: `k_write_strobe`; the value is `out_port`.
    WriteK,
}

/// One port access: the cycle its strobe is high, `port_id`, and the data on the bus.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PortEvent {
    pub cycle: u64,
    pub access: PortAccess,
    pub port: u8,
    pub value: u8,
}

impl std::fmt::Display for PortEvent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = match self.access {
            PortAccess::Read => "INPUT",
            PortAccess::Write => "OUTPUT",
            PortAccess::WriteK => "OUTPUTK",
        };
        write!(f, "cycle {}: {what} port {:02X} value {:02X}", self.cycle, self.port, self.value)
    }
}

/// A simulated BotSim 2.0, whatever runs it.
pub trait Backend {
    /// Run to the next upd_sysregs pulse within `budget` cycles; stop at the start of the
    /// pulse's first cycle.
    fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error>;
    /// The budget of [`Backend::wait_update`]: two `hw` sample periods unless set otherwise.
    fn update_budget(&self) -> u64;
    /// MotCtl_in from the next cycle on.
    fn set_motors(&mut self, m: MotCtl);
    /// The next cycle to simulate.
    fn cycle(&self) -> u64;
    /// Where the CPU is now.
    fn cpu_at(&self) -> CpuAt;
    /// Run to the next upd_sysregs pulse within the backend's cycle budget.
    fn wait_update(&mut self) -> Result<Snapshot, Error> {
        self.wait_update_within(self.update_budget())
    }
}

impl Backend for BotSim {
    fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error> {
        BotSim::wait_update_within(self, budget)
    }
    fn update_budget(&self) -> u64 {
        BotSim::update_budget(self)
    }
    fn set_motors(&mut self, m: MotCtl) {
        BotSim::set_motors(self, m)
    }
    fn cycle(&self) -> u64 {
        BotSim::cycle(self)
    }
    fn cpu_at(&self) -> CpuAt {
        BotSim::cpu_at(self)
    }
}

/// The ISS backend waits at most this many cycles for a pulse: two `hw` sample periods.
pub const ISS_UPDATE_BUDGET: u64 = 2 * 5_314_000 + 10_000;

impl Backend for IssBot {
    fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error> {
        IssBot::wait_update(self, budget)
    }
    fn update_budget(&self) -> u64 {
        ISS_UPDATE_BUDGET
    }
    fn set_motors(&mut self, m: MotCtl) {
        IssBot::set_motors(self, m)
    }
    fn cycle(&self) -> u64 {
        IssBot::cycle(self)
    }
    fn cpu_at(&self) -> CpuAt {
        IssBot::cpu_at(self)
    }
}
