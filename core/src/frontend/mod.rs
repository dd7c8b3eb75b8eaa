//! The repository front end: a team's files become a design plan, before anything is built.
//!
//! [`repo`] lists a repository as committed and [`project`] reads its Vivado or ISE project;
//! [`scan`] reads each Verilog file's modules, ports and instances; [`resolve`] finds the top
//! and one definition of every module it reaches, the IP from its configuration ([`ip`],
//! [`memcore`], [`coe_match`]), the course's modules ([`course`]), VHDL through GHDL
//! ([`vhdl`]), and edits what Vivado accepts and Verilator refuses ([`commas`], [`flops`]);
//! [`constraints`] and [`pins`] say what each top port is on the board ([`role`]);
//! [`drivers`] finds nets with several drivers; [`plan`] decides what botsim substitutes
//! ([`parts`]: its own modules and primitives) and [`wrapper`] writes the Verilog around the
//! design. [`locate`] maps Verilator's names back to the user's sources. The plan goes to
//! the board runtime (the `botsim` crate's `board`), which builds and runs it.
//!
//! ```
//! use botsim_core::frontend::scan::scan;
//! let m = &scan("module top(input clk, output [15:0] led);\n  assign led = 0;\nendmodule\n")[0];
//! assert_eq!((m.name.as_str(), m.ports.len()), ("top", 2));
//! ```

pub mod coe_match;
pub mod commas;
pub mod constraints;
pub mod course;
pub mod drivers;
pub mod flops;
pub mod ip;
pub mod locate;
pub mod memcore;
pub mod parts;
pub mod pins;
pub mod plan;
pub mod project;
pub mod repo;
pub mod resolve;
pub mod role;
pub mod scan;
pub mod source;
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
