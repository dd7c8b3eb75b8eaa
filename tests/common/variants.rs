//! Syntax variants of Verilog sources, for the metamorphic test (tests/boards/syntax_variants.rs):
//! the same design re-emitted token by token with the white space, comments, line breaks and
//! attributes Verilog allows between tokens changed, so every run of a variant must equal the
//! original's. Students write `bot(` and `bot (`, `#(` and `# (`, statements over several
//! lines, `(* keep *)` before items; a rule of botsim's that reads one of them and not the
//! other is a defect this finds.
//!
//! The lexer knows what re-spacing must keep: compiler directives stay whole lines (`` `define``
//! bodies, `` `timescale``), strings and numbers (`8'h0A`, `32'd4_000_000`) stay one token, a
//! `//` comment ends its line, an escaped identifier ends with a space, and two tokens are
//! only joined where they cannot read as one (`<` `=`, `(` `*`, two words).

/// A token of the source, as re-emitted.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Tok {
    /// An identifier, keyword, number, system task or macro use: needs a separator from the
    /// next word.
    Word(String),
    /// An escaped identifier (`\bus[0] `): always followed by white space.
    Escaped(String),
    /// A string literal.
    Str(String),
    /// An operator or punctuation (longest match).
    Punct(String),
    /// A comment (`//` ones end their line; block ones are kept as written).
    Comment(String),
    /// A compiler directive's whole line (`` `timescale 1ns / 1ps``, a `` `define``).
    Directive(String),
}

/// The operators of more than one character, longest first.
const OPERATORS: &[&str] = &[
    "<<<=", ">>>=", "<<<", ">>>", "===", "!==", "<<=", ">>=", "<=", ">=", "==", "!=", "&&", "||", "<<", ">>", "**",
    "~&", "~|", "~^", "^~", "+:", "-:", "->", "(*", "*)", "+=", "-=", "++", "--",
];

fn lex(src: &str) -> Vec<Tok> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    // `*)` closes an attribute only where one is open (`@(*)` is `(`, `*`, `)`).
    let mut attribute = false;
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_' || c == b'$';
    while i < b.len() {
        let c = b[i];
        let start = i;
        if c.is_ascii_whitespace() {
            i += 1;
        } else if src[i..].starts_with("//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            out.push(Tok::Comment(src[start..i].trim_end().to_string()));
        } else if src[i..].starts_with("/*") {
            i = src[i + 2..].find("*/").map_or(b.len(), |k| i + 2 + k + 2);
            out.push(Tok::Comment(src[start..i].to_string()));
        } else if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i = (i + 1).min(b.len());
            out.push(Tok::Str(src[start..i].to_string()));
        } else if c == b'\\' {
            while i < b.len() && !b[i].is_ascii_whitespace() {
                i += 1;
            }
            out.push(Tok::Escaped(src[start..i].to_string()));
        } else if c == b'`' {
            // A directive is its whole line (with its continuations); a macro's use is a word.
            let name_end = (i + 1..b.len()).find(|&k| !word(b[k])).unwrap_or(b.len());
            let name = &src[i + 1..name_end];
            let directive = [
                "timescale",
                "define",
                "include",
                "ifdef",
                "ifndef",
                "else",
                "elsif",
                "endif",
                "undef",
                "default_nettype",
                "resetall",
                "celldefine",
                "endcelldefine",
                "line",
            ]
            .contains(&name);
            if directive {
                loop {
                    while i < b.len() && b[i] != b'\n' {
                        i += 1;
                    }
                    if i > 0 && b[i - 1] == b'\\' && i < b.len() {
                        i += 1;
                        continue;
                    }
                    break;
                }
                out.push(Tok::Directive(src[start..i].trim_end().to_string()));
            } else {
                i = name_end;
                out.push(Tok::Word(src[start..i].to_string()));
            }
        } else if word(c) || (c == b'\'' && i + 1 < b.len() && b"sSbBoOdDhH".contains(&b[i + 1])) {
            // Identifiers, keywords and numbers: a number's size, base and digits stay one
            // token (`8'h0A`, `'d5`, `4'b10_1x`, `1.5e3`).
            while i < b.len()
                && (word(b[i]) || b[i] == b'\'' || b[i] == b'?' || (b[i] == b'.' && b[start].is_ascii_digit()))
            {
                i += 1;
            }
            out.push(Tok::Word(src[start..i].to_string()));
        } else {
            let op = OPERATORS.iter().find(|o| src[i..].starts_with(**o));
            // `@(*)` is no attribute: `(` then `*`.
            let op = op.filter(|o| match **o {
                "(*" => !src[i + 2..].trim_start().starts_with(')'),
                "*)" => attribute,
                _ => true,
            });
            match op {
                Some(&"(*") => attribute = true,
                Some(&"*)") => attribute = false,
                _ => {}
            }
            let len = op.map_or_else(|| src[i..].chars().next().map_or(1, char::len_utf8), |o| o.len());
            i += len;
            out.push(Tok::Punct(src[start..i].to_string()));
        }
    }
    out
}

