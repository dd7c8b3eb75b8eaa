//! Pass 2: the global names (predefined, CONSTANT, STRING, TABLE, `-D`), and their use.

use super::lexer::{self, Arg, ColError};
use super::names::check_name;
use super::operands::{arg_text, char_value, literal8, printable, string_value, table_bytes};
use super::{Assembler, Symbol, SymbolValue, KCPSM6_VERSION};
use crate::diag::{Diagnostic, Loc};

impl Assembler<'_> {
    pub(super) fn add_symbol(&mut self, name: &str, value: SymbolValue, loc: Option<Loc>, src: Option<usize>) {
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

    pub(super) fn predefine(&mut self) {
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
    pub(super) fn psm_env(&self, word: &str) -> Option<String> {
        let name = &word[1..];
        self.opts
            .defines
            .iter()
            .chain(self.opts.env.iter())
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.clone())
    }

    pub(super) fn define(&mut self) {
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
                                        _ => {
                                            Err(ColError::new(w.col, format!("{} = '{t}' is not a table [..]", w.text)))
                                        }
                                    },
                                    Err(ColError { col: _, message: m }) => {
                                        Err(ColError::new(w.col, format!("{} = '{t}': {m}", w.text)))
                                    }
                                },
                                None => Err(ColError::new(
                                    w.col,
                                    format!("environment value '{}' is not set", &w.text[1..]),
                                )),
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
                        (_, Err(ColError { col, message })) => self.err_at(src, col, message),
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

    pub(super) fn warn_unused(&mut self) {
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
