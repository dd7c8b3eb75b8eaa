//! Board simulation, the half that needs Verilator at run time: [`build`] turns a plan
//! (`botsim_core::board::plan`) into a shared library of the Verilated design with the C++
//! harness (cached), [`model`] loads it and runs it.

pub mod apart;
pub mod build;
pub mod checks;
pub mod counters;
mod counts;
pub mod cpp;
pub mod demand;
pub mod dialect;
pub mod explain;
pub mod iss;
pub mod lockstep;
pub mod model;
pub mod observed;
mod replay;
pub mod solo;
pub mod strobes;
pub mod waveform;

pub use botsim_core::board::*;
