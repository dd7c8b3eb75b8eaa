//! One reader for `$readmemh` text, shared by program images and worlds: hex values separated
//! by white space (CR and tabs included), `@address` lines, `//` and `/* */` comments, `_`
//! inside a number ignored: what Verilator's and Icarus's `$readmemh` accept
//! (spec/verilator.md §3). The caller reads each value's digits into its own type.
//!
//! ```
//! use kcpsm6::readmemh::{entries, Entry};
//! let e = entries("@10 // start\n2D_056 1\n", 4096).unwrap();
//! assert_eq!(e[0], Entry { address: 0x10, value: "2D056".into(), line: 2, col: 1 });
//! assert_eq!((e[1].address, e[1].value.as_str(), e[1].col), (0x11, "1", 8));
//! ```

/// One value, the address it goes to, and where it stands (1-based line and column).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    pub address: usize,
    /// The value's digits, underscores removed (not checked: the caller parses them).
    pub value: String,
    pub line: usize,
    pub col: usize,
}

/// Why the text cannot be read, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// An `@` not followed by a hex address below the memory's size.
    BadAddress { token: String, line: usize, col: usize },
    /// A value at or past the memory's size.
    PastEnd { line: usize, col: usize },
    /// A `/*` comment without its `*/`.
    UnclosedComment { line: usize, col: usize },
}

/// The values of `text` in order, for a memory of `size` entries.
pub fn entries(text: &str, size: usize) -> Result<Vec<Entry>, Error> {
    let mut out = Vec::new();
    let mut address = 0usize;
    let (mut line, mut col) = (1, 1);
    let mut chars = text.chars().peekable();
    let mut token = String::new();
    let (mut tok_line, mut tok_col) = (1, 1);

    // Ends the token being read, if any.
    let mut finish = |token: &mut String, tl: usize, tc: usize, out: &mut Vec<Entry>| -> Result<(), Error> {
        if token.is_empty() {
            return Ok(());
        }
        let t = std::mem::take(token);
        if let Some(a) = t.strip_prefix('@') {
            address = usize::from_str_radix(&a.replace('_', ""), 16)
                .ok()
                .filter(|&a| a < size)
                .ok_or(Error::BadAddress { token: t.clone(), line: tl, col: tc })?;
            return Ok(());
        }
        if address >= size {
            return Err(Error::PastEnd { line: tl, col: tc });
        }
        out.push(Entry { address, value: t.replace('_', ""), line: tl, col: tc });
        address += 1;
        Ok(())
    };

    while let Some(c) = chars.next() {
        let (here_line, here_col) = (line, col);
        if c == '\n' {
            line += 1;
            col = 1;
        } else {
            col += 1;
        }
        if c == '/' && matches!(chars.peek(), Some('/') | Some('*')) {
            finish(&mut token, tok_line, tok_col, &mut out)?;
            if chars.next() == Some('/') {
                // Line comment: skip to the end of the line.
                for c in chars.by_ref() {
                    if c == '\n' {
                        line += 1;
                        col = 1;
                        break;
                    }
                }
            } else {
                col += 1;
                let mut closed = false;
                while let Some(c) = chars.next() {
                    if c == '\n' {
                        line += 1;
                        col = 1;
                        continue;
                    }
                    col += 1;
                    if c == '*' && chars.peek() == Some(&'/') {
                        chars.next();
                        col += 1;
                        closed = true;
                        break;
                    }
                }
                if !closed {
                    return Err(Error::UnclosedComment { line: here_line, col: here_col });
                }
            }
        } else if c.is_whitespace() {
            finish(&mut token, tok_line, tok_col, &mut out)?;
        } else {
            if token.is_empty() {
                (tok_line, tok_col) = (here_line, here_col);
            }
            token.push(c);
        }
    }
    finish(&mut token, tok_line, tok_col, &mut out)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(text: &str) -> Vec<(usize, String)> {
        entries(text, 16).unwrap().into_iter().map(|e| (e.address, e.value)).collect()
    }

    #[test]
    fn white_space_comments_and_addresses() {
        let v = values("1\r\n2\t3 // four\n/* five\n six */ 7\n@A 8 @0_F 9\n");
        let want: Vec<(usize, String)> = [(0, "1"), (1, "2"), (2, "3"), (3, "7"), (10, "8"), (15, "9")]
            .iter()
            .map(|(a, v)| (*a, v.to_string()))
            .collect();
        assert_eq!(v, want);
    }

    #[test]
    fn places_are_1_based_lines_and_columns() {
        let e = entries("  1\n\t 22 3//x\n", 16).unwrap();
        let at: Vec<(usize, usize)> = e.iter().map(|e| (e.line, e.col)).collect();
        assert_eq!(at, [(1, 3), (2, 3), (2, 6)]);
    }

    #[test]
    fn errors_say_where() {
        assert_eq!(entries("1\n@G\n", 16), Err(Error::BadAddress { token: "@G".into(), line: 2, col: 1 }));
        assert_eq!(entries("@10\n", 16), Err(Error::BadAddress { token: "@10".into(), line: 1, col: 1 }));
        assert_eq!(entries("@F 1 2\n", 16), Err(Error::PastEnd { line: 1, col: 6 }));
        assert_eq!(entries("1 /* open\n", 16), Err(Error::UnclosedComment { line: 1, col: 3 }));
    }
}
