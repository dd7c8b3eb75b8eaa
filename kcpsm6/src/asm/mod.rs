//! The KCPSM6 assembler (kcpsm6.exe v2.70 syntax, spec §4), one module per pass:
//!
//! | pass | module | what |
//! |---|---|---|
//! | 1 | [`load`](self) | read the file and every `INCLUDE` (relative to the including file; `\` or `/`), lex each line ([`lexer`]) |
//! | 2 | `symbols` | the global names: predefined, `CONSTANT`, `STRING`, `TABLE`, caller overrides (`-D`) |
//! | 3 | `layout` | in order: addresses, labels, `ADDRESS`, `NAMEREG` (sequential), operands parsed with the register names valid on the line (`operands`) |
//! | 4 | `encode` | resolve constants and labels, emit the words and the listing |
//!
//! Every error of a run is reported, each as `FILE:LINE:COL: error: message`, in source order;
//! an INCLUDE that cannot be read stops the run after pass 1.
//!
//! ```
//! use kcpsm6::asm::{assemble_str, Options};
//! let p = assemble_str("CONSTANT port, 07\nstart: OUTPUT s0, port\nJUMP start\n").unwrap();
//! assert_eq!(&p.image.words[..2], &[0x2D007, 0x22000]);
//!
//! let err = assemble_str("LOAD s0, 7\nJUMP nowhere\n").unwrap_err();
//! assert_eq!(err.to_string(),
//!     "<input>:1:10: error: hex value '7' must have exactly 2 digits\n\
//!      <input>:2:6: error: undefined label 'nowhere'");
//! ```

mod encode;
mod layout;
pub mod lexer;
mod load;
mod names;
mod number;
mod operands;
mod symbols;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::diag::{io_reason, Diagnostic, Diagnostics, Loc, Severity};
use crate::image::Image;
use crate::isa::Instr;

pub use operands::literal8;

/// The version string KCPSM6 puts in `KCPSM6_version$`.
pub const KCPSM6_VERSION: &str = "v2.70";

/// A program memory size, for the size check (`-c` in kcpsm6.exe).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RomSize {
    K1,
    K2,
    K4,
}

impl RomSize {
    pub fn words(self) -> usize {
        match self {
            RomSize::K1 => 1024,
            RomSize::K2 => 2048,
            RomSize::K4 => 4096,
        }
    }

    /// The smallest size that holds `last` (the last occupied address).
    pub fn nominal(last: u16) -> RomSize {
        match last {
            0..=0x3FF => RomSize::K1,
            0x400..=0x7FF => RomSize::K2,
            _ => RomSize::K4,
        }
    }

    /// Parse `1K`, `2K`, `4K` (or 1024, 2048, 4096).
    pub fn parse(s: &str) -> Option<RomSize> {
        match s.to_ascii_uppercase().as_str() {
            "1K" | "1024" => Some(RomSize::K1),
            "2K" | "2048" => Some(RomSize::K2),
            "4K" | "4096" => Some(RomSize::K4),
            _ => None,
        }
    }
}

/// Caller choices for one assembly.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Constants defined or overridden by the caller (`-D NAME=VALUE`); a value is written as in
    /// a CONSTANT directive (`0F`, `15'd`, `00001111'b`, `"A"`).
    pub defines: Vec<(String, String)>,
    /// Environment for `%PSM_name` values; the CLI passes the process environment.
    pub env: Vec<(String, String)>,
    /// Refuse a program that does not fit this ROM size.
    pub rom_size: Option<RomSize>,
    /// Seconds since 1970 for the predefined time and date stamps (0 if not given).
    pub timestamp: u64,
}

/// What a name stands for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SymbolValue {
    Constant(u8),
    Label(u16),
    String(Vec<u8>),
    Table(Vec<u8>),
}

/// A defined name, for the listing's symbol tables.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symbol {
    pub name: String,
    pub value: SymbolValue,
    /// Where it was defined (`None` for predefined names and caller defines).
    pub loc: Option<Loc>,
    pub used: bool,
}

/// One line of the assembly listing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Listed {
    pub loc: Loc,
    pub address: Option<u16>,
    pub word: Option<u32>,
    pub label: Option<String>,
    /// The statement re-written in canonical form with names annotated, e.g. `JUMP 022[loop]`.
    pub text: String,
    pub comment: Option<String>,
}

/// An assembled program.
#[derive(Clone, Debug)]
pub struct Program {
    pub image: Image,
    /// The address of every occupied location, ascending.
    pub occupied: Vec<u16>,
    pub listing: Vec<Listed>,
    /// All names (predefined first), in definition order.
    pub symbols: Vec<Symbol>,
    pub files: Vec<PathBuf>,
    pub warnings: Vec<Diagnostic>,
    pub default_jump: Option<u16>,
    pub timestamp: u64,
}

impl Program {
    /// The last occupied address, if any.
    pub fn last_address(&self) -> Option<u16> {
        self.occupied.last().copied()
    }

