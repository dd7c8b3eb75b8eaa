//! Simulating the bot: what every backend offers ([`Backend`]), the one [`Error`] they report,
//! and the instruction-set-simulator backend ([`iss::IssBot`]). The Verilator backends and
//! lock-step live in the `botsim` crate, beside their FFI; drivers and scenarios written
//! against [`Backend`] run on any of them.
//!
//! ```
//! use botsim_core::sim::{iss::IssBot, Backend};
//! use botsim_core::{Firmware, MotCtl, Timing, World};
//!
//! /// Drive forward for 16 samples; where does the bot end up?
//! fn forward(bot: &mut dyn Backend) -> (u8, u8) {
//!     bot.wait_update().unwrap();
//!     bot.set_motors(MotCtl::FORWARD);
//!     (0..16).map(|_| bot.wait_update().unwrap()).last().unwrap().location()
//! }
//! let fw = Firmware { timing: Timing::Fast, ..Firmware::default() };
//! let mut iss = IssBot::new(&fw.assemble().unwrap(), World::builtin()).unwrap();
//! iss.set_update_budget(Timing::Fast.update_budget());
//! assert_eq!(forward(&mut iss), (65, 64));
//! ```

pub mod iss;

use kcpsm6::Diagnostics;

pub use kcpsm6::iss::{PortEvent, PortKind};

use crate::regs::{MotCtl, Snapshot};

/// The words of bot_pgm, a 1K ROM (000-3FF).
pub const BOT_ROM_WORDS: usize = 1024;

/// What went wrong in a simulation.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A wait ran out of its cycle budget: a firmware stuck in a loop, held in reset, or a
    /// budget too small for its timing.
    #[error("no {waited_for} within {budget} cycles (stopped at cycle {cycle}, {cpu})")]
    Timeout { waited_for: &'static str, budget: u64, cycle: u64, cpu: CpuAt },
    #[error("the model has finished ($finish) and cannot run further")]
    Finished,
    /// The waveform could not be written (a full disk, say); the model stopped.
    #[error("cannot write the waveform: {0}")]
    Waveform(String),
    /// Two backends disagreed in a lock-step run.
    #[error("lock-step mismatch: {0}")]
    Mismatch(String),
    /// Another fatal runtime error stopped the model.
    #[error("the simulation stopped: {0}")]
    Stopped(String),
    #[error("{0}")]
    Program(Diagnostics),
    #[error("the program uses address {0:03X}; bot_pgm is a 1K ROM (000-3FF)")]
    ProgramTooLarge(usize),
    #[error("{0}")]
    Io(String),
}

impl Error {
    /// No upd_sysregs pulse within `budget` cycles: the one way every backend says so.
    pub fn no_update(budget: u64, cycle: u64, cpu: CpuAt) -> Error {
        Error::Timeout { waited_for: "upd_sysregs pulse", budget, cycle, cpu }
    }
}

/// Refuse a program that does not fit bot_pgm's 1K ROM.
pub fn check_program_size(words: &[u32]) -> Result<(), Error> {
    match words.iter().rposition(|&w| w != 0) {
        Some(last) if last >= BOT_ROM_WORDS => Err(Error::ProgramTooLarge(last)),
        _ => Ok(()),
    }
}

/// Where the CPU was when a wait gave up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CpuAt {
    /// Running; the program counter.
    Address(u16),
    /// Held in reset (the reset pin, or the internal reset that follows it).
    Reset,
}

impl std::fmt::Display for CpuAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CpuAt::Address(a) => write!(f, "the CPU at address {a:03X}"),
            CpuAt::Reset => f.write_str("the CPU held in reset"),
        }
    }
}

/// A simulated BotSim 2.0, whatever runs it.
pub trait Backend {
    /// Run to the next upd_sysregs pulse within `budget` cycles; stop at the start of the
    /// pulse's first cycle.
    fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error>;
    /// The budget of [`Backend::wait_update`] (by default [`crate::Timing::update_budget`] of
    /// the firmware's timing, `hw` for a program of the user's).
    fn update_budget(&self) -> u64;
    /// Change the budget of [`Backend::wait_update`].
    fn set_update_budget(&mut self, cycles: u64);
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
