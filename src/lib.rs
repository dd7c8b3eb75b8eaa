//! botsim: a cycle-exact RTL co-simulation of the Rojobot BotSim 2.0 (PSU ECE 540), driven
//! from Rust. The KCPSM6 toolchain lives in the `kcpsm6` crate, re-exported here.

pub mod cpu;
pub mod files;
mod rtl;

pub use kcpsm6;
