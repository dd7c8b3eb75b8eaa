//! botsim: a cycle-exact RTL co-simulation of the Rojobot BotSim 2.0 (PSU ECE 540), driven
//! from Rust. The KCPSM6 toolchain lives in the `kcpsm6` crate, re-exported here.
//!
//! | module | job |
//! |---|---|
//! | [`botsim`] | the testbench API: build, reset, motors, wait for updates, video port |
//! | [`regs`] | typed registers: MotCtl, Orientation, Movement, Sensors, Snapshot |
//! | [`world`] | the 128 x 128 world and its file formats; the built-in course |
//! | [`model`] | the golden behavioural model of the spec |
//! | [`firmware`] | the BotSim firmware and its assembly-time constants |
//! | [`cpu`] | the KCPSM6 RTL core in a test harness (lock-step DUT) |
//! | [`iss_backend`] | the same bot on the ISS, with cycle-timed Rust models of world_if and map |
//! | [`backend`] | the [`backend::Backend`] trait all of them implement; port events |
//! | [`lockstep`] | RTL and ISS side by side, every snapshot and port event compared |

pub mod backend;
pub mod botsim;
pub mod cpu;
pub mod driver;
pub mod files;
pub mod firmware;
pub mod iss_backend;
pub mod lockstep;
pub mod model;
mod picture;
pub mod regs;
pub mod render;
mod rtl;
pub mod script;
pub mod world;

pub use crate::botsim::{BotSim, CpuAt, Error};
pub use firmware::{Compat, Firmware, Timing};
pub use kcpsm6;
pub use regs::{MotCtl, Movement, Orientation, Registers, Sensors, Snapshot};
pub use world::{Cell, World};
