//! Reading the C++ that Verilator generates: the functions of a file, text without white
//! space or comments. Shared by [`super::checks`] and [`super::observed`].
//!
//! ```
//! use botsim::fastforward::cpp;
//! let code = "void f(int x) {\n    x = 1; /* set */\n}\n";
//! assert_eq!(cpp::functions(code), [("f", "    x = 1; /* set */")]);
//! assert_eq!(cpp::squeeze(&cpp::strip_comments("    x = 1; /* set */")), "x=1;");
//! ```

/// The text without white space (Verilator breaks long expressions over lines).
pub fn squeeze(s: &str) -> String {
    s.chars().filter(|c| !c.is_whitespace()).collect()
}

/// The body of the function `name` defined in `code`.
pub fn function<'a>(code: &'a str, name: &str) -> Option<&'a str> {
    functions(code).into_iter().find(|(n, _)| *n == name).map(|(_, b)| b)
}

/// The functions defined in a generated file: (name, body), a definition being a line that
/// ends with `{` and names a function, up to the next line that is `}`.
pub fn functions(code: &str) -> Vec<(&str, &str)> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(open) = rest.find(") {\n") {
        let line_start = rest[..open].rfind('\n').map_or(0, |i| i + 1);
        let head = &rest[line_start..open];
        let name = head.split('(').next().unwrap_or("").split_whitespace().last().unwrap_or("");
        let body_start = open + 4;
        let end = rest[body_start..].find("\n}\n").map_or(rest.len(), |i| body_start + i);
        if !head.starts_with(' ') && !name.is_empty() {
            out.push((name, &rest[body_start..end]));
        }
        rest = &rest[end.min(rest.len())..];
        if rest.len() <= 3 {
            break;
        }
        rest = &rest[3..];
    }
    out
}

/// The index of the bracket that closes the one at `open` (any of `(`, `[`, `{`), if the
/// tokens close it.
pub fn closing(toks: &[Tok], open: usize) -> Option<usize> {
    let mut depth = 0usize;
    for (j, t) in toks.iter().enumerate().skip(open) {
        match t {
            Tok::P("(" | "[" | "{") => depth += 1,
            Tok::P(")" | "]" | "}") => {
                depth = depth.checked_sub(1)?;
                if depth == 0 {
                    return Some(j);
                }
            }
            _ => {}
        }
    }
    None
}

/// The line without its `/* */` and `//` comments.
pub fn strip_comments(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(i) = rest.find("/*") {
        out.push_str(&rest[..i]);
        match rest[i..].find("*/") {
            Some(j) => rest = &rest[i + j + 2..],
            None => return out,
        }
    }
    out.push_str(rest.split("//").next().unwrap_or(""));
    out
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
/// A token of generated C++.
pub enum Tok<'a> {
    Id(&'a str),
    Num(&'a str),
    Str,
    P(&'a str),
}

/// A function body as tokens; comments, strings and `#ifdef VL_DEBUG` blocks dropped.
pub fn tokens(src: &str) -> Result<Vec<Tok<'_>>, String> {
    const PUNCT: &[&str] = &[
        "<<=", ">>=", "->", "::", "<<", ">>", "==", "!=", "<=", ">=", "&&", "||", "|=", "&=", "^=", "+=", "-=", "*=",
        "/=", "%=", "++", "--",
    ];
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    let mut line_start = true;
    while i < b.len() {
        let c = b[i];
        if c == b'\n' {
            line_start = true;
            i += 1;
            continue;
        }
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        if line_start && c == b'#' {
            // A directive; a debug-only block goes whole.
            let end = src[i..].find('\n').map_or(b.len(), |e| i + e);
            let line = src[i..end].trim();
            i = end;
            if line.starts_with("#if") {
                let mut depth = 1;
                while depth > 0 && i < b.len() {
                    let next = src[i + 1..].find('\n').map_or(b.len(), |e| i + 1 + e);
                    let l = src[(i + 1).min(b.len())..next].trim();
                    if l.starts_with("#if") {
                        depth += 1;
                    } else if l.starts_with("#endif") {
                        depth -= 1;
                    } else if depth == 1 && l.starts_with("#el") {
                        return Err(format!("a preprocessor branch in Verilator's output (`{l}`)"));
                    }
                    i = next;
                }
                if !line.contains("VL_DEBUG") {
                    return Err(format!("a preprocessor block in Verilator's output (`{line}`)"));
                }
            }
            continue;
        }
        line_start = false;
        if src[i..].starts_with("//") {
            i = src[i..].find('\n').map_or(b.len(), |e| i + e);
            continue;
        }
        if src[i..].starts_with("/*") {
            i = src[i + 2..].find("*/").map_or(b.len(), |e| i + 2 + e + 2);
            continue;
        }
        if c == b'"' || c == b'\'' {
            let mut j = i + 1;
            while j < b.len() && b[j] != c {
                j += if b[j] == b'\\' { 2 } else { 1 };
            }
            out.push(Tok::Str);
            i = j + 1;
            continue;
        }
        if c.is_ascii_alphabetic() || c == b'_' {
            let mut j = i;
            while j < b.len() && (b[j].is_ascii_alphanumeric() || b[j] == b'_') {
                j += 1;
            }
            out.push(Tok::Id(&src[i..j]));
            i = j;
            continue;
        }
        if c.is_ascii_digit() {
            let mut j = i;
            while j < b.len() && (b[j].is_ascii_alphanumeric() || b[j] == b'.') {
                j += 1;
            }
            out.push(Tok::Num(&src[i..j]));
            i = j;
            continue;
        }
        let p = PUNCT.iter().find(|p| src[i..].starts_with(**p)).copied().unwrap_or(&src[i..i + 1]);
        if !p.is_ascii() {
            return Err("a character the analysis does not know in Verilator's output".into());
        }
        out.push(Tok::P(p));
        i += p.len();
    }
    Ok(out)
}
