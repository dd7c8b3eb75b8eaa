//! Splits one source line into an optional label, a keyword and its operands.
//!
//! Lexical rules (spec §4.1): `;` starts a comment outside quotes; a character literal is
//! exactly three characters `"c"` (so `"""`, `";"` and `":"` are legal); the text of a
//! `STRING` directive is everything between the first and last `"` of the line.

/// A word: a run of name characters (letters, digits, `_`, and the `$ # ' & @ % ~` that
/// KCPSM6 uses in names, mnemonics and number suffixes).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Word {
    pub text: String,
    /// 1-based column.
    pub col: usize,
}

/// One operand: the comma-separated pieces of a statement.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Arg {
    /// A word, or several separated by blanks (`ENABLE INTERRUPT` has the second as its operand).
    Word(Word),
    /// A quoted text: a character literal, an INCLUDE path or a STRING's text.
    Str(Word),
    /// `( ... )` with its comma-separated words.
    Paren(Vec<Word>, usize),
    /// `[ ... ]` with its comma-separated words and an optional suffix word such as `'d`.
    List(Vec<Arg>, Option<Word>, usize),
}

impl Arg {
    pub fn col(&self) -> usize {
        match self {
            Arg::Word(w) | Arg::Str(w) => w.col,
            Arg::Paren(_, c) | Arg::List(_, _, c) => *c,
        }
    }
}

/// A lexed line.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Line {
    pub label: Option<Word>,
    pub keyword: Option<Word>,
    pub args: Vec<Arg>,
    /// The comment, without the `;`.
    pub comment: Option<String>,
    /// The column of a `,` after the last operand (`RETURN NZ, ; done`): kcpsm6.exe ignores
    /// it, and so does the assembler, with a warning.
    pub trailing_comma: Option<usize>,
}

/// An error at a column of the line being read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ColError {
    /// 1-based column.
    pub col: usize,
    pub message: String,
}

impl ColError {
    pub fn new(col: usize, message: impl Into<String>) -> ColError {
        ColError { col, message: message.into() }
    }
}

fn is_name_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '_' | '$' | '#' | '\'' | '&' | '@' | '%' | '~')
}

#[derive(Clone, Debug, PartialEq, Eq)]
enum Tok {
    Word(Word),
    Str(Word),
    Punct(char, usize),
}

