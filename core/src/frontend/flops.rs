//! Flip-flops written with blocking assignments: `always @(posedge clk) DataOut = ...;`, as
//! the course's BotSim 3.1 world interface writes its read mux. Vivado builds a flip-flop for
//! such a variable when its block does not read it after writing it, and every other block
//! reads the flip-flop as it was before the clock edge. In Verilog the same text is a race:
//! a block that reads the variable at the same edge (the KCPSM6 taking `in_port`) may see
//! the old value or the new one, as the simulator orders the two, and botsim's boards order
//! them differently (the RTL core beside the instruction-set simulator). botsim simulates
//! what Vivado builds: such a variable's blocking assignments become non-blocking ones.
//!
//! A variable qualifies when all of this holds in its module:
//! - every assignment to it outside `initial` blocks is a blocking one in one clocked block
//!   (`always @(posedge ...)` or `negedge`, a `begin`/`end` body without loops, delays or
//!   event controls), each a statement of its own (`x = ...;`, `x[3:0] = ...;`);
//! - that block reads it only before its first write ends (`x = x + 1;` reads the old value
//!   either way).
//!
//! ```
//! use botsim_core::frontend::flops::blocking_flops;
//! let text = "module m(input clk, input [1:0] a, output reg [7:0] q, output reg [7:0] n);\n  reg [7:0] t;\n  always @(posedge clk) begin\n    case (a)\n      2'd0: q = 8'h55;\n      default: q = 8'h00;\n    endcase\n    t = q + 1;\n    n = n + 1;\n  end\nendmodule\n";
//! let found = blocking_flops(text, 0..text.len());
//! // q is read after its write (by `t = q + 1`), t is read nowhere but written: t and n qualify.
//! let names: Vec<&str> = found.iter().map(|f| f.name.as_str()).collect();
//! assert_eq!(names, ["t", "n"]);
//! assert_eq!(found[0].line, 8);
//! ```

use std::collections::BTreeMap;
use std::ops::Range;

use super::scan::{group_close, group_open, tokenize, Tok, Token};

/// A variable of a clocked block whose blocking assignments Vivado builds as a flip-flop.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlockingFlop {
    pub name: String,
    /// Where its first write is (1-based).
    pub line: u32,
    pub col: u32,
    /// The byte offset of each of its assignments' `=`.
    pub writes: Vec<usize>,
}

/// What ends a statement, so that a name after it starts the next one.
const STATEMENT_STARTS: &[&str] = &["begin", "end", "else", "endcase", "default"];

/// What a block must not hold for its order to be the text's order.
const UNORDERED: &[&str] = &["for", "while", "repeat", "forever", "fork", "disable", "wait", "task", "function"];

