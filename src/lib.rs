//! botsim: a cycle-exact RTL co-simulation of the Rojobot BotSim 2.0 (PSU ECE 540), driven
//! from Rust. The KCPSM6 toolchain lives in the `kcpsm6` crate.

pub mod files;

pub use kcpsm6;
