//! Where each ROM address came from: the source file, line and text of the instruction, and
//! the label it lies under (`label+offset`), from the assembler's own listing; for a program
//! with no source (INIT strings, a .hex) only the disassembly is known.
//!
//! ```
//! use kcpsm6::{asm::assemble_source, source::SourceMap};
//! use std::path::Path;
//! let text = "start: LOAD s0, 01\n       ADD s0, 01 ; two\nloop:  JUMP loop\n";
//! let p = assemble_source(Path::new("p.psm"), text, &Default::default()).unwrap();
//! let map = SourceMap::of_source(&p, Path::new("p.psm"), text);
//! assert_eq!(map.label(1).unwrap(), ("start", 1));
//! assert_eq!(map.line(2).unwrap().line, 3);
//! assert_eq!(map.line(2).unwrap().text, "loop:  JUMP loop");
//! assert_eq!(map.line(1).unwrap().text, "       ADD s0, 01");
//! assert_eq!(map.describe(1), "start+1");
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::asm::{Program, SymbolValue};
use crate::isa::ROM_WORDS;

/// The source line of one instruction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceLine {
    pub file: PathBuf,
    /// 1-based.
    pub line: usize,
    /// The line as written (without its comment), or the listing's canonical statement when
    /// the file cannot be read again.
    pub text: String,
}

/// The source of every address of a program.
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    lines: BTreeMap<u16, SourceLine>,
    /// Labels by address, ascending (several labels at one address: the first defined).
    labels: Vec<(u16, String)>,
}

impl SourceMap {
    /// The map of an assembled program: its listing's lines (read again from the files the
    /// program came from, for their text as written) and its labels.
    pub fn of(program: &Program) -> SourceMap {
        SourceMap::with(program, BTreeMap::new())
    }

    /// The same for a program assembled from text in memory (`assemble_source`, `assemble_str`):
    /// `text` is the source of `path`.
    pub fn of_source(program: &Program, path: &Path, text: &str) -> SourceMap {
        let lines = text.lines().map(str::to_string).collect();
        SourceMap::with(program, BTreeMap::from([(path.to_path_buf(), Some(lines))]))
    }

    fn with(program: &Program, mut files: BTreeMap<PathBuf, Option<Vec<String>>>) -> SourceMap {
        let mut lines = BTreeMap::new();
        for l in &program.listing {
            let (Some(addr), Some(_)) = (l.address, l.word) else { continue };
            let text = files
                .entry(l.loc.file.clone())
                .or_insert_with(|| read_lines(&l.loc.file))
                .as_ref()
                .and_then(|f| f.get(l.loc.line.wrapping_sub(1)))
                .map(|t| strip_comment(t))
                .unwrap_or_else(|| l.text.clone());
            lines.insert(addr, SourceLine { file: l.loc.file.clone(), line: l.loc.line, text });
        }
        let mut labels: Vec<(u16, String)> = program
            .symbols
            .iter()
            .filter_map(|s| match s.value {
                SymbolValue::Label(a) if s.loc.is_some() => Some((a, s.name.clone())),
                _ => None,
            })
            .collect();
        labels.sort_by_key(|(a, _)| *a);
        labels.dedup_by_key(|(a, _)| *a);
        SourceMap { lines, labels }
    }

    /// The source line of the instruction at `addr`.
    pub fn line(&self, addr: u16) -> Option<&SourceLine> {
        self.lines.get(&(addr % ROM_WORDS as u16))
    }

    /// The label at or before `addr`, and the distance from it.
    pub fn label(&self, addr: u16) -> Option<(&str, u16)> {
        let k = self.labels.partition_point(|(a, _)| *a <= addr);
        k.checked_sub(1).map(|k| (self.labels[k].1.as_str(), addr - self.labels[k].0))
    }

    /// `label+offset` (`label` at the label itself), or the address in hex with no label.
    pub fn describe(&self, addr: u16) -> String {
        match self.label(addr) {
            Some((l, 0)) => l.to_string(),
            Some((l, k)) => format!("{l}+{k}"),
            None => format!("{addr:03X}"),
        }
    }

    /// The address of the label `name`.
    pub fn label_address(&self, name: &str) -> Option<u16> {
        self.labels.iter().find(|(_, l)| l == name).map(|(a, _)| *a)
    }

    /// The address of the instruction on line `line` of the file named `file` (its name, or
    /// a path ending in it).
    pub fn line_address(&self, file: &str, line: usize) -> Option<u16> {
        self.lines.iter().find(|(_, l)| l.line == line && l.file.ends_with(file)).map(|(a, _)| *a)
    }

    /// Whether the map knows any source.
    pub fn has_source(&self) -> bool {
        !self.lines.is_empty()
    }
}

fn read_lines(path: &Path) -> Option<Vec<String>> {
    let text = std::fs::read(path).ok()?;
    Some(String::from_utf8_lossy(&text).lines().map(str::to_string).collect())
}

/// The line without its `;` comment and trailing blanks (a `;` inside quotes is kept).
fn strip_comment(line: &str) -> String {
    let mut quoted = None;
    for (i, c) in line.char_indices() {
        match (quoted, c) {
            (None, '"' | '\'') => quoted = Some(c),
            (Some(q), c) if c == q => quoted = None,
            (None, ';') => return line[..i].trim_end().to_string(),
            _ => {}
        }
    }
    line.trim_end().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_go_and_quoted_semicolons_stay() {
        assert_eq!(strip_comment("  LOAD s0, 01   ; one"), "  LOAD s0, 01");
        assert_eq!(strip_comment("STRING x$, \"a;b\" ; c"), "STRING x$, \"a;b\"");
    }
}
