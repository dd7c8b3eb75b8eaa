//! Trailing commas in the lists Vivado reads without them: `.gameover(gameover),` then `);`
//! in an instance's named port connections, in its parameter overrides, and in a module's
//! port or parameter declarations. Verilog has no empty item there; Verilator takes the
//! comma for an empty positional connection (`Duplicate pin connection: '__pinNumber12'`) or
//! stops at the `)`. A positional connection list keeps its comma: an empty last connection
//! is Verilog's way of leaving a port open.
//!
//! ```
//! use botsim_core::frontend::commas::trailing_commas;
//! let text = "module top(input clk, output [1:0] led,\n);\n  game #(.W(4),) g (\n    .clk(clk),\n    .over(led[0]),\n  );\n  $display(\"a\",);\nendmodule\n";
//! let found = trailing_commas(text);
//! let lists: Vec<(u32, &str)> = found.iter().map(|c| (c.line, c.list.as_str())).collect();
//! assert_eq!(lists, [(1, "the ports of module `top`"), (3, "the parameters of `g`"), (5, "the port connections of `g`")]);
//! assert!(found.iter().all(|c| &text[c.at..c.at + 1] == ","));
//! ```

use super::scan::{group_open, tokenize, Tok, Token};

/// A comma just before the `)` that ends a list.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TrailingComma {
    /// Its byte offset, line and column (1-based).
    pub at: usize,
    pub line: u32,
    pub col: u32,
    /// The list it ends, for a message: "the port connections of `u1`".
    pub list: String,
}

/// Every trailing comma of `src` in a list Vivado reads without it.
pub fn trailing_commas(src: &str) -> Vec<TrailingComma> {
    let (t, _) = tokenize(src);
    let ident = |k: Option<usize>| match k.and_then(|k| t.get(k)).map(|t| &t.tok) {
        Some(Tok::Ident(w)) => Some(w.as_str()),
        _ => None,
    };
    let punct = |k: Option<usize>, c: char| k.and_then(|k| t.get(k)).is_some_and(|t| t.tok == Tok::Punct(c));
    let mut found = Vec::new();
    for k in 0..t.len().saturating_sub(1) {
        if !punct(Some(k), ',') || !punct(Some(k + 1), ')') {
            continue;
        }
        let Some(open) = group_open(&t, k + 1) else { continue };
        let before = open.checked_sub(1);
        let list = if punct(before, '#') {
            // `#(` of a module's parameters or of an instance's overrides.
            let name = before.and_then(|b| b.checked_sub(1));
            match (ident(name), ident(name.and_then(|n| n.checked_sub(1)))) {
                (Some(m), Some("module" | "macromodule")) => format!("the parameters of module `{m}`"),
                (Some(_), _) => match instance_name(&t, k + 1) {
                    Some(i) => format!("the parameters of `{i}`"),
                    None => continue,
                },
                _ => continue,
            }
        } else if let Some(header) = module_of_ports(&t, open) {
            format!("the ports of module `{header}`")
        } else if let (Some(name), Some(_)) = (ident(before), instance_type(&t, before)) {
            if !punct(Some(open + 1), '.') {
                continue; // positional: an empty last connection is an open port
            }
            format!("the port connections of `{name}`")
        } else {
            continue;
        };
        let c = &t[k];
        found.push(TrailingComma { at: c.at, line: c.line, col: c.col, list });
    }
    found
}

/// The module whose port list opens at `open`: `module m (` or `module m #(...) (`.
fn module_of_ports(t: &[Token], open: usize) -> Option<String> {
    let mut k = open.checked_sub(1)?;
    if t[k].tok == Tok::Punct(')') {
        let params = group_open(t, k)?;
        if params == 0 || t[params - 1].tok != Tok::Punct('#') {
            return None;
        }
        k = params.checked_sub(2)?;
    }
    match (&t[k].tok, &t.get(k.checked_sub(1)?)?.tok) {
        (Tok::Ident(name), Tok::Ident(kw)) if kw == "module" || kw == "macromodule" => Some(name.clone()),
        _ => None,
    }
}

/// With `name` on an instance's name, its module's name: `type name (` or `type #(...) name (`.
fn instance_type(t: &[Token], name: Option<usize>) -> Option<String> {
    let k = name?.checked_sub(1)?;
    let ty = match t[k].tok {
        Tok::Punct(')') => group_open(t, k)?.checked_sub(2)?,
        _ => k,
    };
    match &t[ty].tok {
        Tok::Ident(w) if !is_keyword(w) && !w.starts_with('$') => Some(w.clone()),
        _ => None,
    }
}

/// With `close` on the `)` of an instance's `#(...)`, the instance's name after it.
fn instance_name(t: &[Token], close: usize) -> Option<String> {
    match (&t.get(close + 1)?.tok, &t.get(close + 2)?.tok) {
        (Tok::Ident(name), Tok::Punct('(')) => Some(name.clone()),
        _ => None,
    }
}

/// Words before a name and a `(` that make no instance (`assign x (`, `always @ (`...).
fn is_keyword(w: &str) -> bool {
    matches!(
        w,
        "module"
            | "macromodule"
            | "assign"
            | "always"
            | "initial"
            | "if"
            | "else"
            | "case"
            | "casex"
            | "casez"
            | "for"
            | "while"
            | "repeat"
            | "function"
            | "task"
            | "begin"
            | "end"
            | "wire"
            | "reg"
            | "input"
            | "output"
            | "inout"
            | "parameter"
            | "localparam"
            | "return"
            | "posedge"
            | "negedge"
            | "or"
            | "and"
            | "not"
            | "generate"
            | "genvar"
            | "integer"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positional_lists_calls_and_tasks_keep_their_commas() {
        for text in [
            "module t;\n  sub u (a, b, );\nendmodule\n",
            "module t;\n  initial $display(\"x\", );\n  wire y = f(a, );\nendmodule\n",
            "module t;\n  sub u [1:0] (.a(a), );\nendmodule\n",
        ] {
            assert!(trailing_commas(text).is_empty(), "{text}: {:?}", trailing_commas(text));
        }
    }

    #[test]
    fn a_header_with_parameters_and_an_instance_with_overrides() {
        let text = "module m #(parameter W = 4,) (input [W-1:0] a, output b,);\n  sub #(.N(2)) s (.x(a), .y(b), );\nendmodule\n";
        let lists: Vec<String> = trailing_commas(text).into_iter().map(|c| c.list).collect();
        assert_eq!(lists, ["the parameters of module `m`", "the ports of module `m`", "the port connections of `s`"]);
    }
}