/// How a variant spaces its tokens.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// No white space but where Verilog needs it: `bot(`, `#(`, `a<=b;`, one line per
    /// directive and `//` comment.
    Tight,
    /// White space around every token, line breaks inside statements, block comments
    /// between tokens and an attribute before each `always` and `assign`.
    Loose,
    /// One space between tokens and a trailing comma before the `)` of every list Vivado
    /// accepts one in: named port connections and parameter overrides (`.x(y),)`), and a
    /// module's port declarations.
    Commas,
}

/// The `)` tokens of `toks` a trailing comma goes before, in [`Style::Commas`].
fn trailing_comma_places(toks: &[Tok]) -> std::collections::BTreeSet<usize> {
    let code: Vec<usize> = (0..toks.len()).filter(|&i| !matches!(toks[i], Tok::Comment(_))).collect();
    let is = |k: Option<&usize>, p: &str| k.is_some_and(|&i| matches!(&toks[i], Tok::Punct(x) if x == p));
    let word = |k: Option<&usize>, w: &str| k.is_some_and(|&i| matches!(&toks[i], Tok::Word(x) if x == w));
    let (mut open, mut matched) = (Vec::new(), std::collections::BTreeMap::new());
    let mut places = std::collections::BTreeSet::new();
    for (c, &i) in code.iter().enumerate() {
        match &toks[i] {
            Tok::Punct(p) if p == "(" => open.push(c),
            Tok::Punct(p) if p == ")" => {
                let Some(o) = open.pop() else { continue };
                matched.insert(c, o);
                let named = is(code.get(o + 1), ".") && is(code.get(c.wrapping_sub(1)), ")");
                // `module m (` or `module m #(...) (`, with ports.
                let name = match o.checked_sub(1) {
                    Some(b) if is(code.get(b), ")") => matched.get(&b).and_then(|&p| p.checked_sub(2)),
                    b => b,
                };
                let header = name.is_some_and(|n| n > 0 && word(code.get(n - 1), "module")) && o + 1 != c;
                if named || header {
                    places.insert(i);
                }
            }
            _ => {}
        }
    }
    places
}

/// Whether `a` then `b` with nothing between would read as other tokens.
fn needs_space(a: &Tok, b: &Tok) -> bool {
    use Tok::*;
    match (a, b) {
        (Escaped(_), _) | (_, Escaped(_)) => true,
        (Word(_), Word(_)) => true,
        (Word(x), Str(_)) | (Str(_), Word(x)) => x.starts_with('`'),
        (Punct(x), Punct(y)) => {
            let joined = format!("{x}{y}");
            OPERATORS.iter().any(|o| joined.contains(o) && !x.contains(o) && !y.contains(o))
                || joined.contains("//")
                || joined.contains("/*")
        }
        (Punct(x), Comment(_)) => x.ends_with('/'),
        _ => false,
    }
}

/// A small deterministic generator for where the loose variant breaks lines.
struct Rng(u64);

impl Rng {
    fn chance(&mut self, percent: u64) -> bool {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0 % 100 < percent
    }
}

/// `src` re-emitted in `style` (the loose style's line breaks and comments drawn from `seed`).
pub fn variant(src: &str, style: Style, seed: u64) -> String {
    let toks = lex(src);
    let mut out = String::new();
    let mut r = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut prev: Option<&Tok> = None;
    let commas = if style == Style::Commas { trailing_comma_places(&toks) } else { Default::default() };
    for (i, t) in toks.iter().enumerate() {
        // What must stand alone on its line.
        let own_line = matches!(t, Tok::Directive(_));
        let after_line =
            matches!(prev, Some(Tok::Directive(_))) || matches!(prev, Some(Tok::Comment(c)) if c.starts_with("//"));
        if let Some(p) = prev {
            if own_line || after_line {
                out.push('\n');
            } else {
                match style {
                    Style::Tight => {
                        if needs_space(p, t) {
                            out.push(' ');
                        }
                    }
                    Style::Commas => out.push(' '),
                    Style::Loose => {
                        out.push_str(if r.chance(12) { "\n    " } else { " " });
                        if r.chance(4) && !matches!(t, Tok::Comment(_)) && !matches!(p, Tok::Punct(x) if x == "/") {
                            out.push_str("/* variant */ ");
                        }
                    }
                }
            }
        }
        if style == Style::Loose && matches!(t, Tok::Word(w) if w == "always" || w == "assign") {
            out.push_str("(* keep = \"true\" *) ");
        }
        if commas.contains(&i) {
            out.push_str(", ");
        }
        match t {
            Tok::Word(s) | Tok::Escaped(s) | Tok::Str(s) | Tok::Punct(s) | Tok::Comment(s) | Tok::Directive(s) => {
                out.push_str(s)
            }
        }
        prev = Some(t);
    }
    out.push('\n');
    out
}

/// The tokens of `src` but its comments, as text: what a variant must keep.
pub fn tokens(src: &str) -> Vec<String> {
    lex(src)
        .into_iter()
        .filter_map(|t| match t {
            Tok::Comment(_) => None,
            Tok::Word(s) | Tok::Escaped(s) | Tok::Str(s) | Tok::Punct(s) | Tok::Directive(s) => Some(s),
        })
        .collect()
}
