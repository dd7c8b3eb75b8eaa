//! BotSim 2.0 without Verilator: everything about the Rojobot that needs no Verilated model.
//! The `botsim` crate adds the RTL backends (Verilator), lock-step and the command line on top;
//! the KCPSM6 toolchain is the `kcpsm6` crate.
//!
//! | module | job |
//! |---|---|
//! | [`regs`] | typed registers: MotCtl, Orientation, Movement, Sensors, Snapshot |
//! | [`ports`] | the world_if port numbers, as `rtl/world_if.v` and `rtl/bot_pgm.psm` name them |
//! | [`world`] | the 128 x 128 world, its file formats and the built-in course |
//! | [`script`] | motor scripts |
//! | [`firmware`] | the BotSim firmware (`rtl/bot_pgm.psm`) and its assembly-time constants |
//! | [`golden`] | the golden behavioural model of the spec (no CPU, no firmware) |
//! | [`frontend`] | a team's repository to a design plan: scanning, resolving, IP, pins, the substitution plan |
//! | [`board`] | what the board shows and takes: the display, VGA frames, UART, keyboard, audio, stimuli |
//! | [`driver`] | closed-loop drivers: the motor script, the line follower |
//! | [`render`] | pictures: the path on the world, the course's 640 x 480 display |
//! | [`files`] | output files that are never half-written |
//! | [`sim`] | the [`sim::Backend`] trait, its errors, and the bot on the ISS ([`sim::iss`]) |
//!
//! ```
//! use botsim_core::golden::GoldenBot;
//! use botsim_core::{MotCtl, World};
//! let mut bot = GoldenBot::new(World::builtin(), 15, Default::default());
//! assert_eq!(bot.initial().loc_x, 64);
//! let after: Vec<_> = (0..16).map(|_| bot.step(MotCtl::FORWARD)).collect();
//! assert_eq!((after[15].loc_x, after[15].loc_y), (65, 64));
//! ```

pub mod board;
pub mod debug;
pub mod driver;
pub mod files;
pub mod firmware;
pub mod frontend;
pub mod golden;
mod picture;
pub mod ports;
pub mod regs;
pub mod render;
pub mod script;
pub mod sim;
pub mod world;

pub use firmware::{Compat, Firmware, Timing};

/// One cycle of the 100 MHz clock, in picoseconds: the board's oscillator, and the clock the
/// bot's program is calibrated for (botsim.md §11). Cycle counts (`5000000c`, a trace's
/// `cycle`) are in it.
pub const PS_PER_CYCLE: u64 = 10_000;
pub use kcpsm6;
pub use regs::{MotCtl, Movement, Orientation, Registers, Sensors, Snapshot};
pub use sim::{Backend, CpuAt, Error};
pub use world::{Cell, World};
