//! botsim: a cycle-exact RTL co-simulation of the Rojobot BotSim 2.0 (PSU ECE 540), driven
//! from Rust. This crate adds what needs Verilator to [`botsim_core`] (re-exported here, so
//! `botsim::world::World` and `botsim_core::world::World` are the same): the RTL backends and
//! their FFI ([`sim::rtl`]), lock-step of RTL and ISS ([`sim::lockstep`]), and the `botsim`
//! command line. The KCPSM6 toolchain is the [`kcpsm6`] crate.
//!
//! | module | job |
//! |---|---|
//! | [`sim`] | the [`Backend`] trait, [`Error`]; the RTL backends ([`sim::rtl`]), the ISS backend ([`sim::iss`]), lock-step ([`sim::lockstep`]) |
//! | [`regs`], [`world`], [`script`], [`firmware`], [`golden`], [`driver`], [`render`], [`ports`], [`files`] | from [`botsim_core`] |
//!
//! ```
//! use botsim::{MotCtl, Orientation, RtlBot, Timing};
//! let mut bot = RtlBot::builder().timing(Timing::Fast).build().unwrap();
//! let first = bot.wait_update().unwrap(); // sample 0: the register dump after start-up
//! assert_eq!((first.location(), first.orientation()), ((64, 64), Orientation::East));
//! ```

pub use botsim_core::{driver, files, firmware, golden, kcpsm6, ports, regs, render, script, world};
pub use botsim_core::{
    Cell, Compat, Firmware, MotCtl, Movement, Orientation, Registers, Sensors, Snapshot, Timing, World, PS_PER_CYCLE,
};

pub mod board;
pub mod fastforward;
pub mod interrupt;
pub mod sim;

pub use sim::iss::IssBot;
pub use sim::rtl::RtlBot;
pub use sim::{Backend, CpuAt, Error};