/// Lex a line into tokens (without the comment).
fn tokens(chars: &[char], string_directive: bool) -> Result<(Vec<Tok>, Option<String>), ColError> {
    let mut out = Vec::new();
    let mut i = 0;
    let last_quote = chars.iter().rposition(|&c| c == '"');
    while i < chars.len() {
        let c = chars[i];
        let col = i + 1;
        if c == ';' {
            let comment: String = chars[i + 1..].iter().collect();
            return Ok((out, Some(comment)));
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '"' {
            let end = if string_directive {
                // STRING: the text runs to the last quote of the line.
                match last_quote {
                    Some(j) if j > i => j,
                    _ => return Err(ColError::new(col, "unterminated string: expected a closing '\"'")),
                }
            } else if i + 2 < chars.len() && chars[i + 2] == '"' {
                i + 2
            } else {
                match chars[i + 1..].iter().position(|&c| c == '"') {
                    Some(j) => i + 1 + j,
                    None => return Err(ColError::new(col, "unterminated string: expected a closing '\"'")),
                }
            };
            out.push(Tok::Str(Word { text: chars[i + 1..end].iter().collect(), col }));
            i = end + 1;
        } else if is_name_char(c) {
            let start = i;
            while i < chars.len() && is_name_char(chars[i]) {
                i += 1;
            }
            out.push(Tok::Word(Word { text: chars[start..i].iter().collect(), col: start + 1 }));
        } else if matches!(c, ',' | '(' | ')' | '[' | ']' | ':') {
            out.push(Tok::Punct(c, col));
            i += 1;
        } else {
            return Err(ColError::new(col, format!("unexpected character '{}'", c.escape_default())));
        }
    }
    Ok((out, None))
}

/// Lex one line of source.
pub fn lex_line(text: &str) -> Result<Line, ColError> {
    let chars: Vec<char> = text.chars().collect();
    // Find out whether this is a STRING directive before lexing quotes.
    let string_directive = {
        let words: Vec<String> = text
            .split(|c: char| !is_name_char(c))
            .filter(|w| !w.is_empty())
            .take(2)
            .map(|w| w.to_ascii_uppercase())
            .collect();
        let before_quote = text.split('"').next().unwrap_or("");
        let has_label = before_quote.contains(':');
        let kw = if has_label { words.get(1) } else { words.first() };
        kw.is_some_and(|w| w == "STRING")
    };
    let (toks, comment) = tokens(&chars, string_directive)?;
    let mut line = Line { comment, ..Line::default() };
    let mut rest = &toks[..];

    if let [Tok::Word(w), Tok::Punct(':', _), tail @ ..] = rest {
        line.label = Some(w.clone());
        rest = tail;
    }
    match rest.first() {
        None => return Ok(line),
        Some(Tok::Word(w)) => {
            line.keyword = Some(w.clone());
            rest = &rest[1..];
        }
        Some(Tok::Punct(':', col)) => return Err(ColError::new(*col, "a label needs a name before ':'")),
        Some(Tok::Punct(c, col)) => {
            return Err(ColError::new(*col, format!("expected an instruction or directive, found '{c}'")))
        }
        Some(Tok::Str(w)) => return Err(ColError::new(w.col, "expected an instruction or directive, found a string")),
    }

    // Operands: the first follows the keyword, each later one follows a comma.
    let mut i = 0;
    let mut want = true;
    while i < rest.len() {
        let tok = &rest[i];
        i += 1;
        let arg = match tok {
            Tok::Punct(',', col) if want => return Err(ColError::new(*col, "missing operand before ','")),
            Tok::Punct(',', col) => {
                if i == rest.len() {
                    line.trailing_comma = Some(*col);
                }
                want = true;
                continue;
            }
            Tok::Word(w) | Tok::Str(w) if !want => {
                return Err(ColError::new(w.col, format!("expected ',' before '{}'", w.text)))
            }
            Tok::Punct(c, col) if !want => return Err(ColError::new(*col, format!("unexpected '{c}'"))),
            Tok::Word(w) => Arg::Word(w.clone()),
            Tok::Str(w) => Arg::Str(w.clone()),
            Tok::Punct('(', col) => {
                let (words, next) = group(rest, i, ')', *col)?;
                i = next;
                Arg::Paren(words, *col)
            }
            Tok::Punct('[', col) => {
                let (items, next) = table(rest, i, *col)?;
                i = next;
                let suffix = match rest.get(i) {
                    Some(Tok::Word(w)) if w.text.starts_with('\'') => {
                        i += 1;
                        Some(w.clone())
                    }
                    _ => None,
                };
                Arg::List(items, suffix, *col)
            }
            Tok::Punct(c, col) => return Err(ColError::new(*col, format!("unexpected '{c}'"))),
        };
        line.args.push(arg);
        want = false;
    }
    Ok(line)
}

/// Table values (words or character literals) separated by commas up to `]`.
fn table(toks: &[Tok], mut i: usize, open_col: usize) -> Result<(Vec<Arg>, usize), ColError> {
    let mut items = Vec::new();
    let mut want = true;
    loop {
        match toks.get(i) {
            None => return Err(ColError::new(open_col, "missing ']'")),
            Some(Tok::Punct(']', _)) if !want => return Ok((items, i + 1)),
            Some(Tok::Punct(',', _)) if !want => want = true,
            Some(Tok::Word(w)) if want => {
                items.push(Arg::Word(w.clone()));
                want = false;
            }
            Some(Tok::Str(w)) if want => {
                items.push(Arg::Str(w.clone()));
                want = false;
            }
            Some(Tok::Punct(c, col)) => return Err(ColError::new(*col, format!("unexpected '{c}' in a table"))),
            Some(Tok::Word(w) | Tok::Str(w)) => return Err(ColError::new(w.col, "expected ',' between table values")),
        }
        i += 1;
    }
}

/// Words separated by commas up to the closing `close`; returns them and the index after it.
fn group(toks: &[Tok], mut i: usize, close: char, open_col: usize) -> Result<(Vec<Word>, usize), ColError> {
    let mut words = Vec::new();
    let mut want = true;
    loop {
        match toks.get(i) {
            None => return Err(ColError::new(open_col, format!("missing '{close}'"))),
            Some(Tok::Punct(c, _)) if *c == close && !want => return Ok((words, i + 1)),
            Some(Tok::Punct(',', _)) if !want => want = true,
            Some(Tok::Word(w)) if want => {
                words.push(w.clone());
                want = false;
            }
            Some(Tok::Punct(c, col)) => return Err(ColError::new(*col, format!("unexpected '{c}'"))),
            Some(Tok::Word(w) | Tok::Str(w)) => return Err(ColError::new(w.col, format!("unexpected '{}'", w.text))),
        }
        i += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(l: &Line) -> Vec<String> {
        l.args
            .iter()
            .map(|a| match a {
                Arg::Word(w) => w.text.clone(),
                Arg::Str(w) => format!("\"{}\"", w.text),
                Arg::Paren(ws, _) => format!("({})", ws.iter().map(|w| w.text.as_str()).collect::<Vec<_>>().join(",")),
                Arg::List(items, s, _) => format!("[{}]{}", items.len(), s.as_ref().map_or("", |w| &w.text)),
            })
            .collect()
    }

    #[test]
    fn label_instruction_comment() {
        let l = lex_line("loop: ADD s0, 01 ; count").unwrap();
        assert_eq!(l.label.unwrap().text, "loop");
        assert_eq!(l.keyword.unwrap().text, "ADD");
        assert_eq!(words(&lex_line("loop: ADD s0, 01 ; count").unwrap()), ["s0", "01"]);
        assert_eq!(l.comment.as_deref(), Some(" count"));
    }

    #[test]
    fn character_literals_with_quote_and_semicolon() {
        assert_eq!(words(&lex_line("LOAD s0, \";\" ; c").unwrap()), ["s0", "\";\""]);
        assert_eq!(words(&lex_line("LOAD s0, \"\"\"").unwrap()), ["s0", "\"\"\""]);
    }

    #[test]
    fn string_runs_to_last_quote() {
        let l = lex_line("STRING msg$, \"say \"hi\"; now\" ; comment").unwrap();
        assert_eq!(words(&l), ["msg$", "\"say \"hi\"; now\""]);
    }

    #[test]
    fn groups_and_tables() {
        assert_eq!(words(&lex_line("JUMP@ (s3, s4)").unwrap()), ["(s3,s4)"]);
        assert_eq!(words(&lex_line("INPUT s0, (s1)").unwrap()), ["s0", "(s1)"]);
        assert_eq!(words(&lex_line("TABLE t#, [1, 2, 3]'d").unwrap()), ["t#", "[3]'d"]);
        assert_eq!(words(&lex_line("ENABLE INTERRUPT").unwrap()), ["INTERRUPT"]);
    }

    #[test]
    fn errors_have_columns() {
        assert_eq!(lex_line("LOAD s0 01").unwrap_err().col, 9);
        assert_eq!(lex_line("LOAD s0, !").unwrap_err().col, 10);
        assert_eq!(lex_line("LOAD ,s0").unwrap_err().col, 6);
    }

    #[test]
    fn a_trailing_comma_is_kept_aside() {
        let l = lex_line("RETURN NZ, ;comment").unwrap();
        assert_eq!((words(&l), l.trailing_comma), (vec!["NZ".to_string()], Some(10)));
        assert_eq!(lex_line("RETURN NZ").unwrap().trailing_comma, None);
    }
}
