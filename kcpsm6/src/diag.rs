//! Diagnostics: one line each, `FILE:LINE:COL: error: message`.

use std::fmt;
use std::path::{Path, PathBuf};

/// The reason of an I/O error without Rust's "(os error N)" suffix.
pub fn io_reason(e: &std::io::Error) -> String {
    let s = e.to_string();
    match s.find(" (os error") {
        Some(i) => s[..i].to_lowercase(),
        None => s,
    }
}

/// A place in a source file (1-based line and column; 0 means "not known").
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Loc {
    pub file: PathBuf,
    pub line: usize,
    pub col: usize,
}

impl Loc {
    pub fn new(file: impl AsRef<Path>, line: usize, col: usize) -> Loc {
        Loc { file: file.as_ref().to_path_buf(), line, col }
    }

    /// A whole file (no line).
    pub fn file(file: impl AsRef<Path>) -> Loc {
        Loc::new(file, 0, 0)
    }
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if self.line > 0 {
            write!(f, ":{}", self.line)?;
            if self.col > 0 {
                write!(f, ":{}", self.col)?;
            }
        }
        Ok(())
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Severity {
    Warning,
    Error,
}

/// One message about an input.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub loc: Loc,
    pub message: String,
}

impl Diagnostic {
    pub fn error(loc: Loc, message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Error, loc, message: message.into() }
    }

    pub fn warning(loc: Loc, message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, loc, message: message.into() }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.severity {
            Severity::Warning => "warning",
            Severity::Error => "error",
        };
        write!(f, "{}: {kind}: {}", self.loc, self.message)
    }
}

/// All the errors of one run (at least one), plus the warnings seen before them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostics(pub Vec<Diagnostic>);

impl Diagnostics {
    pub fn single(d: Diagnostic) -> Diagnostics {
        Diagnostics(vec![d])
    }

    pub fn errors(&self) -> impl Iterator<Item = &Diagnostic> {
        self.0.iter().filter(|d| d.severity == Severity::Error)
    }

    /// The same without the warnings (for `--quiet`).
    pub fn without_warnings(&self) -> Diagnostics {
        Diagnostics(self.errors().cloned().collect())
    }

    /// The errors, a line each, and how many warnings came with them: what an error message
    /// of another tool quotes (the warnings are `botsim asm`'s to show).
    ///
    /// ```
    /// use kcpsm6::asm::assemble_str;
    /// let d = assemble_str("CONSTANT unused, 01\nCONSTANT other, 02\n  LOAD s0, nowhere\n").unwrap_err();
    /// let text = d.errors_text();
    /// assert!(text.contains("error:") && !text.contains("warning:"), "{text}");
    /// assert!(text.ends_with("(and 2 warnings)"), "{text}");
    /// ```
    pub fn errors_text(&self) -> String {
        let mut text: Vec<String> = self.errors().map(|d| d.to_string()).collect::<Vec<_>>();
        let warnings = self.0.len() - text.len();
        if warnings > 0 {
            let last = text.pop().unwrap_or_default();
            text.push(format!("{last} (and {warnings} warning{})", if warnings == 1 { "" } else { "s" }));
        }
        text.join("\n")
    }
}

impl fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostics {}
