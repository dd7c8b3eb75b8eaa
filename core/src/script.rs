//! Motor scripts: one segment per line, `<MOTCTL> <COUNT>`.
//!
//! MOTCTL is a byte as two hex digits (`33`) or `0x33`, or a named command (`forward`,
//! `reverse`, `stop`, `slow-left`, `slow-right`, `fast-left`, `fast-right`); COUNT is a decimal
//! number of main-loop iterations. `#` starts a comment; blank lines are ignored.
//! Segments cover iterations 1, 2, ... in order; the first segment's value is on MotCtl_in
//! from reset.
//!
//! ```
//! use botsim_core::script::MotorScript;
//! use botsim_core::MotCtl;
//! let s = MotorScript::parse("m.txt", "forward 2  # go\n0x30 1\n").unwrap();
//! assert_eq!(s.total(), 3);
//! assert_eq!(s.value_for(1), MotCtl::FORWARD);
//! assert_eq!(s.value_for(3), MotCtl(0x30));
//! assert_eq!(s.value_for(9), MotCtl(0x30)); // the last value is held
//! ```

use std::path::Path;

use kcpsm6::diag::{Diagnostic, Loc};

use crate::regs::MotCtl;

/// The most main-loop iterations a script may cover (about 1.7 years of `hw` time): counts
/// beyond it are typing errors, and totals stay far from overflow.
pub const MAX_ITERATIONS: u64 = 1_000_000_000;

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MotorScript {
    pub segments: Vec<(MotCtl, u64)>,
}

impl MotorScript {
    /// Read a script file.
    pub fn load(path: &Path) -> Result<MotorScript, Diagnostic> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            Diagnostic::error(Loc::file(path), format!("cannot read file: {}", kcpsm6::diag::io_reason(&e)))
        })?;
        MotorScript::parse(path, &text)
    }

    /// Parse script text; `path` names it in errors.
    pub fn parse(path: impl AsRef<Path>, text: &str) -> Result<MotorScript, Diagnostic> {
        let path = path.as_ref();
        let mut segments = Vec::new();
        let mut total = 0u64;
        for (i, line) in text.lines().enumerate() {
            let code = line.split('#').next().unwrap_or("");
            let mut words = Vec::new();
            let mut start = None;
            for (at, c) in code.char_indices().chain([(code.len(), ' ')]) {
                match (c.is_whitespace(), start) {
                    (false, None) => start = Some(at),
                    (true, Some(s)) => {
                        words.push((&code[s..at], code[..s].chars().count() + 1));
                        start = None;
                    }
                    _ => {}
                }
            }
            let at = |c| Loc::new(path, i + 1, c);
            match words[..] {
                [] => continue,
                [(m, mc), (n, nc)] => {
                    let motctl = m.parse::<MotCtl>().map_err(|e| Diagnostic::error(at(mc), e))?;
                    let count = n.parse::<u64>().map_err(|_| {
                        Diagnostic::error(at(nc), format!("'{n}' is not a count (a decimal number of iterations)"))
                    })?;
                    total += count.min(MAX_ITERATIONS + 1);
                    if total > MAX_ITERATIONS {
                        return Err(Diagnostic::error(
                            at(nc),
                            format!("the script covers more than {MAX_ITERATIONS} iterations"),
                        ));
                    }
                    segments.push((motctl, count));
                }
                [(_, c)] => {
                    return Err(Diagnostic::error(at(c), "expected '<MOTCTL> <COUNT>', e.g. 'forward 15' or '33 15'"))
                }
                [_, _, (w, c), ..] => {
                    return Err(Diagnostic::error(at(c), format!("unexpected '{w}' after the count")))
                }
            }
        }
        if segments.is_empty() {
            return Err(Diagnostic::error(Loc::file(path), "no segments (expected lines '<MOTCTL> <COUNT>')"));
        }
        Ok(MotorScript { segments })
    }

    /// The number of iterations the script covers.
    pub fn total(&self) -> u64 {
        self.segments.iter().map(|s| s.1).sum()
    }

    /// MotCtl for main-loop iteration `k` (1-based); the last value holds after the end.
    pub fn value_for(&self, k: u64) -> MotCtl {
        let mut end = 0;
        for &(m, n) in &self.segments {
            end += n;
            if k <= end {
                return m;
            }
        }
        self.segments.last().map_or(MotCtl::STOP, |s| s.0)
    }

    /// The value on MotCtl_in from reset (the first segment's, also when it has count 0).
    pub fn initial(&self) -> MotCtl {
        self.segments.first().map_or(MotCtl::STOP, |s| s.0)
    }
}
