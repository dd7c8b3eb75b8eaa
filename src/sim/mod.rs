//! Simulating the bot: everything of [`botsim_core::sim`] (the [`Backend`] trait, [`Error`],
//! the ISS backend [`iss::IssBot`]) plus what needs Verilator: the RTL backends ([`rtl`]) and
//! lock-step of the two ([`lockstep`]).

pub use botsim_core::sim::*;

pub mod lockstep;
pub mod rtl;