/// The variables of the module at `span` of `text` whose blocking assignments are flip-flops.
pub fn blocking_flops(text: &str, span: Range<usize>) -> Vec<BlockingFlop> {
    let (all, _) = tokenize(text);
    // The module's tokens (in the order of the text: a run of them).
    let from = all.partition_point(|t| t.at < span.start);
    let to = all.partition_point(|t| t.at < span.end);
    let t: &[Token] = &all[from..to];
    let ident = |k: usize| match t.get(k).map(|t| &t.tok) {
        Some(Tok::Ident(w)) => Some(w.as_str()),
        _ => None,
    };
    let punct = |k: usize, c: char| t.get(k).is_some_and(|t| t.tok == Tok::Punct(c));

    // The clocked blocks' bodies and the initial blocks, as token ranges.
    let mut clocked: Vec<Range<usize>> = Vec::new();
    let mut initial: Vec<Range<usize>> = Vec::new();
    let mut k = 0;
    while k < t.len() {
        match ident(k) {
            Some("always" | "always_ff") if punct(k + 1, '@') && punct(k + 2, '(') => {
                let close = group_close(t, k + 2);
                let edge = (k + 3..close).any(|j| matches!(ident(j), Some("posedge" | "negedge")));
                let body = close + 1;
                if ident(body) == Some("begin") {
                    let end = begin_end(t, body);
                    if edge {
                        clocked.push(body..end);
                    }
                    k = end;
                    continue;
                }
            }
            Some("initial") => {
                let end = if ident(k + 1) == Some("begin") { begin_end(t, k + 1) } else { statement_end(t, k + 1) };
                initial.push(k..end);
                k = end;
                continue;
            }
            _ => {}
        }
        k += 1;
    }

    // Every `=` of an assignment (not of `==`, `!=`, `>=`, `<=` as a comparison), and each
    // whose target starts a statement: (name, its token, the `=`, blocking?).
    let mut assignments: Vec<usize> = Vec::new();
    let mut targets: Vec<(&str, usize, usize, bool)> = Vec::new();
    for k in 0..t.len() {
        if !punct(k, '=') || punct(k + 1, '=') {
            continue;
        }
        let before = |c: char| k > 0 && punct(k - 1, c);
        if before('>') || before('!') || before('=') {
            continue;
        }
        let blocking = !before('<');
        if blocking {
            assignments.push(k);
        }
        // Back over the target's selects: `x[3:0]`, `mem[a][b]`.
        let mut j = if blocking { k } else { k - 1 };
        while j > 0 && punct(j - 1, ']') {
            j = group_open(t, j - 1).unwrap_or(0);
        }
        let Some(name) = j.checked_sub(1).and_then(ident) else { continue };
        let starts = j < 2
            || punct(j - 2, ';')
            || punct(j - 2, ')')
            || punct(j - 2, ':')
            || ident(j - 2).is_some_and(|w| STATEMENT_STARTS.contains(&w) || w == "assign");
        if starts {
            targets.push((name, j - 1, k, blocking));
        }
    }

    let mut found = Vec::new();
    for body in &clocked {
        if (body.start..body.end)
            .any(|j| ident(j).is_some_and(|w| UNORDERED.contains(&w)) || punct(j, '#') || punct(j, '@'))
        {
            continue;
        }
        let mut writes: BTreeMap<&str, Vec<(usize, usize)>> = BTreeMap::new();
        for &(name, at, eq, blocking) in &targets {
            if blocking && body.contains(&at) {
                writes.entry(name).or_default().push((at, eq));
            }
        }
        // A blocking assignment whose target is not a name (`{a, b} = ...`, `x.y = ...`):
        // the block is left as written.
        let named = writes.values().map(Vec::len).sum::<usize>();
        if assignments.iter().filter(|&&k| body.contains(&k)).count() != named {
            continue;
        }
        for (name, w) in writes {
            let elsewhere = targets.iter().any(|&(n, at, _, blocking)| {
                n == name && !initial.iter().any(|r| r.contains(&at)) && !(blocking && body.contains(&at))
            });
            if elsewhere {
                continue;
            }
            let first_end = statement_end(t, w[0].1);
            let read_late = (body.start..body.end)
                .any(|j| ident(j) == Some(name) && j >= first_end && !w.iter().any(|&(at, _)| at == j));
            if read_late {
                continue;
            }
            let first = &t[w[0].0];
            found.push(BlockingFlop {
                name: name.to_string(),
                line: first.line,
                col: first.col,
                writes: w.iter().map(|&(_, eq)| t[eq].at).collect(),
            });
        }
    }
    found.sort_by_key(|f| f.writes[0]);
    found
}

/// With `begin` at `k`, the index just past its `end`.
fn begin_end(t: &[Token], k: usize) -> usize {
    let mut depth = 0i32;
    for (j, tok) in t.iter().enumerate().skip(k) {
        match &tok.tok {
            Tok::Ident(w) if w == "begin" => depth += 1,
            Tok::Ident(w) if w == "end" => {
                depth -= 1;
                if depth == 0 {
                    return j + 1;
                }
            }
            _ => {}
        }
    }
    t.len()
}

