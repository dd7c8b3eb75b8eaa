//! The board runtime, the half that needs Verilator: [`build`] turns a plan
//! (`botsim_core::frontend::plan`) into a shared library of the Verilated design with the C++
//! harness (cached), [`model`] loads it and runs it, [`lockstep`] runs two side by side,
//! [`iss`] stands the instruction-set simulator in for the design's KCPSM6s, [`waveform`]
//! marks what a run did not simulate. What the run may skip is [`crate::fastforward`]'s.

pub mod build;
pub mod explain;
pub mod iss;
pub mod lockstep;
pub mod model;
mod replay;
pub mod waveform;