    /// The value of a constant or label.
    pub fn symbol(&self, name: &str) -> Option<&SymbolValue> {
        self.symbols.iter().find(|s| s.name == name).map(|s| &s.value)
    }
}

/// Assemble a file (and its INCLUDEs).
pub fn assemble_file(path: &Path, opts: &Options) -> Result<Program, Diagnostics> {
    let text = std::fs::read(path).map_err(|e| {
        Diagnostics::single(Diagnostic::error(Loc::file(path), format!("cannot read file: {}", io_reason(&e))))
    })?;
    let text = decode_text(path, &text).map_err(Diagnostics::single)?;
    assemble_source(path, &text, opts)
}

/// Assemble source text held in memory; INCLUDE paths are relative to `path`'s directory.
pub fn assemble_source(path: &Path, text: &str, opts: &Options) -> Result<Program, Diagnostics> {
    Assembler::new(opts).run(path, text)
}

/// Assemble a string named `<input>` with default options.
pub fn assemble_str(text: &str) -> Result<Program, Diagnostics> {
    assemble_source(Path::new("<input>"), text, &Options::default())
}

/// Source files are ASCII; accept UTF-8 and Latin-1 (old Windows editors) rather than refuse.
fn decode_text(path: &Path, bytes: &[u8]) -> Result<String, Diagnostic> {
    if bytes.contains(&0) {
        return Err(Diagnostic::error(Loc::file(path), "not a text file (contains NUL bytes)"));
    }
    Ok(match std::str::from_utf8(bytes) {
        Ok(s) => s.to_string(),
        Err(_) => bytes.iter().map(|&b| b as char).collect(),
    })
}

struct SrcLine {
    loc: Loc,
    /// Position in assembly order, to sort diagnostics.
    seq: usize,
    line: lexer::Line,
}

struct Assembler<'a> {
    opts: &'a Options,
    diags: Vec<(usize, Diagnostic)>,
    /// An INCLUDE could not be read: the program is incomplete, so nothing after loading is
    /// checked (its undefined names would only bury the reason).
    include_failed: bool,
    lines: Vec<SrcLine>,
    files: Vec<PathBuf>,
    symbols: Vec<Symbol>,
    index: HashMap<String, usize>,
}

impl<'a> Assembler<'a> {
    fn new(opts: &'a Options) -> Assembler<'a> {
        Assembler {
            opts,
            diags: vec![],
            include_failed: false,
            lines: vec![],
            files: vec![],
            symbols: vec![],
            index: HashMap::new(),
        }
    }

    fn error(&mut self, seq: usize, loc: Loc, msg: impl Into<String>) {
        self.diags.push((seq, Diagnostic::error(loc, msg)));
    }

    fn err_at(&mut self, src: usize, col: usize, msg: impl Into<String>) {
        let loc = Loc { col, ..self.lines[src].loc.clone() };
        let seq = self.lines[src].seq;
        self.error(seq, loc, msg);
    }

    fn warn_at(&mut self, src: usize, col: usize, msg: impl Into<String>) {
        let loc = Loc { col, ..self.lines[src].loc.clone() };
        let seq = self.lines[src].seq;
        self.diags.push((seq, Diagnostic::warning(loc, msg)));
    }

    fn run(mut self, path: &Path, text: &str) -> Result<Program, Diagnostics> {
        self.load(path, text, &mut vec![]);
        if self.include_failed {
            self.diags.sort_by_key(|(seq, d)| (*seq, d.loc.col));
            return Err(Diagnostics(self.diags.into_iter().map(|(_, d)| d).collect()));
        }
        self.predefine();
        self.define();
        let layout = self.lay_out();
        let encoded = self.encode(&layout);
        let default_jump = layout.default_jump.and_then(|(a, src)| self.resolve_addr(&a, src));
        self.warn_unused();

        self.diags.sort_by_key(|(seq, d)| (*seq, d.loc.col));
        let has_error = self.diags.iter().any(|(_, d)| d.severity == Severity::Error);
        let diags: Vec<Diagnostic> = self.diags.into_iter().map(|(_, d)| d).collect();
        if has_error {
            return Err(Diagnostics(diags));
        }
        let mut image = encoded.image;
        if let Some(t) = default_jump {
            // Every unused location holds JUMP target.
            let jump = Instr::Jump(None, t).encode();
            let mut used = vec![false; image.words.len()];
            for &a in &encoded.occupied {
                used[a as usize] = true;
            }
            for (w, _) in image.words.iter_mut().zip(&used).filter(|(_, &u)| !u) {
                *w = jump;
            }
        }
        Ok(Program {
            image,
            occupied: encoded.occupied,
            listing: encoded.listing,
            symbols: self.symbols,
            files: self.files,
            warnings: diags,
            default_jump,
            timestamp: self.opts.timestamp,
        })
    }
}