/// The index just past the `;` that ends the statement at `k` (outside brackets).
fn statement_end(t: &[Token], k: usize) -> usize {
    let mut depth = 0i32;
    for (j, tok) in t.iter().enumerate().skip(k) {
        match tok.tok {
            Tok::Punct('(' | '[' | '{') => depth += 1,
            Tok::Punct(')' | ']' | '}') => depth -= 1,
            Tok::Punct(';') if depth <= 0 => return j + 1,
            _ => {}
        }
    }
    t.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(text: &str) -> Vec<String> {
        blocking_flops(text, 0..text.len()).into_iter().map(|f| f.name).collect()
    }

    #[test]
    fn a_read_mux_of_blocking_assignments_is_a_flop() {
        let text = "module w(input clk, input [3:0] a, output reg [7:0] d);\n  always @(posedge clk) begin\n    case (a[3:0])\n      4'b0000 : d = 8'h01;\n      4'b1000 : d = 8'b01010101;\n    endcase\n  end\nendmodule\n";
        let f = blocking_flops(text, 0..text.len());
        assert_eq!(f.len(), 1);
        assert_eq!((f[0].name.as_str(), f[0].line, f[0].col), ("d", 4, 17));
        assert_eq!(f[0].writes.len(), 2);
        assert!(f[0].writes.iter().all(|&at| &text[at..at + 1] == "="));
    }

    #[test]
    fn what_is_not_a_flop_of_blocking_assignments_is_left_alone() {
        // Read after its write in the block (a temporary), a comparison, a non-blocking
        // assignment elsewhere, a loop, a combinational block, a reset assignment elsewhere.
        let cases = [
            "module m(input clk, input a, output reg q);\n  reg t;\n  always @(posedge clk) begin\n    t = a;\n    q <= t;\n  end\nendmodule\n",
            "module m(input clk, input a, output reg q);\n  always @(posedge clk) begin\n    if (a == 1'b1) q <= 1'b0;\n  end\nendmodule\n",
            "module m(input clk, input rst, input a, output reg q);\n  always @(posedge clk) begin\n    q = a;\n  end\n  always @(posedge rst) begin\n    q <= 1'b0;\n  end\nendmodule\n",
            "module m(input clk, input [3:0] a, output reg [3:0] q);\n  integer i;\n  always @(posedge clk) begin\n    for (i = 0; i < 4; i = i + 1) q[i] = a[i];\n  end\nendmodule\n",
            "module m(input a, output reg q);\n  always @(*) begin\n    q = a;\n  end\nendmodule\n",
            "module m(input clk, input a, output reg q);\n  always @(posedge clk) begin\n    q = a;\n  end\n  always @(posedge clk) begin\n    q = 1'b0;\n  end\nendmodule\n",
            "module m(input clk, input [1:0] a, output reg q, output reg r);\n  always @(posedge clk) begin\n    r = 1'b0;\n    {q, r} = a;\n  end\nendmodule\n",
        ];
        for text in cases {
            assert!(names(text).is_empty(), "{text}: {:?}", names(text));
        }
    }

    #[test]
    fn an_initial_value_and_a_read_before_the_write_keep_a_flop() {
        let text = "module m(input clk, output reg [7:0] n);\n  initial begin\n    n = 8'd0;\n  end\n  always @(posedge clk) begin\n    if (n == 8'd9) n = 8'd0;\n    else n = n + 8'd1;\n  end\nendmodule\n";
        // `n == 8'd9` reads it before the first write ends? No: the `if` is before it, so
        // the read comes first; the `else` branch's read comes after the first write's end.
        assert!(names(text).is_empty(), "{:?}", names(text));
        let text = "module m(input clk, output reg [7:0] n);\n  initial n = 8'd0;\n  always @(posedge clk) begin\n    n = n + 8'd1;\n  end\nendmodule\n";
        assert_eq!(names(text), ["n"]);
    }
}
