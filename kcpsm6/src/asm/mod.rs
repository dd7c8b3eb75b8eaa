//! The KCPSM6 assembler (kcpsm6.exe v2.70 syntax, spec §4).
//!
//! Four passes over the source:
//! 1. **load**: read the file and every `INCLUDE` (relative to the including file) and lex each line;
//! 2. **define**: the global names: `CONSTANT`, `STRING`, `TABLE`, plus caller overrides (`-D`);
//! 3. **lay out**, in order: addresses, labels, `ADDRESS`, `NAMEREG` (sequential), operands parsed
//!    with the register names valid on that line;
//! 4. **encode**: resolve constants and labels, emit the words.
//!
//! Every error of a run is reported, each as `FILE:LINE:COL: error: message`.
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

pub mod lexer;
mod names;
mod number;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::diag::{Diagnostic, Diagnostics, Loc, Severity};
use crate::image::Image;
use crate::isa::{Cond, Instr, Op2, Operand, Reg, Shift};
use lexer::{Arg, Word};
use names::{check_name, is_default_reg};
use number::{parse_num, Num};

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

/// The reason of an I/O error without Rust's "(os error N)" suffix.
pub fn io_reason(e: &std::io::Error) -> String {
    let s = e.to_string();
    match s.find(" (os error") {
        Some(i) => s[..i].to_lowercase(),
        None => s,
    }
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

/// A lexed source line with where it came from.
struct SrcLine {
    loc: Loc,
    /// Position in assembly order, to sort diagnostics.
    seq: usize,
    line: lexer::Line,
}

/// A value in an 8-bit field, resolved in pass 4.
#[derive(Clone, Debug)]
enum Val {
    Lit(u8),
    /// A CONSTANT, possibly inverted with `~`.
    Const {
        name: String,
        col: usize,
        invert: bool,
    },
    /// `label'upper` / `label'lower`.
    LabelPart {
        name: String,
        col: usize,
        upper: bool,
    },
}

/// A 12-bit address field.
#[derive(Clone, Debug)]
enum Addr {
    Lit(u16),
    Label(String, usize),
}

/// The second operand of a two-operand instruction.
#[derive(Clone, Debug)]
enum Opnd {
    Reg(Reg),
    Val(Val),
}

/// An instruction with its registers resolved and its names not yet.
#[derive(Clone, Debug)]
enum Tmpl {
    Op2(Op2, Reg, Opnd),
    Fixed(Instr),
    OutputK(Val, Val),
    /// OUTPUTK of each byte of a STRING or TABLE.
    OutputKSeq(Vec<u8>, String, Val),
    Jump(Option<Cond>, Addr),
    Call(Option<Cond>, Addr),
    LoadReturn(Reg, Val),
    LoadReturnSeq(Reg, Vec<u8>, String),
    Inst(u32),
}

impl Tmpl {
    fn size(&self) -> usize {
        match self {
            Tmpl::OutputKSeq(b, ..) | Tmpl::LoadReturnSeq(_, b, _) => b.len(),
            _ => 1,
        }
    }
}

/// An instruction placed at an address.
struct Placed {
    src: usize,
    addr: u16,
    tmpl: Tmpl,
}

/// NAMEREG state: the current name of each register.
struct RegNames {
    current: [String; 16],
}

impl RegNames {
    fn new() -> RegNames {
        RegNames { current: std::array::from_fn(|i| format!("s{i:X}")) }
    }

    /// The register a word names on this line: `Ok(Some)` for a valid name, `Err` for a default
    /// name that NAMEREG has replaced, `Ok(None)` when it is not a register name at all.
    fn lookup(&self, w: &str) -> Result<Option<u8>, String> {
        if let Some(i) = self.current.iter().position(|n| n == w || (is_default_reg(n) && n.eq_ignore_ascii_case(w))) {
            return Ok(Some(i as u8));
        }
        if is_default_reg(w) {
            let i = u8::from_str_radix(&w[1..], 16).unwrap_or(0);
            return Err(format!("register '{w}' was renamed '{}' by NAMEREG", self.current[i as usize]));
        }
        Ok(None)
    }
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

const MAX_INCLUDE_DEPTH: usize = 32;

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
        let (placed, labels_at, default_jump) = self.lay_out();
        let (image, occupied, listing) = self.encode(&placed, &labels_at, default_jump.as_ref());
        let default_jump = default_jump.and_then(|(a, src)| self.resolve_addr(&a, src));
        self.warn_unused();

        self.diags.sort_by_key(|(seq, d)| (*seq, d.loc.col));
        let has_error = self.diags.iter().any(|(_, d)| d.severity == Severity::Error);
        let diags: Vec<Diagnostic> = self.diags.into_iter().map(|(_, d)| d).collect();
        if has_error {
            return Err(Diagnostics(diags));
        }
        let mut image = image;
        if let Some(t) = default_jump {
            let jump = Instr::Jump(None, t).encode();
            let mut used = vec![false; 4096];
            for &a in &occupied {
                used[a as usize] = true;
            }
            for (a, w) in image.words.iter_mut().enumerate() {
                if !used[a] {
                    *w = jump;
                }
            }
        }
        Ok(Program {
            image,
            occupied,
            listing,
            symbols: self.symbols,
            files: self.files,
            warnings: diags,
            default_jump,
            timestamp: self.opts.timestamp,
        })
    }

    // ---- pass 1: load ------------------------------------------------------------------------

    fn load(&mut self, path: &Path, text: &str, stack: &mut Vec<PathBuf>) {
        self.files.push(path.to_path_buf());
        stack.push(path.to_path_buf());
        for (n, raw) in text.lines().enumerate() {
            let seq = self.lines.len();
            let loc = Loc::new(path, n + 1, 0);
            let line = match lexer::lex_line(raw.trim_end_matches('\r')) {
                Ok(l) => l,
                Err((col, msg)) => {
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

    fn include(&mut self, src: usize, loc: &Loc, args: &[Arg], stack: &mut Vec<PathBuf>) {
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

    // ---- pass 2: global names ----------------------------------------------------------------

    fn add_symbol(&mut self, name: &str, value: SymbolValue, loc: Option<Loc>, src: Option<usize>) {
        if let Some(&i) = self.index.get(name) {
            let prev = match &self.symbols[i].loc {
                Some(l) => format!(" (first defined at {l})"),
                None => " (a predefined name)".to_string(),
            };
            if let (Some(src), Some(l)) = (src, loc) {
                self.err_at(src, l.col, format!("'{name}' is already defined{prev}"));
            }
            return;
        }
        self.index.insert(name.to_string(), self.symbols.len());
        self.symbols.push(Symbol { name: name.to_string(), value, loc, used: false });
    }

    fn predefine(&mut self) {
        let t = crate::time::Civil::from_unix(self.opts.timestamp);
        let consts: [(&str, u8); 17] = [
            ("timestamp_hours", t.hour),
            ("timestamp_minutes", t.minute),
            ("timestamp_seconds", t.second),
            ("datestamp_year", (t.year % 100) as u8),
            ("datestamp_month", t.month),
            ("datestamp_day", t.day),
            ("NUL", 0x00),
            ("BEL", 0x07),
            ("BS", 0x08),
            ("HT", 0x09),
            ("LF", 0x0A),
            ("VT", 0x0B),
            ("CR", 0x0D),
            ("ESC", 0x1B),
            ("DEL", 0x7F),
            ("DCS", 0x90),
            ("ST", 0x9C),
        ];
        for (n, v) in consts {
            self.add_symbol(n, SymbolValue::Constant(v), None, None);
        }
        let strings = [
            ("timestamp$", format!("{:02}:{:02}:{:02}", t.hour, t.minute, t.second)),
            ("datestamp$", format!("{:02} {} {:04}", t.day, t.month_name(), t.year)),
            ("KCPSM6_version$", KCPSM6_VERSION.to_string()),
        ];
        for (n, v) in strings {
            self.add_symbol(n, SymbolValue::String(v.into_bytes()), None, None);
        }
        for i in 0..self.symbols.len() {
            self.symbols[i].used = true;
        }
    }

    /// Look up `%PSM_name` in the caller's defines, then in the environment.
    fn psm_env(&self, word: &str) -> Option<String> {
        let name = &word[1..];
        self.opts
            .defines
            .iter()
            .chain(self.opts.env.iter())
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.clone())
    }

    fn define(&mut self) {
        for src in 0..self.lines.len() {
            let Some(kw) = self.lines[src].line.keyword.clone() else { continue };
            let args = self.lines[src].line.args.clone();
            let loc = |col| Loc { col, ..self.lines[src].loc.clone() };
            match kw.text.to_ascii_uppercase().as_str() {
                "CONSTANT" => {
                    let [Arg::Word(name), value] = &args[..] else {
                        self.err_at(src, kw.col, "CONSTANT needs a name and a value, e.g. CONSTANT name, 7B");
                        continue;
                    };
                    if let Err(m) = check_name(&name.text) {
                        self.err_at(src, name.col, m);
                        continue;
                    }
                    let v = match value {
                        Arg::Word(w) if w.text.starts_with('%') => match self.psm_env(&w.text) {
                            Some(text) => literal8(&text).map_err(|m| format!("{} = '{text}': {m}", w.text)),
                            None => Err(format!("environment value '{}' is not set", &w.text[1..])),
                        },
                        Arg::Word(w) => literal8(&w.text),
                        Arg::Str(w) => char_value(&w.text),
                        other => Err(format!("'{}' is not a constant value", arg_text(other))),
                    };
                    match v {
                        Ok(v) => self.add_symbol(&name.text, SymbolValue::Constant(v), Some(loc(name.col)), Some(src)),
                        Err(m) => self.err_at(src, value.col(), m),
                    }
                }
                "STRING" => {
                    let [Arg::Word(name), value] = &args[..] else {
                        self.err_at(
                            src,
                            kw.col,
                            "STRING needs a name and a quoted text, e.g. STRING hello$, \"Hello\"",
                        );
                        continue;
                    };
                    let text = match value {
                        Arg::Str(w) => Ok(w.text.clone()),
                        Arg::Word(w) if w.text.starts_with('%') => {
                            self.psm_env(&w.text).ok_or(format!("environment value '{}' is not set", &w.text[1..]))
                        }
                        other => Err(format!("expected a quoted text, found '{}'", arg_text(other))),
                    };
                    let checked = text.and_then(|t| printable(&t));
                    match (name.text.strip_suffix('$').map(check_name), checked) {
                        (None, _) => {
                            self.err_at(src, name.col, format!("a STRING name must end in '$': '{}'", name.text))
                        }
                        (Some(Err(m)), _) => self.err_at(src, name.col, m),
                        (_, Err(m)) => self.err_at(src, value.col(), m),
                        (Some(Ok(())), Ok(b)) => {
                            self.add_symbol(&name.text, SymbolValue::String(b), Some(loc(name.col)), Some(src))
                        }
                    }
                }
                "TABLE" => {
                    let (name, list) = match &args[..] {
                        [Arg::Word(name), Arg::List(items, suffix, _)] => (name, Ok((items.clone(), suffix.clone()))),
                        [Arg::Word(name), Arg::Word(w)] if w.text.starts_with('%') => (
                            name,
                            match self.psm_env(&w.text) {
                                Some(t) => match lexer::lex_line(&format!("X {t}")) {
                                    Ok(l) => match &l.args[..] {
                                        [Arg::List(items, suffix, _)] => Ok((items.clone(), suffix.clone())),
                                        _ => Err((w.col, format!("{} = '{t}' is not a table [..]", w.text))),
                                    },
                                    Err((_, m)) => Err((w.col, format!("{} = '{t}': {m}", w.text))),
                                },
                                None => Err((w.col, format!("environment value '{}' is not set", &w.text[1..]))),
                            },
                        ),
                        _ => {
                            self.err_at(src, kw.col, "TABLE needs a name and a list, e.g. TABLE t#, [01, 02]");
                            continue;
                        }
                    };
                    let bytes = list.and_then(|(items, suffix)| table_bytes(&items, suffix.as_ref()));
                    match (name.text.strip_suffix('#').map(check_name), bytes) {
                        (None, _) => {
                            self.err_at(src, name.col, format!("a TABLE name must end in '#': '{}'", name.text))
                        }
                        (Some(Err(m)), _) => self.err_at(src, name.col, m),
                        (_, Err((col, m))) => self.err_at(src, col, m),
                        (Some(Ok(())), Ok(b)) => {
                            self.add_symbol(&name.text, SymbolValue::Table(b), Some(loc(name.col)), Some(src))
                        }
                    }
                }
                _ => {}
            }
        }
        // Caller overrides: replace a constant's or a string's value, or define a new one.
        for (name, value) in &self.opts.defines {
            let loc = Loc::file(format!("-D {name}={value}"));
            if let Some(stem) = name.strip_suffix('$') {
                match (check_name(stem), string_value(value)) {
                    (Err(m), _) | (_, Err(m)) => self.error(0, loc, m),
                    (Ok(()), Ok(text)) => match self.index.get(name) {
                        Some(&i) => match self.symbols[i].value {
                            SymbolValue::String(_) => self.symbols[i].value = SymbolValue::String(text),
                            _ => self.error(0, loc, format!("'{name}' is not a STRING")),
                        },
                        None => {
                            self.index.insert(name.clone(), self.symbols.len());
                            self.symbols.push(Symbol {
                                name: name.clone(),
                                value: SymbolValue::String(text),
                                loc: None,
                                used: true,
                            });
                        }
                    },
                }
                continue;
            }
            if check_name(name).is_err() && !name.to_ascii_uppercase().starts_with("PSM_") {
                self.error(0, loc, format!("'{name}' is not a valid constant name"));
                continue;
            }
            match literal8(value) {
                Err(m) => self.error(0, loc, m),
                Ok(v) => match self.index.get(name) {
                    Some(&i) => match self.symbols[i].value {
                        SymbolValue::Constant(_) => self.symbols[i].value = SymbolValue::Constant(v),
                        _ => self.error(0, loc, format!("'{name}' is not a CONSTANT")),
                    },
                    None => {
                        self.index.insert(name.clone(), self.symbols.len());
                        self.symbols.push(Symbol {
                            name: name.clone(),
                            value: SymbolValue::Constant(v),
                            loc: None,
                            used: true,
                        });
                    }
                },
            }
        }
    }

    // ---- pass 3: layout ----------------------------------------------------------------------

    #[allow(clippy::type_complexity)]
    fn lay_out(&mut self) -> (Vec<Placed>, HashMap<usize, Vec<String>>, Option<(Addr, usize)>) {
        let mut regs = RegNames::new();
        let mut addr: usize = 0;
        let mut placed = Vec::new();
        let mut labels_at: HashMap<usize, Vec<String>> = HashMap::new();
        let mut default_jump = None;
        let mut past_end_reported = false;
        let limit = self.opts.rom_size.map_or(4096, |s| s.words());

        for src in 0..self.lines.len() {
            let line = self.lines[src].line.clone();
            if let Some(l) = &line.label {
                match check_name(&l.text) {
                    Err(m) => self.err_at(src, l.col, m),
                    Ok(()) if addr > 0xFFF => {
                        self.err_at(src, l.col, format!("label '{}' is past the last address FFF", l.text));
                    }
                    Ok(()) => {
                        let loc = Loc { col: l.col, ..self.lines[src].loc.clone() };
                        self.add_symbol(&l.text, SymbolValue::Label(addr as u16), Some(loc), Some(src));
                        labels_at.entry(src).or_default().push(l.text.clone());
                    }
                }
            }
            let Some(kw) = &line.keyword else { continue };
            let upper = kw.text.to_ascii_uppercase();
            match upper.as_str() {
                "CONSTANT" | "STRING" | "TABLE" | "INCLUDE" => continue,
                "NAMEREG" => {
                    self.namereg(src, kw, &line.args, &mut regs);
                    continue;
                }
                "ADDRESS" => {
                    match &line.args[..] {
                        [Arg::Word(w)] => match parse_num(&w.text, 3, 12) {
                            Some(Ok(a)) if (a as usize) < addr => self.err_at(
                                src,
                                w.col,
                                format!("ADDRESS {:03X} is below the current address {:03X}", a, addr),
                            ),
                            Some(Ok(a)) => addr = a as usize,
                            Some(Err(m)) => self.err_at(src, w.col, m),
                            None => self.err_at(src, w.col, format!("ADDRESS needs a number, found '{}'", w.text)),
                        },
                        _ => self.err_at(src, kw.col, "ADDRESS needs one address, e.g. ADDRESS 3FF"),
                    }
                    continue;
                }
                "DEFAULT_JUMP" => {
                    match &line.args[..] {
                        [Arg::Word(w)] if default_jump.is_none() => match address(w) {
                            Ok(a) => default_jump = Some((a, src)),
                            Err(m) => self.err_at(src, w.col, m),
                        },
                        [Arg::Word(w)] => self.err_at(src, w.col, "DEFAULT_JUMP is given more than once"),
                        _ => self.err_at(src, kw.col, "DEFAULT_JUMP needs one target, e.g. DEFAULT_JUMP reset"),
                    }
                    continue;
                }
                _ => {}
            }
            let tmpl = match self.instruction(kw, &line.args, &regs) {
                Ok(t) => t,
                Err((col, m)) => {
                    self.err_at(src, col, m);
                    addr += 1;
                    continue;
                }
            };
            let size = tmpl.size();
            if addr + size > limit && !past_end_reported {
                past_end_reported = true;
                let what = match self.opts.rom_size {
                    Some(s) if s.words() < 4096 => {
                        format!("the {}-word ROM (last address {:03X})", s.words(), s.words() - 1)
                    }
                    _ => "the last address FFF".to_string(),
                };
                self.err_at(src, kw.col, format!("program runs past {what}"));
            }
            if addr + size <= 4096 {
                placed.push(Placed { src, addr: addr as u16, tmpl });
            }
            addr += size;
        }
        (placed, labels_at, default_jump)
    }

    fn namereg(&mut self, src: usize, kw: &Word, args: &[Arg], regs: &mut RegNames) {
        let [Arg::Word(old), Arg::Word(new)] = args else {
            return self.err_at(src, kw.col, "NAMEREG needs a register and a new name, e.g. NAMEREG s5, count");
        };
        let r = match regs.lookup(&old.text) {
            Ok(Some(r)) => r,
            Ok(None) => return self.err_at(src, old.col, format!("'{}' is not a register name", old.text)),
            Err(m) => return self.err_at(src, old.col, m),
        };
        if is_default_reg(&new.text) {
            if u8::from_str_radix(&new.text[1..], 16).ok() != Some(r) {
                return self.err_at(
                    src,
                    new.col,
                    format!("cannot rename s{r:X} to another register name '{}'", new.text),
                );
            }
        } else if let Err(m) = check_name(&new.text) {
            return self.err_at(src, new.col, m);
        } else if let Some(&i) = self.index.get(&new.text) {
            let at = self.symbols[i].loc.as_ref().map_or(" (a predefined name)".to_string(), |l| format!(" at {l}"));
            return self.err_at(src, new.col, format!("'{}' is already defined{at}", new.text));
        } else if regs.current.iter().any(|n| n == &new.text) {
            return self.err_at(src, new.col, format!("'{}' already names a register", new.text));
        }
        regs.current[r as usize] = new.text.clone();
    }

    /// Parse one instruction's operands.
    fn instruction(&mut self, kw: &Word, args: &[Arg], regs: &RegNames) -> Result<Tmpl, (usize, String)> {
        let upper = kw.text.to_ascii_uppercase();
        let reg = |a: &Arg| -> Result<Reg, (usize, String)> {
            match a {
                Arg::Word(w) => match regs.lookup(&w.text) {
                    Ok(Some(r)) => Ok(Reg(r)),
                    Ok(None) => Err((w.col, format!("expected a register, found '{}'", w.text))),
                    Err(m) => Err((w.col, m)),
                },
                other => Err((other.col(), format!("expected a register, found '{}'", arg_text(other)))),
            }
        };
        let count = |n: usize, form: &str| -> Result<(), (usize, String)> {
            if args.len() == n {
                Ok(())
            } else {
                Err((kw.col, format!("{upper} takes {form}")))
            }
        };
        let op2 = Op2::ALL.into_iter().find(|o| o.mnemonic() == upper);
        if let Some(op) = op2 {
            let form =
                if op.indirect() { "a register and a port or (sY)" } else { "a register and a register or constant" };
            count(2, &format!("two operands: {form}"))?;
            let sx = if op == Op2::Star {
                match &args[0] {
                    Arg::Word(w) if is_default_reg(&w.text) => Reg(u8::from_str_radix(&w.text[1..], 16).unwrap_or(0)),
                    a => {
                        return Err((
                            a.col(),
                            format!("STAR needs a default register name s0-sF first, found '{}'", arg_text(a)),
                        ))
                    }
                }
            } else {
                reg(&args[0])?
            };
            let second = match (&args[1], op.indirect()) {
                (Arg::Paren(ws, col), true) => match &ws[..] {
                    [w] => Opnd::Reg(reg(&Arg::Word(w.clone()))?),
                    _ => return Err((*col, "expected one register in '( )'".into())),
                },
                (Arg::Paren(_, col), false) => return Err((*col, format!("{upper} does not take '( )'"))),
                (Arg::Word(w), indirect) => match regs.lookup(&w.text) {
                    Ok(Some(_)) if indirect => {
                        return Err((w.col, format!("write a register port or address as '({})'", w.text)))
                    }
                    Ok(Some(r)) => Opnd::Reg(Reg(r)),
                    Err(m) => return Err((w.col, m)),
                    Ok(None) => Opnd::Val(value8(w)?),
                },
                (Arg::Str(w), _) => Opnd::Val(Val::Lit(char_value(&w.text).map_err(|m| (w.col, m))?)),
                (a, _) => return Err((a.col(), format!("unexpected '{}'", arg_text(a)))),
            };
            return Ok(Tmpl::Op2(op, sx, second));
        }
        if let Some(s) = Shift::ALL.into_iter().find(|s| s.mnemonic() == upper) {
            count(1, "one register")?;
            return Ok(Tmpl::Fixed(Instr::Shift(s, reg(&args[0])?)));
        }
        let word_arg = |i: usize| -> Option<String> {
            match args.get(i) {
                Some(Arg::Word(w)) => Some(w.text.to_ascii_uppercase()),
                _ => None,
            }
        };
        let cond_of = |s: &str| Cond::ALL.into_iter().find(|c| c.name() == s);
        match upper.as_str() {
            "HWBUILD" => {
                count(1, "one register")?;
                Ok(Tmpl::Fixed(Instr::HwBuild(reg(&args[0])?)))
            }
            "JUMP" | "CALL" => {
                let (cond, target) = match args {
                    [Arg::Word(t)] => (None, t),
                    [Arg::Word(c), Arg::Word(t)] => match cond_of(&c.text.to_ascii_uppercase()) {
                        Some(cond) => (Some(cond), t),
                        None => {
                            return Err((c.col, format!("expected a condition Z, NZ, C or NC, found '{}'", c.text)))
                        }
                    },
                    [Arg::Paren(_, col), ..] => {
                        return Err((*col, format!("write {upper}@ (sX, sY) for a register target")))
                    }
                    _ => return Err((kw.col, format!("{upper} takes [condition,] target"))),
                };
                let a = address(target).map_err(|m| (target.col, m))?;
                Ok(if upper == "JUMP" { Tmpl::Jump(cond, a) } else { Tmpl::Call(cond, a) })
            }
            "JUMP@" | "CALL@" => match args {
                [Arg::Paren(ws, col)] if ws.len() == 2 => {
                    let x = reg(&Arg::Word(ws[0].clone()))?;
                    let y = reg(&Arg::Word(ws[1].clone()))?;
                    let _ = col;
                    Ok(Tmpl::Fixed(if upper == "JUMP@" { Instr::JumpAt(x, y) } else { Instr::CallAt(x, y) }))
                }
                _ => Err((kw.col, format!("{upper} takes (sX, sY)"))),
            },
            "RETURN" => match args {
                [] => Ok(Tmpl::Fixed(Instr::Return(None))),
                [Arg::Word(c)] => match cond_of(&c.text.to_ascii_uppercase()) {
                    Some(cond) => Ok(Tmpl::Fixed(Instr::Return(Some(cond)))),
                    None => Err((c.col, format!("expected a condition Z, NZ, C or NC, found '{}'", c.text))),
                },
                _ => Err((kw.col, "RETURN takes an optional condition (no comma)".into())),
            },
            "RETURNI" => match word_arg(0).as_deref() {
                Some("ENABLE") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::ReturnI(true))),
                Some("DISABLE") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::ReturnI(false))),
                _ => Err((kw.col, "RETURNI takes ENABLE or DISABLE".into())),
            },
            "ENABLE" | "DISABLE" => match word_arg(0).as_deref() {
                Some("INTERRUPT") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::Interrupt(upper == "ENABLE"))),
                _ => Err((kw.col, format!("write {upper} INTERRUPT"))),
            },
            "REGBANK" => match word_arg(0).as_deref() {
                Some("A") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::RegBank(false))),
                Some("B") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::RegBank(true))),
                _ => Err((kw.col, "REGBANK takes A or B".into())),
            },
            "OUTPUTK" => {
                count(2, "a constant (or STRING$/TABLE#) and a port 0-F")?;
                let port = match &args[1] {
                    Arg::Word(w) => port4(w)?,
                    a => return Err((a.col(), format!("expected a port 0-F, found '{}'", arg_text(a)))),
                };
                match &args[0] {
                    Arg::Word(w) if w.text.ends_with('$') || w.text.ends_with('#') => {
                        let bytes = self.sequence(&w.text).map_err(|m| (w.col, m))?;
                        Ok(Tmpl::OutputKSeq(bytes, w.text.clone(), port))
                    }
                    Arg::Word(w) => Ok(Tmpl::OutputK(value8(w)?, port)),
                    Arg::Str(w) => Ok(Tmpl::OutputK(Val::Lit(char_value(&w.text).map_err(|m| (w.col, m))?), port)),
                    a => Err((a.col(), format!("expected a constant, found '{}'", arg_text(a)))),
                }
            }
            "LOAD&RETURN" => {
                count(2, "a register and a constant (or STRING$/TABLE#)")?;
                let sx = reg(&args[0])?;
                match &args[1] {
                    Arg::Word(w) if w.text.ends_with('$') || w.text.ends_with('#') => {
                        let bytes = self.sequence(&w.text).map_err(|m| (w.col, m))?;
                        Ok(Tmpl::LoadReturnSeq(sx, bytes, w.text.clone()))
                    }
                    Arg::Word(w) => Ok(Tmpl::LoadReturn(sx, value8(w)?)),
                    Arg::Str(w) => Ok(Tmpl::LoadReturn(sx, Val::Lit(char_value(&w.text).map_err(|m| (w.col, m))?))),
                    a => Err((a.col(), format!("expected a constant, found '{}'", arg_text(a)))),
                }
            }
            "INST" => match args {
                [Arg::Word(w)] => match parse_num(&w.text, 5, 18) {
                    Some(Ok(v)) if v <= 0x3FFFF => Ok(Tmpl::Inst(v)),
                    Some(Ok(_)) => Err((w.col, format!("INST value '{}' is above 3FFFF", w.text))),
                    Some(Err(m)) => Err((w.col, m)),
                    None => Err((w.col, format!("INST needs a 5-digit hex word, found '{}'", w.text))),
                },
                _ => Err((kw.col, "INST takes one 18-bit word, e.g. INST 2EA7B".into())),
            },
            _ => Err((kw.col, format!("unknown instruction or directive '{}'", kw.text))),
        }
    }

    /// The bytes of a STRING$ or TABLE#, marking it used.
    fn sequence(&mut self, name: &str) -> Result<Vec<u8>, String> {
        match self.index.get(name) {
            Some(&i) => {
                self.symbols[i].used = true;
                match &self.symbols[i].value {
                    SymbolValue::String(b) | SymbolValue::Table(b) => Ok(b.clone()),
                    _ => Err(format!("'{name}' is not a STRING or TABLE")),
                }
            }
            None => Err(format!("undefined {} '{name}'", if name.ends_with('$') { "STRING" } else { "TABLE" })),
        }
    }

    // ---- pass 4: encode ----------------------------------------------------------------------

    fn lookup(&mut self, name: &str) -> Option<SymbolValue> {
        let i = *self.index.get(name)?;
        self.symbols[i].used = true;
        Some(self.symbols[i].value.clone())
    }

    /// Resolve an 8-bit value; returns it and a listing annotation.
    fn resolve_val(&mut self, v: &Val, src: usize) -> Option<(u8, Option<String>)> {
        match v {
            Val::Lit(b) => Some((*b, None)),
            Val::Const { name, col, invert } => match self.lookup(name) {
                Some(SymbolValue::Constant(c)) => {
                    let tag = if *invert { format!("~{name}") } else { name.clone() };
                    Some((if *invert { !c } else { c }, Some(tag)))
                }
                Some(SymbolValue::Label(_)) => {
                    self.err_at(
                        src,
                        *col,
                        format!("'{name}' is a label; write {name}'upper or {name}'lower for its address bytes"),
                    );
                    None
                }
                Some(_) => {
                    self.err_at(src, *col, format!("'{name}' is not a CONSTANT"));
                    None
                }
                None => {
                    self.err_at(src, *col, format!("undefined constant '{name}'"));
                    None
                }
            },
            Val::LabelPart { name, col, upper } => match self.lookup(name) {
                Some(SymbolValue::Label(a)) => {
                    let b = if *upper { (a >> 8) as u8 } else { a as u8 };
                    Some((b, Some(format!("{name}'{}", if *upper { "upper" } else { "lower" }))))
                }
                _ => {
                    self.err_at(src, *col, format!("undefined label '{name}'"));
                    None
                }
            },
        }
    }

    fn resolve_addr(&mut self, a: &Addr, src: usize) -> Option<u16> {
        match a {
            Addr::Lit(v) => Some(*v),
            Addr::Label(name, col) => match self.lookup(name) {
                Some(SymbolValue::Label(v)) => Some(v),
                Some(_) => {
                    self.err_at(src, *col, format!("'{name}' is not a label"));
                    None
                }
                None => {
                    self.err_at(src, *col, format!("undefined label '{name}'"));
                    None
                }
            },
        }
    }

    #[allow(clippy::type_complexity)]
    fn encode(
        &mut self,
        placed: &[Placed],
        labels_at: &HashMap<usize, Vec<String>>,
        default_jump: Option<&(Addr, usize)>,
    ) -> (Image, Vec<u16>, Vec<Listed>) {
        let mut image = Image::zeroed();
        let mut occupied = Vec::new();
        let mut listing = Vec::new();
        let mut by_src: HashMap<usize, usize> = HashMap::new();
        for (i, p) in placed.iter().enumerate() {
            by_src.insert(p.src, i);
        }
        let _ = default_jump;
        for src in 0..self.lines.len() {
            let loc = self.lines[src].loc.clone();
            let comment = self.lines[src].line.comment.clone();
            let label = labels_at.get(&src).and_then(|v| v.first().cloned());
            let Some(&pi) = by_src.get(&src) else {
                let text = self.directive_text(src);
                let address = label.as_ref().and_then(|l| match self.lookup_quiet(l) {
                    Some(SymbolValue::Label(a)) => Some(a),
                    _ => None,
                });
                if label.is_some() || !text.is_empty() || comment.is_some() {
                    listing.push(Listed { loc, address, word: None, label, text, comment });
                }
                continue;
            };
            let p = &placed[pi];
            let words = self.encode_one(&p.tmpl, p.src);
            for (k, (word, text)) in words.into_iter().enumerate() {
                let a = p.addr + k as u16;
                image.words[a as usize] = word;
                occupied.push(a);
                listing.push(Listed {
                    loc: loc.clone(),
                    address: Some(a),
                    word: Some(word),
                    label: if k == 0 { label.clone() } else { None },
                    text,
                    comment: if k == 0 { comment.clone() } else { None },
                });
            }
        }
        occupied.sort_unstable();
        (image, occupied, listing)
    }

    fn lookup_quiet(&self, name: &str) -> Option<SymbolValue> {
        self.index.get(name).map(|&i| self.symbols[i].value.clone())
    }

    /// The words of one placed instruction with their canonical, annotated text.
    fn encode_one(&mut self, t: &Tmpl, src: usize) -> Vec<(u32, String)> {
        let ann = |base: String, tag: Option<String>| match tag {
            Some(t) => format!("{base}[{t}]"),
            None => base,
        };
        match t {
            Tmpl::Fixed(i) => vec![(i.encode(), i.to_string())],
            Tmpl::Inst(w) => vec![(*w, format!("INST {w:05X}"))],
            Tmpl::Op2(op, sx, Opnd::Reg(sy)) => {
                let i = Instr::Op2(*op, *sx, Operand::Reg(*sy));
                vec![(i.encode(), i.to_string())]
            }
            Tmpl::Op2(op, sx, Opnd::Val(v)) => {
                let Some((k, tag)) = self.resolve_val(v, src) else { return vec![(0, String::new())] };
                let i = Instr::Op2(*op, *sx, Operand::Const(k));
                vec![(i.encode(), ann(i.to_string(), tag))]
            }
            Tmpl::OutputK(v, p) => {
                let (Some((k, tk)), Some((port, tp))) = (self.resolve_val(v, src), self.resolve_val(p, src)) else {
                    return vec![(0, String::new())];
                };
                if port > 15 {
                    let col = match p {
                        Val::Const { col, .. } | Val::LabelPart { col, .. } => *col,
                        Val::Lit(_) => 0,
                    };
                    self.err_at(src, col, format!("OUTPUTK port must be 0-F, the constant is {port:02X}"));
                    return vec![(0, String::new())];
                }
                let i = Instr::OutputK(k, port);
                let text = format!("OUTPUTK {}, {}", ann(format!("{k:02X}"), tk), ann(format!("{port:X}"), tp));
                vec![(i.encode(), text)]
            }
            Tmpl::OutputKSeq(bytes, name, p) => {
                let Some((port, _)) = self.resolve_val(p, src) else { return vec![(0, String::new())] };
                bytes
                    .iter()
                    .map(|&b| {
                        (Instr::OutputK(b, port & 15).encode(), format!("OUTPUTK {b:02X}[{name}], {:X}", port & 15))
                    })
                    .collect()
            }
            Tmpl::LoadReturn(sx, v) => {
                let Some((k, tag)) = self.resolve_val(v, src) else { return vec![(0, String::new())] };
                let i = Instr::LoadReturn(*sx, k);
                vec![(i.encode(), ann(i.to_string(), tag))]
            }
            Tmpl::LoadReturnSeq(sx, bytes, name) => bytes
                .iter()
                .map(|&b| (Instr::LoadReturn(*sx, b).encode(), format!("LOAD&RETURN {sx}, {b:02X}[{name}]")))
                .collect(),
            Tmpl::Jump(c, a) | Tmpl::Call(c, a) => {
                let Some(target) = self.resolve_addr(a, src) else { return vec![(0, String::new())] };
                let i = if matches!(t, Tmpl::Jump(..)) { Instr::Jump(*c, target) } else { Instr::Call(*c, target) };
                let tag = match a {
                    Addr::Label(n, _) => Some(n.clone()),
                    Addr::Lit(_) => None,
                };
                vec![(i.encode(), ann(i.to_string(), tag))]
            }
        }
    }

    /// The listing text of a directive line.
    fn directive_text(&self, src: usize) -> String {
        let l = &self.lines[src].line;
        let Some(kw) = &l.keyword else { return String::new() };
        let args: Vec<String> = l.args.iter().map(arg_text).collect();
        format!("{} {}", kw.text.to_ascii_uppercase(), args.join(", ")).trim_end().to_string()
    }

    fn warn_unused(&mut self) {
        for s in &self.symbols {
            if let (false, Some(loc), SymbolValue::Constant(_)) = (s.used, &s.loc, &s.value) {
                let seq =
                    self.lines.iter().find(|l| l.loc.file == loc.file && l.loc.line == loc.line).map_or(0, |l| l.seq);
                self.diags
                    .push((seq, Diagnostic::warning(loc.clone(), format!("constant '{}' is never used", s.name))));
            }
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

/// An operand written back as text (for messages and the listing).
fn arg_text(a: &Arg) -> String {
    match a {
        Arg::Word(w) => w.text.clone(),
        Arg::Str(w) => format!("\"{}\"", w.text),
        Arg::Paren(ws, _) => format!("({})", ws.iter().map(|w| w.text.as_str()).collect::<Vec<_>>().join(", ")),
        Arg::List(items, suffix, _) => format!(
            "[{}]{}",
            items.iter().map(arg_text).collect::<Vec<_>>().join(", "),
            suffix.as_ref().map_or("", |w| w.text.as_str())
        ),
    }
}

/// A character literal's value.
fn char_value(text: &str) -> Result<u8, String> {
    let mut chars = text.chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) if c.is_ascii() => Ok(c as u8),
        _ => Err(format!("a character literal holds one ASCII character, found \"{text}\"")),
    }
}

