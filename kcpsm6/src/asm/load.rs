//! Pass 1: read the top file and every INCLUDE, and lex each line.

use std::path::{Path, PathBuf};

use super::lexer::{self, Arg, ColError};
use super::{decode_text, Assembler, SrcLine};
use crate::diag::{io_reason, Loc};

/// INCLUDEs nested deeper than this are taken for a cycle.
const MAX_INCLUDE_DEPTH: usize = 32;

impl Assembler<'_> {
    pub(super) fn load(&mut self, path: &Path, text: &str, stack: &mut Vec<PathBuf>) {
        // A UTF-8 byte-order mark (Windows editors write one) is not text: KCPSM6 skips it.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        self.files.push(path.to_path_buf());
        stack.push(path.to_path_buf());
        for (n, raw) in text.lines().enumerate() {
            let seq = self.lines.len();
            let loc = Loc::new(path, n + 1, 0);
            let line = match lexer::lex_line(raw.trim_end_matches('\r')) {
                Ok(l) => l,
                Err(ColError { col, message: msg }) => {
                    self.error(seq, Loc { col, ..loc.clone() }, msg);
                    lexer::Line::default()
                }
            };
            let include = line.keyword.as_ref().is_some_and(|k| k.text.eq_ignore_ascii_case("INCLUDE"));
            let args = line.args.clone();
            let trailing_comma = line.trailing_comma;
            self.lines.push(SrcLine { loc: loc.clone(), seq, line });
            if let Some(col) = trailing_comma {
                self.warn_at(seq, col, "trailing ',' ignored");
            }
            if include {
                self.include(seq, &loc, &args, stack);
            }
        }
        stack.pop();
    }

    pub(super) fn include(&mut self, src: usize, loc: &Loc, args: &[Arg], stack: &mut Vec<PathBuf>) {
        let fail = |me: &mut Self, col: usize, msg: String| {
            me.include_failed = true;
            me.err_at(src, col, msg);
        };
        let (name, col) = match args {
            [Arg::Str(w)] => (w.text.clone(), w.col),
            [a, ..] => {
                return fail(self, a.col(), "INCLUDE needs a quoted file name, e.g. INCLUDE \"file.psm\"".into())
            }
            [] => return fail(self, 1, "INCLUDE needs a quoted file name".into()),
        };
        if !name.to_ascii_lowercase().ends_with(".psm") {
            return fail(self, col, format!("INCLUDE file '{name}' must have the extension .psm"));
        }
        let written = include_path(loc.file.parent().unwrap_or(Path::new("")), &name);
        let path = match find_ignoring_case(&written) {
            Some(found) if found != written => {
                self.warn_at(
                    src,
                    col,
                    format!(
                        "INCLUDE \"{name}\" found as '{}' (the names differ in case, which Windows ignores)",
                        found.display()
                    ),
                );
                found
            }
            _ => written,
        };
        if stack.len() >= MAX_INCLUDE_DEPTH || stack.iter().any(|p| same_file(p, &path)) {
            return fail(self, col, format!("INCLUDE \"{name}\" includes itself"));
        }
        match std::fs::read(&path) {
            Err(e) => fail(self, col, format!("cannot read INCLUDE file '{}': {}", path.display(), io_reason(&e))),
            Ok(bytes) => match decode_text(&path, &bytes) {
                Ok(text) => self.load(&path, &text, stack),
                Err(d) => fail(self, col, d.message),
            },
        }
    }
}

/// The path an INCLUDE names, relative to the including file's folder `dir`: kcpsm6.exe ran on
/// Windows, so `\` separates folders as well as `/` (`.\lib\ports.psm`, `..\common.psm`).
fn include_path(dir: &Path, name: &str) -> PathBuf {
    let mut path = if name.starts_with(['/', '\\']) { PathBuf::from("/") } else { dir.to_path_buf() };
    for part in name.split(['\\', '/']) {
        match part {
            "" | "." => {}
            part => path.push(part),
        }
    }
    path
}

/// `path` if it exists; otherwise the one file whose components match it ignoring case (the
/// way a Windows file system finds it), if there is exactly one.
fn find_ignoring_case(path: &Path) -> Option<PathBuf> {
    if path.exists() {
        return Some(path.to_path_buf());
    }
    let mut found = PathBuf::new();
    for part in path.components() {
        let next = found.join(part);
        if next.exists() || !matches!(part, std::path::Component::Normal(_)) {
            found = next;
            continue;
        }
        let want = part.as_os_str().to_string_lossy().to_lowercase();
        let dir = if found.as_os_str().is_empty() { Path::new(".") } else { &found };
        let mut matches = std::fs::read_dir(dir)
            .ok()?
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().to_lowercase() == want);
        let hit = matches.next()?;
        if matches.next().is_some() {
            return None;
        }
        found.push(hit.file_name());
    }
    Some(found)
}

fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}
