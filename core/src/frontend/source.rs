//! A Verilog source of a design: its path, its text and its modules, and what of it the build
//! leaves out.

use std::ops::Range;
use std::path::{Path, PathBuf};

use super::scan::{self, Module};
use super::BoardError;

/// A source file, scanned.
#[derive(Clone, Debug)]
pub struct Source {
    pub path: PathBuf,
    pub text: String,
    /// The modules the build compiles from it.
    pub modules: Vec<Module>,
    /// Parts of the text the build blanks out (modules the design does not reach, other
    /// copies of a module), lines kept so that messages keep the file's line numbers.
    pub dropped: Vec<Range<usize>>,
    /// The text is not the file's as it is on disk: botsim generated it (a core from its
    /// configuration, a stand-in) or rewrote a construct in it.
    pub edited: bool,
    /// botsim wrote all of it (a core, a stand-in, a stub, a conversion).
    pub generated: bool,
    /// A conversion of another language's file (GHDL's Verilog of a VHDL entity): the file
    /// and line that messages about any of its lines point at, the entity's declaration.
    pub converted_from: Option<(PathBuf, u32)>,
}

impl Source {
    /// A source from its text.
    pub fn new(path: impl Into<PathBuf>, text: impl Into<String>) -> Source {
        let text = text.into();
        let modules = scan::scan(&text);
        Source {
            path: path.into(),
            text,
            modules,
            dropped: Vec::new(),
            edited: false,
            generated: false,
            converted_from: None,
        }
    }

    /// A source botsim wrote (`path` says where it comes from and ends in `.v`).
    pub fn generated(path: impl Into<PathBuf>, text: impl Into<String>) -> Source {
        Source { edited: true, generated: true, ..Source::new(path, text) }
    }

    /// Read and scan a file (a UTF-8 byte-order mark, as Windows editors write, is skipped).
    pub fn read(path: &Path) -> Result<Source, BoardError> {
        let bytes = std::fs::read(path).map_err(|e| BoardError::at(path, 0, 0, format!("cannot read: {e}")))?;
        let mut text = String::from_utf8_lossy(&bytes).into_owned();
        let bom = text.starts_with('\u{feff}');
        if bom {
            // Three spaces keep every column.
            text.replace_range(..3, "   ");
        }
        Ok(Source { edited: bom, ..Source::new(path, text) })
    }

    /// The module named `name`, if this source compiles it.
    pub fn module(&self, name: &str) -> Option<&Module> {
        self.modules.iter().find(|m| m.name == name)
    }

    /// The 1-based line and column of byte `at` of the text.
    pub fn line_col(&self, at: usize) -> (u32, u32) {
        let before = &self.text[..at];
        let line = before.matches('\n').count() + 1;
        let col = before.len() - before.rfind('\n').map_or(0, |k| k + 1) + 1;
        (line as u32, col as u32)
    }

    /// Replace the bytes `at` of the text with `with` (no newline in either), keeping every
    /// position of the modules and the dropped parts on the text; marks the source edited.
    pub fn replace(&mut self, at: Range<usize>, with: &str) {
        let delta = with.len() as isize - at.len() as isize;
        let shift = |x: usize| if x >= at.end { (x as isize + delta) as usize } else { x };
        for m in &mut self.modules {
            m.shift(&shift);
        }
        for span in &mut self.dropped {
            *span = shift(span.start)..shift(span.end);
        }
        self.text.replace_range(at, with);
        self.edited = true;
    }

    /// The text the build compiles: `dropped` and `also` blanked (newlines kept).
    pub fn compiled_text(&self, also: &[Range<usize>]) -> String {
        let mut text = self.text.clone().into_bytes();
        for span in self.dropped.iter().chain(also) {
            for b in &mut text[span.clone()] {
                if *b != b'\n' {
                    *b = b' ';
                }
            }
        }
        String::from_utf8_lossy(&text).into_owned()
    }
}
