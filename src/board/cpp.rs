//! Reading the C++ that Verilator generates: the functions of a file, text without white
//! space or comments. Shared by [`super::checks`] and [`super::observed`].
//!
//! ```
//! use botsim::board::cpp;
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
