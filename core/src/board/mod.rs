//! Board simulation, the Verilator-free half: a student's Nexys4 design read from its
//! sources ([`scan`]), the plan of what botsim substitutes ([`plan`]), the board's pins
//! ([`pins`]), the generated Verilog around it ([`wrapper`]), and what the board shows
//! ([`display`]: the seven-segment display as a person sees it; [`vga`]: frames from the VGA pins). The `botsim` crate builds
//! and runs the plan (`botsim::board`).

pub mod audio;
pub mod coe_match;
pub mod commas;
pub mod constraints;
pub mod course;
pub mod display;
pub mod drivers;
pub mod flops;
pub mod gtkw;
pub mod ip;
pub mod keyboard;
pub mod locate;
pub mod memcore;
pub mod parts;
pub mod pins;
pub mod plan;
pub mod project;
pub mod random_stimulus;
pub mod repo;
pub mod resolve;
pub mod role;
pub mod scan;
pub mod source;
pub mod stimulus;
pub mod uart;
pub mod vga;
pub mod vhdl;
pub mod wrapper;

use std::fmt;
use std::path::Path;

/// One error of board planning: the user's file:line:col when there is one, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BoardError {
    pub location: Option<String>,
    pub message: String,
}

impl BoardError {
    /// An error at `path:line:col` (line 0: the file itself).
    pub fn at(path: &Path, line: u32, col: u32, message: impl Into<String>) -> BoardError {
        let location = match (line, col) {
            (0, _) => path.display().to_string(),
            (l, 0) => format!("{}:{l}", path.display()),
            (l, c) => format!("{}:{l}:{c}", path.display()),
        };
        BoardError { location: Some(location), message: message.into() }
    }

    /// An error with no location.
    pub fn plain(message: impl Into<String>) -> BoardError {
        BoardError { location: None, message: message.into() }
    }
}

impl fmt::Display for BoardError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.location {
            Some(l) => write!(f, "{l}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for BoardError {}