/// A STRING's text as given with `-D name$=text`: the text, or the text in double quotes.
fn string_value(value: &str) -> Result<Vec<u8>, String> {
    printable(value.strip_prefix('"').and_then(|v| v.strip_suffix('"')).unwrap_or(value))
}

/// A STRING's bytes: printable ASCII only (32-126).
fn printable(text: &str) -> Result<Vec<u8>, String> {
    match text.chars().find(|c| !(' '..='~').contains(c)) {
        Some(c) => Err(format!("STRING text may hold only printable ASCII, found '{}'", c.escape_default())),
        None => Ok(text.as_bytes().to_vec()),
    }
}

/// An 8-bit literal as written in CONSTANT or `-D`: hex (2 digits), 'd, 'b (8 digits), "c".
pub fn literal8(text: &str) -> Result<u8, String> {
    let t = text.trim();
    if t.len() == 3 && t.starts_with('"') && t.ends_with('"') {
        return char_value(&t[1..2]);
    }
    match parse_num(t, 2, 8) {
        Some(r) => r.map(|v| v as u8),
        None => Err(format!("'{t}' is not a value (write 2 hex digits, nn'd, 8 binary digits 'b or \"c\")")),
    }
}

/// An operand in a kk, pp or ss position.
fn value8(w: &Word) -> Result<Val, (usize, String)> {
    let t = &w.text;
    if let Some(name) = t.strip_prefix('~') {
        return match check_name(name) {
            Ok(()) => Ok(Val::Const { name: name.to_string(), col: w.col, invert: true }),
            Err(_) => Err((w.col, format!("'~' applies to a CONSTANT name, found '{t}'"))),
        };
    }
    if let Some((name, part)) = t.split_once('\'') {
        let lower = part.to_ascii_lowercase();
        if lower == "upper" || lower == "lower" {
            check_name(name).map_err(|m| (w.col, m))?;
            return Ok(Val::LabelPart { name: name.to_string(), col: w.col, upper: lower == "upper" });
        }
    }
    match parse_num(t, 2, 8) {
        Some(Ok(v)) => Ok(Val::Lit(v as u8)),
        Some(Err(m)) => Err((w.col, m)),
        None => match check_name(t) {
            Ok(()) => Ok(Val::Const { name: t.clone(), col: w.col, invert: false }),
            Err(m) => Err((w.col, m)),
        },
    }
}

