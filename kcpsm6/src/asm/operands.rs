//! Operands as the layout pass reads them: values and addresses whose names are resolved
//! in pass 4, and the literal forms (spec §4.1).

use super::lexer::{Arg, ColError, Word};
use super::names::check_name;
use super::number::{parse_num, Num};
use crate::isa::{Cond, Instr, Op2, Reg};

#[derive(Clone, Debug)]
pub(super) enum Val {
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
pub(super) enum Addr {
    Lit(u16),
    Label(String, usize),
}

/// The second operand of a two-operand instruction.
#[derive(Clone, Debug)]
pub(super) enum Opnd {
    Reg(Reg),
    Val(Val),
}

/// An instruction with its registers resolved and its names not yet.
#[derive(Clone, Debug)]
pub(super) enum Tmpl {
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
    pub(super) fn size(&self) -> usize {
        match self {
            Tmpl::OutputKSeq(b, ..) | Tmpl::LoadReturnSeq(_, b, _) => b.len(),
            _ => 1,
        }
    }
}

/// An operand written back as text (for messages and the listing).
pub(super) fn arg_text(a: &Arg) -> String {
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
pub(super) fn char_value(text: &str) -> Result<u8, String> {
    let mut chars = text.chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) if c.is_ascii() => Ok(c as u8),
        _ => Err(format!("a character literal holds one ASCII character, found \"{text}\"")),
    }
}

/// A STRING's text as given with `-D name$=text`: the text, or the text in double quotes.
pub(super) fn string_value(value: &str) -> Result<Vec<u8>, String> {
    printable(value.strip_prefix('"').and_then(|v| v.strip_suffix('"')).unwrap_or(value))
}

/// A STRING's bytes: printable ASCII only (32-126).
pub(super) fn printable(text: &str) -> Result<Vec<u8>, String> {
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
pub(super) fn value8(w: &Word) -> Result<Val, ColError> {
    let t = &w.text;
    if let Some(name) = t.strip_prefix('~') {
        return match check_name(name) {
            Ok(()) => Ok(Val::Const { name: name.to_string(), col: w.col, invert: true }),
            Err(_) => Err(ColError::new(w.col, format!("'~' applies to a CONSTANT name, found '{t}'"))),
        };
    }
    if let Some((name, part)) = t.split_once('\'') {
        let lower = part.to_ascii_lowercase();
        if lower == "upper" || lower == "lower" {
            check_name(name).map_err(|m| ColError::new(w.col, m))?;
            return Ok(Val::LabelPart { name: name.to_string(), col: w.col, upper: lower == "upper" });
        }
    }
    match parse_num(t, 2, 8) {
        Some(Ok(v)) => Ok(Val::Lit(v as u8)),
        Some(Err(m)) => Err(ColError::new(w.col, m)),
        None => match check_name(t) {
            Ok(()) => Ok(Val::Const { name: t.clone(), col: w.col, invert: false }),
            Err(m) => Err(ColError::new(w.col, m)),
        },
    }
}

/// The OUTPUTK port: one hex digit, 4 binary digits, 0'd-15'd or a CONSTANT (00-0F).
pub(super) fn port4(w: &Word) -> Result<Val, ColError> {
    match parse_num(&w.text, 1, 4) {
        Some(Ok(v)) if v <= 15 => Ok(Val::Lit(v as u8)),
        Some(Ok(_)) => Err(ColError::new(w.col, format!("OUTPUTK port '{}' is above F", w.text))),
        Some(Err(m)) => Err(ColError::new(w.col, m)),
        None => match check_name(&w.text) {
            Ok(()) => Ok(Val::Const { name: w.text.clone(), col: w.col, invert: false }),
            Err(m) => Err(ColError::new(w.col, m)),
        },
    }
}

/// A 12-bit target or address: 3 hex digits, 'd, 12 binary digits, or a label.
pub(super) fn address(w: &Word) -> Result<Addr, String> {
    match parse_num(&w.text, 3, 12) {
        Some(Ok(v)) => Ok(Addr::Lit(v as u16)),
        Some(Err(m)) => Err(m),
        None => check_name(&w.text).map(|()| Addr::Label(w.text.clone(), w.col)),
    }
}

/// The bytes of a TABLE list with its optional `'d` / `'b` suffix.
pub(super) fn table_bytes(items: &[Arg], suffix: Option<&Word>) -> Result<Vec<u8>, ColError> {
    let radix = match suffix.map(|w| w.text.to_ascii_lowercase()) {
        None => Num::Hex,
        Some(s) if s == "'d" => Num::Dec,
        Some(s) if s == "'b" => Num::Bin,
        Some(_) => {
            let w = suffix.unwrap_or_else(|| unreachable!());
            return Err(ColError::new(w.col, format!("a TABLE suffix is 'd or 'b, found '{}'", w.text)));
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
                    Some(Err(m)) => Err(ColError::new(w.col, m)),
                    None => Err(ColError::new(w.col, format!("'{}' is not a table value", w.text))),
                }
            }
            Arg::Str(w) => char_value(&w.text).map_err(|m| ColError::new(w.col, m)),
            other => Err(ColError::new(other.col(), format!("'{}' is not a table value", arg_text(other)))),
        })
        .collect()
}