/// The OUTPUTK port: one hex digit, 4 binary digits, 0'd-15'd or a CONSTANT (00-0F).
fn port4(w: &Word) -> Result<Val, (usize, String)> {
    match parse_num(&w.text, 1, 4) {
        Some(Ok(v)) if v <= 15 => Ok(Val::Lit(v as u8)),
        Some(Ok(_)) => Err((w.col, format!("OUTPUTK port '{}' is above F", w.text))),
        Some(Err(m)) => Err((w.col, m)),
        None => match check_name(&w.text) {
            Ok(()) => Ok(Val::Const { name: w.text.clone(), col: w.col, invert: false }),
            Err(m) => Err((w.col, m)),
        },
    }
}

/// A 12-bit target or address: 3 hex digits, 'd, 12 binary digits, or a label.
fn address(w: &Word) -> Result<Addr, String> {
    match parse_num(&w.text, 3, 12) {
        Some(Ok(v)) => Ok(Addr::Lit(v as u16)),
        Some(Err(m)) => Err(m),
        None => check_name(&w.text).map(|()| Addr::Label(w.text.clone(), w.col)),
    }
}

/// The bytes of a TABLE list with its optional `'d` / `'b` suffix.
fn table_bytes(items: &[Arg], suffix: Option<&Word>) -> Result<Vec<u8>, (usize, String)> {
    let radix = match suffix.map(|w| w.text.to_ascii_lowercase()) {
        None => Num::Hex,
        Some(s) if s == "'d" => Num::Dec,
        Some(s) if s == "'b" => Num::Bin,
        Some(_) => {
            let w = suffix.unwrap_or_else(|| unreachable!());
            return Err((w.col, format!("a TABLE suffix is 'd or 'b, found '{}'", w.text)));
        }
    };
    items
        .iter()
        .map(|a| match a {
            Arg::Word(w) => {
                let text = match radix {
                    Num::Hex => w.text.clone(),
                    Num::Dec => format!("{}'d", w.text),
                    Num::Bin => format!("{}'b", w.text),
                };
                match parse_num(&text, 2, 8) {
                    Some(Ok(v)) => Ok(v as u8),
                    Some(Err(m)) => Err((w.col, m)),
                    None => Err((w.col, format!("'{}' is not a table value", w.text))),
                }
            }
            Arg::Str(w) => char_value(&w.text).map_err(|m| (w.col, m)),
            other => Err((other.col(), format!("'{}' is not a table value", arg_text(other)))),
        })
        .collect()
}
