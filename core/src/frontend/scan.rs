//! A structural scanner for Verilog: the modules of a file, their ports, parameters and the
//! instances they contain, with the line and column of each. It reads what board
//! simulation needs to plan a build (which modules exist, which is the top, what to replace,
//! how the top's pins are named); Verilator reads the design itself.
//!
//! It skips comments, strings and compiler directives, and tolerates what it does not
//! understand: a construct it cannot read is simply not reported.
//!
//! ```
//! use botsim_core::frontend::scan::scan;
//! let src = "module top(input wire clk, output wire [7:0] led);\n  blink #(.N(3)) u1 (.clk(clk), .q(led));\nendmodule\n";
//! let modules = scan(src);
//! assert_eq!(modules[0].name, "top");
//! assert_eq!(modules[0].ports[1].name, "led");
//! assert_eq!(modules[0].ports[1].width, 8);
//! assert_eq!(modules[0].instances[0].module, "blink");
//! assert_eq!(modules[0].instances[0].connections[1], ("q".to_string(), "led".to_string()));
//! ```

use std::ops::Range;

/// A port direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dir {
    Input,
    Output,
    Inout,
}

/// A port of a module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Port {
    pub name: String,
    pub dir: Dir,
    /// Width in bits when the range is two integer constants, else 1 (or 0 when unknown).
    pub width: u32,
    /// The declared range, `msb:lsb`, when it was two integer constants.
    pub range: Option<(i64, i64)>,
    /// 1-based line and column of its name in its direction's declaration.
    pub line: u32,
    pub col: u32,
}

/// An instance of a module (or primitive) inside another module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Instance {
    pub module: String,
    pub name: String,
    /// 1-based line and column of the module name.
    pub line: u32,
    pub col: u32,
    /// Named connections `(port, expression)`; positional ones are named `#0`, `#1`...
    pub connections: Vec<(String, String)>,
    /// The bytes of each connection's expression in the source, in the order of
    /// `connections` (empty where it is empty or implicit).
    pub spans: Vec<Range<usize>>,
    /// Parameter overrides `(name, value)`; positional ones are named `#0`...
    pub params: Vec<(String, String)>,
    /// It stands inside a `begin`/`end`, a generate region or after an `if`, `else`, `for`
    /// or `case`: one of several alternatives (a generate branch), or repeated.
    pub guarded: bool,
    /// The instance has no name in the source (`bot (.clk(clk), ...);`, which Vivado
    /// accepts and names itself): `name` is botsim's, to be written at this byte of the text.
    pub unnamed_at: Option<usize>,
}

/// One module of a source file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Module {
    pub name: String,
    /// 1-based line and column of the name.
    pub line: u32,
    pub col: u32,
    /// Bytes of the source from `module` to the end of `endmodule`.
    pub span: Range<usize>,
    pub params: Vec<String>,
    pub ports: Vec<Port>,
    pub instances: Vec<Instance>,
    /// Nothing but port and parameter declarations: a black box (a synthesis stub such as
    /// Vivado's `<ip>_stub.v`), which declares a module without defining it.
    pub empty: bool,
    /// It has no `endmodule`: the file ends, or another module begins, before it does (a
    /// file cut short). Its span and instances end there.
    pub unterminated: bool,
    /// Its net and variable declarations (`wire [7:0] a, b;`), each name with its range.
    pub nets: Vec<Net>,
    /// Its continuous assignments to a whole net (`assign a = ...;`).
    pub assigns: Vec<Assign>,
    /// The byte just past the `;` that ends its header, where a declaration may go.
    pub header_end: usize,
    /// Something the scanner cannot read as Verilog where it looked (a keyword where a
    /// port's name should be: a stray `endmodule` in the port list): line, column, what.
    pub unreadable: Option<(u32, u32, String)>,
}

/// A net or variable declared in a module's body.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Net {
    pub name: String,
    /// Its range as written (`[W-1:0]`), if any.
    pub range: Option<String>,
    /// The byte just past the `;` that ends its declaration.
    pub end: usize,
}

/// `assign NAME = ...;`: a continuous assignment to a whole net, outside any generate branch
/// or loop.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Assign {
    pub target: String,
    /// The bytes of the target's name in the source.
    pub at: Range<usize>,
    pub line: u32,
    pub col: u32,
    /// The right-hand side has a `z` literal (a tri-state driver).
    pub tristate: bool,
}

impl Module {
    /// Every byte position the module holds moved by `f` (the text was edited before them).
    pub fn shift(&mut self, f: &dyn Fn(usize) -> usize) {
        let range = |r: &mut Range<usize>| *r = f(r.start)..f(r.end);
        range(&mut self.span);
        self.header_end = f(self.header_end);
        for i in &mut self.instances {
            i.spans.iter_mut().for_each(range);
            i.unnamed_at = i.unnamed_at.map(f);
        }
        self.nets.iter_mut().for_each(|n| n.end = f(n.end));
        self.assigns.iter_mut().for_each(|a| range(&mut a.at));
    }

    /// The port named `name`, if any.
    pub fn port(&self, name: &str) -> Option<&Port> {
        self.ports.iter().find(|p| p.name == name)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Tok {
    Ident(String),
    Num(String),
    Str,
    Punct(char),
}

#[derive(Clone, Debug)]
pub(crate) struct Token {
    pub(crate) tok: Tok,
    pub(crate) at: usize,
    pub(crate) line: u32,
    pub(crate) col: u32,
}

/// Words that start something other than an instance.
const KEYWORDS: &[&str] = &[
    "always",
    "always_comb",
    "always_ff",
    "always_latch",
    "and",
    "assign",
    "automatic",
    "begin",
    "buf",
    "case",
    "casex",
    "casez",
    "cmos",
    "deassign",
    "default",
    "defparam",
    "disable",
    "else",
    "end",
    "endcase",
    "endfunction",
    "endgenerate",
    "endmodule",
    "endtask",
    "event",
    "for",
    "force",
    "forever",
    "fork",
    "function",
    "generate",
    "genvar",
    "if",
    "initial",
    "inout",
    "input",
    "integer",
    "join",
    "localparam",
    "logic",
    "nand",
    "nor",
    "not",
    "or",
    "output",
    "parameter",
    "real",
    "realtime",
    "reg",
    "release",
    "repeat",
    "signed",
    "specify",
    "supply0",
    "supply1",
    "task",
    "time",
    "tri",
    "tri0",
    "tri1",
    "triand",
    "trior",
    "wait",
    "wand",
    "while",
    "wire",
    "wor",
    "xnor",
    "xor",
    "bit",
    "byte",
    "int",
    "shortint",
    "longint",
    "typedef",
    "enum",
    "struct",
    "unsigned",
    "var",
    "return",
    "import",
    "export",
    "unique",
    "priority",
    "bufif0",
    "bufif1",
    "notif0",
    "notif1",
    "pullup",
    "pulldown",
    "nmos",
    "pmos",
    "rnmos",
    "rpmos",
    "tran",
    "rtran",
];

/// A file a source names: an `` `include "..." `` or a `$readmemh`/`$readmemb` file name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileRef {
    pub kind: RefKind,
    pub name: String,
    /// The string literal's bytes, quotes included.
    pub at: Range<usize>,
    pub line: u32,
    pub col: u32,
}

/// What names the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefKind {
    Include,
    /// `$readmemh` or `$readmemb`.
    Readmem,
}

/// The files a source names, in order: includes and the literal file names of `$readmemh`
/// and `$readmemb` (comments skipped).
///
/// ```
/// use botsim_core::frontend::scan::{file_references, RefKind};
/// let src = "`include \"defs.vh\"\n// $readmemh(\"old.mem\", m);\ninitial $readmemh( \"icon.mem\", rom);\n";
/// let r = file_references(src);
/// assert_eq!((r[0].kind, r[0].name.as_str(), r[0].line), (RefKind::Include, "defs.vh", 1));
/// assert_eq!((r[1].kind, r[1].name.as_str(), r[1].line, r[1].col), (RefKind::Readmem, "icon.mem", 3, 20));
/// assert_eq!(&src[r[1].at.clone()], "\"icon.mem\"");
/// ```
pub fn file_references(src: &str) -> Vec<FileRef> {
    let (tokens, mut refs) = tokenize(src);
    for (k, t) in tokens.iter().enumerate() {
        let Tok::Ident(w) = &t.tok else { continue };
        if w != "$readmemh" && w != "$readmemb" {
            continue;
        }
        let (Some(open), Some(lit)) = (tokens.get(k + 1), tokens.get(k + 2)) else { continue };
        if open.tok != Tok::Punct('(') || lit.tok != Tok::Str {
            continue;
        }
        let end = src[lit.at + 1..].find('"').map_or(src.len(), |e| lit.at + 1 + e + 1);
        let name = src[lit.at + 1..end.saturating_sub(1)].to_string();
        refs.push(FileRef { kind: RefKind::Readmem, name, at: lit.at..end, line: lit.line, col: lit.col });
    }
    refs.sort_by_key(|r| r.at.start);
    refs
}

/// With `open` on a `(`, `[` or `{` of `t`, the index of its match (`t.len()` if none).
pub(crate) fn group_close(t: &[Token], open: usize) -> usize {
    let mut depth = 0i32;
    for (j, tok) in t.iter().enumerate().skip(open) {
        match tok.tok {
            Tok::Punct('(' | '[' | '{') => depth += 1,
            Tok::Punct(')' | ']' | '}') => {
                depth -= 1;
                if depth == 0 {
                    return j;
                }
            }
            _ => {}
        }
    }
    t.len()
}

/// With `close` on a `)`, `]` or `}` of `t`, the index of its match, if it has one.
pub(crate) fn group_open(t: &[Token], close: usize) -> Option<usize> {
    let mut depth = 0i32;
    for j in (0..=close).rev() {
        match t[j].tok {
            Tok::Punct(')' | ']' | '}') => depth += 1,
            Tok::Punct('(' | '[' | '{') => {
                depth -= 1;
                if depth == 0 {
                    return Some(j);
                }
            }
            _ => {}
        }
    }
    None
}

pub(crate) fn tokenize(src: &str) -> (Vec<Token>, Vec<FileRef>) {
    let b = src.as_bytes();
    let (mut i, mut line, mut line_start) = (0usize, 1u32, 0usize);
    let mut out = Vec::new();
    let mut includes = Vec::new();
    let mut at_line_start = true;
    while i < b.len() {
        let c = b[i];
        if c == b'\n' {
            i += 1;
            line += 1;
            line_start = i;
            at_line_start = true;
            continue;
        }
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let col = (i - line_start + 1) as u32;
        let start = i;
        if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            continue;
        }
        if c == b'/' && b.get(i + 1) == Some(&b'*') {
            i += 2;
            while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b'/')) {
                if b[i] == b'\n' {
                    line += 1;
                    line_start = i + 1;
                }
                i += 1;
            }
            i = (i + 2).min(b.len());
            continue;
        }
        // An attribute, `(* X_INTERFACE_INFO = "..." *)` (Vivado's IP wrappers put them before
        // their port declarations): as a comment. `@(*)` (or `@(* )`) is no attribute: its `*`
        // is followed by the `)` (the `*)` of a later one must not take it for one's start).
        let attribute = c == b'('
            && b.get(i + 1) == Some(&b'*')
            && !src[i + 2..].trim_start().starts_with(')')
            && src[i + 2..].find("*)").is_some_and(|end| !src[i + 2..i + 2 + end].trim().is_empty());
        if attribute {
            i += 2;
            while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b')')) {
                if b[i] == b'\n' {
                    line += 1;
                    line_start = i + 1;
                }
                i += 1;
            }
            i = (i + 2).min(b.len());
            continue;
        }
        let was_line_start = at_line_start;
        at_line_start = false;
        if c == b'`' {
            // A directive: `define takes the rest of the line (with continuations); others
            // (`timescale, `include, `ifdef...) the line; a macro use is one token.
            let mut j = i + 1;
            while j < b.len() && (b[j].is_ascii_alphanumeric() || b[j] == b'_') {
                j += 1;
            }
            let word = &src[i + 1..j];
            let directive = matches!(
                word,
                "define"
                    | "undef"
                    | "timescale"
                    | "include"
                    | "ifdef"
                    | "ifndef"
                    | "else"
                    | "elsif"
                    | "endif"
                    | "default_nettype"
                    | "resetall"
                    | "celldefine"
                    | "endcelldefine"
                    | "line"
            );
            if directive && (was_line_start || word != "else") {
                let takes_line = !matches!(word, "else" | "endif" | "celldefine" | "endcelldefine" | "resetall");
                i = j;
                if word == "include" {
                    let line_end = src[j..].find('\n').map_or(src.len(), |e| j + e);
                    if let Some(q) = src[j..line_end].find('"').map(|q| j + q) {
                        if let Some(e) = src[q + 1..line_end].find('"').map(|e| q + 1 + e) {
                            let col = (q - line_start + 1) as u32;
                            let name = src[q + 1..e].to_string();
                            includes.push(FileRef { kind: RefKind::Include, name, at: q..e + 1, line, col });
                        }
                    }
                }
                if takes_line {
                    while i < b.len() && b[i] != b'\n' {
                        if b[i] == b'\\' && b.get(i + 1) == Some(&b'\n') {
                            i += 1;
                            line += 1;
                            line_start = i + 1;
                        }
                        i += 1;
                    }
                }
            } else {
                i = j;
                out.push(Token { tok: Tok::Ident(src[start..j].to_string()), at: start, line, col });
            }
            continue;
        }
        if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i = (i + 1).min(b.len());
            out.push(Token { tok: Tok::Str, at: start, line, col });
            continue;
        }
        if c == b'\\' {
            while i < b.len() && !b[i].is_ascii_whitespace() {
                i += 1;
            }
            out.push(Token { tok: Tok::Ident(src[start + 1..i].to_string()), at: start, line, col });
            continue;
        }
        if c.is_ascii_alphabetic() || c == b'_' || c == b'$' {
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'$') {
                i += 1;
            }
            out.push(Token { tok: Tok::Ident(src[start..i].to_string()), at: start, line, col });
            continue;
        }
        if c.is_ascii_digit() || c == b'\'' {
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'\'' || b[i] == b'.') {
                i += 1;
            }
            out.push(Token { tok: Tok::Num(src[start..i].to_string()), at: start, line, col });
            continue;
        }
        // Multi-byte UTF-8 outside comments and strings: skip the whole character.
        let len = src[i..].chars().next().map_or(1, char::len_utf8);
        out.push(Token { tok: Tok::Punct(c as char), at: start, line, col });
        i += len;
    }
    (out, includes)
}

struct Parser<'a> {
    src: &'a str,
    t: Vec<Token>,
    i: usize,
    /// The first thing the module being read has that does not parse where the scanner
    /// looked (see [`Module::unreadable`]).
    trouble: Option<(u32, u32, String)>,
}

impl Parser<'_> {
    /// The identifier at token `k`, if it is one.
    fn ident_at(&self, k: usize) -> Option<&str> {
        match self.t.get(k).map(|t| &t.tok) {
            Some(Tok::Ident(w)) => Some(w.as_str()),
            _ => None,
        }
    }

    /// An instance's group `(`..`)` from `open` to `end` that holds a `;`: its `)` is
    /// missing (or a line was pasted in twice), and what follows it is lost to the instance.
    fn unclosed(&mut self, inst: &Token, module: &str, open: usize, end: usize) {
        if self.trouble.is_some() {
            return;
        }
        if let Some(semi) = self.t[open..end.min(self.t.len())].iter().find(|t| t.tok == Tok::Punct(';')) {
            self.trouble = Some((
                inst.line,
                inst.col,
                format!(
                    "the `(` of this `{module}` does not close before the `;` at line {}: this does not parse",
                    semi.line
                ),
            ));
        }
    }

    fn peek(&self, k: usize) -> Option<&Tok> {
        self.t.get(self.i + k).map(|t| &t.tok)
    }
    fn ident(&self, k: usize) -> Option<&str> {
        match self.peek(k) {
            Some(Tok::Ident(s)) => Some(s),
            _ => None,
        }
    }
    fn is(&self, k: usize, c: char) -> bool {
        self.peek(k) == Some(&Tok::Punct(c))
    }
    /// With the cursor on an opening bracket, the index just past its match.
    fn skip_group(&self, from: usize) -> usize {
        let mut depth = 0i32;
        let mut j = from;
        while j < self.t.len() {
            match self.t[j].tok {
                Tok::Punct('(') | Tok::Punct('[') | Tok::Punct('{') => depth += 1,
                Tok::Punct(')') | Tok::Punct(']') | Tok::Punct('}') => {
                    depth -= 1;
                    if depth == 0 {
                        return j + 1;
                    }
                }
                _ => {}
            }
            j += 1;
        }
        j
    }
    /// The source text of tokens `[from, to)`.
    fn text(&self, from: usize, to: usize) -> String {
        if from >= to || to > self.t.len() {
            return String::new();
        }
        // From the first token to the end of the last: a comment before the next token (or
        // between these) is no part of the text (`.instruction(instruction /* x */)`).
        let last = &self.t[to - 1];
        let end = last.at + token_len(self.src, last);
        let s = without_comments(&self.src[self.t[from].at..end]);
        s.split_whitespace().collect::<Vec<_>>().join(" ")
    }
}

/// Scan one source text.
pub fn scan(src: &str) -> Vec<Module> {
    let (t, _) = tokenize(src);
    let mut p = Parser { src, t, i: 0, trouble: None };
    let mut modules: Vec<Module> = Vec::new();
    while p.i < p.t.len() {
        if matches!(p.ident(0), Some("module" | "macromodule")) {
            if let Some(m) = module(&mut p) {
                modules.push(m);
                continue;
            }
        }
        // Other design units (a UDP, a SystemVerilog package...): skipped whole.
        if let Some(end) = p.ident(0).and_then(|w| {
            ["primitive", "interface", "program", "checker", "class", "package", "config"]
                .contains(&w)
                .then(|| format!("end{w}"))
        }) {
            while p.i < p.t.len() && p.ident(0) != Some(end.as_str()) {
                p.i += 1;
            }
            p.i += 1;
            continue;
        }
        // What only a module holds, outside any: an `endmodule` ended the one before early.
        if let (Some(last), Some(word)) = (modules.last_mut(), p.ident(0)) {
            let item = matches!(
                word,
                "always" | "assign" | "initial" | "wire" | "reg" | "input" | "output" | "inout" | "endmodule" | "begin"
            ) || (p.ident(1).is_some()
                && !KEYWORDS.contains(&word)
                && !word.starts_with('`')
                && p.is(2, '('));
            if item && last.unreadable.is_none() && !last.unterminated {
                let t = &p.t[p.i];
                let ended =
                    p.t[..p.i].iter().rev().find(|t| t.tok == Tok::Ident("endmodule".into())).map_or(0, |t| t.line);
                last.unreadable = Some((
                    t.line,
                    t.col,
                    format!(
                        "`{word}` is outside any module: the `endmodule` at line {ended} ends `{}` before it; this does not parse",
                        last.name
                    ),
                ));
            }
        }
        p.i += 1;
    }
    modules
}

/// One module, from its `module` keyword: its header, then its body item by item, up to
/// its `endmodule` (or where a file cut short ends it).
fn module(p: &mut Parser) -> Option<Module> {
    let start = p.t[p.i].at;
    p.i += 1;
    let name_tok = p.t.get(p.i)?.clone();
    let name = p.ident(0)?.to_string();
    p.i += 1;
    let mut header = header(p);
    let extent = extent(p);
    p.i = extent.body_start;
    let body = Body::read(p, extent.body_end, &mut header);
    p.i = if extent.unterminated { extent.body_end } else { extent.body_end + 1 };
    let Header { params, mut ports, port_order, end: header_end } = header;
    // Keep the declared order of a non-ANSI port list.
    if !port_order.is_empty() {
        ports.sort_by_key(|pt: &Port| port_order.iter().position(|n| *n == pt.name).unwrap_or(usize::MAX));
        ports.retain(|pt| port_order.contains(&pt.name));
    }
    let unreadable = ports
        .iter()
        .find(|pt| KEYWORDS.contains(&pt.name.as_str()))
        .map(|pt| (pt.line, pt.col, format!("`{}` where a port's name should be: this does not parse", pt.name)))
        .or(p.trouble.take());
    Some(Module {
        name,
        line: name_tok.line,
        col: name_tok.col,
        span: start..extent.end,
        params,
        ports,
        empty: !body.logic && body.instances.is_empty(),
        instances: body.instances,
        unterminated: extent.unterminated,
        nets: body.nets,
        assigns: body.assigns,
        header_end,
        unreadable,
    })
}

/// A module's header: its parameters (`#(...)`, and later `parameter`s of its body), its
/// ports (and the order a non-ANSI list names them in), the byte past its `;`.
struct Header {
    params: Vec<String>,
    ports: Vec<Port>,
    port_order: Vec<String>,
    end: usize,
}

fn header(p: &mut Parser) -> Header {
    let mut h = Header { params: Vec::new(), ports: Vec::new(), port_order: Vec::new(), end: p.src.len() };
    if p.is(0, '#') && p.is(1, '(') {
        let end = p.skip_group(p.i + 1);
        h.params.extend(param_names(p, p.i + 2, end - 1));
        p.i = end;
    }
    if p.is(0, '(') {
        let end = p.skip_group(p.i);
        ansi_ports(p, p.i + 1, end - 1, &mut h.ports, &mut h.port_order);
        p.i = end;
    }
    h.end = match p.t.get(p.i) {
        Some(t) if t.tok == Tok::Punct(';') => t.at + 1,
        Some(t) => t.at,
        None => p.src.len(),
    };
    h
}

/// Where a module's body is: from the token after its header to its `endmodule` (token
/// indices), or, in a file cut short, to the next `module` or the end of the file; `end`
/// is the byte past the module.
struct Extent {
    body_start: usize,
    body_end: usize,
    unterminated: bool,
    end: usize,
}

fn extent(p: &Parser) -> Extent {
    let body_start = p.i;
    let is_end = |t: &Token| t.tok == Tok::Ident("endmodule".into());
    let is_next = |t: &Token| matches!(&t.tok, Tok::Ident(w) if w == "module" || w == "macromodule");
    let body_end = (body_start..p.t.len()).find(|&j| is_end(&p.t[j]) || is_next(&p.t[j])).unwrap_or(p.t.len());
    let unterminated = !p.t.get(body_end).is_some_and(is_end);
    let end = match p.t.get(body_end) {
        Some(t) if unterminated => t.at,
        Some(t) => t.at + "endmodule".len(),
        None => p.src.len(),
    };
    Extent { body_start, body_end, unterminated, end }
}

/// What the token at a body's cursor starts, as the body reader acts on it.
enum Item {
    /// `;`: the statement ends.
    Semicolon,
    /// `input`/`output`/`inout` at a statement's start: a non-ANSI port declaration.
    PortDeclaration(Dir),
    /// `wire`/`reg`/`logic`/`tri` at a statement's start.
    NetDeclaration,
    /// `parameter` (true) or `localparam` (false) at a statement's start.
    Parameter(bool),
    /// A name then `#(`, `(`, or a name and `(`/`[`, at a statement's start.
    Instance,
    /// `begin`, `else`, `generate`, `end`, `endgenerate`, `endcase`, `endfunction`, `endtask`.
    Block,
    /// `assign` (true), `always`..., `initial`, `function`, `task`: logic of its own.
    Process(bool),
    /// `=`: an assignment, logic of its own.
    Equals,
    /// `if`, `for`, `case` (true): what follows is one alternative, or repeated.
    Condition(bool),
    /// `(`, `[`, `{`: a group skipped whole.
    Group,
    Other,
}

impl Item {
    fn at(p: &Parser, stmt_start: bool) -> Item {
        let word = match p.peek(0) {
            Some(Tok::Punct(';')) => return Item::Semicolon,
            Some(Tok::Punct('=')) => return Item::Equals,
            Some(Tok::Punct('(' | '[' | '{')) => return Item::Group,
            Some(Tok::Ident(w)) => w.as_str(),
            _ => return Item::Other,
        };
        match word {
            "input" | "output" | "inout" if stmt_start => Item::PortDeclaration(direction(word)),
            "wire" | "reg" | "logic" | "tri" if stmt_start => Item::NetDeclaration,
            "parameter" | "localparam" if stmt_start => Item::Parameter(word == "parameter"),
            w if stmt_start
                && !KEYWORDS.contains(&w)
                && !w.starts_with('$')
                && !w.starts_with('`')
                && (p.is(1, '#') || p.is(1, '(') || (p.ident(1).is_some() && (p.is(2, '(') || p.is(2, '[')))) =>
            {
                Item::Instance
            }
            "begin" | "else" | "generate" | "end" | "endgenerate" | "endcase" | "endfunction" | "endtask" => {
                Item::Block
            }
            "assign" | "always" | "always_ff" | "always_comb" | "always_latch" | "initial" | "function" | "task" => {
                Item::Process(word == "assign")
            }
            "if" | "for" | "case" => Item::Condition(word == "case"),
            _ => Item::Other,
        }
    }
}

/// A module's body as read so far.
struct Body {
    nets: Vec<Net>,
    assigns: Vec<Assign>,
    instances: Vec<Instance>,
    /// The cursor is at the start of a statement.
    stmt_start: bool,
    /// It has logic of its own (an assignment, a process): it is no black box.
    logic: bool,
    /// Inside `begin`/`end`, `generate` or `case` (`nest`), or in a statement after `if`,
    /// `else` or `for` (`guarded`): an item there is one alternative of several, or repeated.
    nest: i32,
    guarded: bool,
}

impl Body {
    /// Read the body from the cursor up to the token `body_end`; its port declarations and
    /// parameters go into the header.
    fn read(p: &mut Parser, body_end: usize, header: &mut Header) -> Body {
        let mut b = Body {
            nets: Vec::new(),
            assigns: Vec::new(),
            instances: Vec::new(),
            stmt_start: true,
            logic: false,
            nest: 0,
            guarded: false,
        };
        let semi = |p: &Parser| (p.i..body_end).find(|&k| p.t[k].tok == Tok::Punct(';')).unwrap_or(body_end);
        while p.i < body_end {
            // Each item either leaves the cursor where the next begins (`true`), or is one
            // token that is no statement's start.
            let placed = match Item::at(p, b.stmt_start) {
                Item::Semicolon => {
                    p.i += 1;
                    b.stmt_start = true;
                    b.guarded &= b.nest > 0;
                    true
                }
                Item::PortDeclaration(dir) => {
                    let end = semi(p);
                    non_ansi_ports(p, dir, p.i + 1, end, &mut header.ports);
                    p.i = end;
                    true
                }
                Item::NetDeclaration => {
                    b.net_declaration(p, semi(p));
                    true
                }
                Item::Parameter(named) => {
                    let end = semi(p);
                    if named {
                        header.params.extend(param_names(p, p.i, end));
                    }
                    p.i = end;
                    true
                }
                Item::Instance => {
                    let before = b.instances.len();
                    p.i = instance_statement(p, body_end, &mut b.instances);
                    let guarded = b.nest > 0 || b.guarded;
                    for i in &mut b.instances[before..] {
                        i.guarded = guarded;
                    }
                    true
                }
                Item::Block => {
                    b.block_word(p);
                    true
                }
                Item::Process(assign) => {
                    b.logic = true;
                    if assign && b.nest == 0 && !b.guarded {
                        b.whole_assign(p, semi(p));
                    }
                    false
                }
                Item::Equals => {
                    b.logic = true;
                    false
                }
                Item::Condition(case) => {
                    b.guarded = true;
                    b.nest += i32::from(case);
                    // generate if/for headers: skip the condition.
                    p.i += 1;
                    if p.is(0, '(') {
                        p.i = p.skip_group(p.i);
                    }
                    b.stmt_start = true;
                    true
                }
                Item::Group => {
                    p.i = p.skip_group(p.i);
                    b.stmt_start = false;
                    true
                }
                Item::Other => false,
            };
            if !placed {
                b.stmt_start = false;
                p.i += 1;
            }
        }
        b
    }

    /// `wire [7:0] a, b;`: its names with their range. A name, then another where a `,`,
    /// `=` or `;` should be (a stray `wire` before an instance), is said here, before the
    /// instance is lost.
    fn net_declaration(&mut self, p: &mut Parser, semi: usize) {
        let (names, range) = declared_names(p, p.i + 1, semi);
        let end = p.t.get(semi).map_or(p.src.len(), |t| t.at + 1);
        self.nets.extend(names.into_iter().map(|name| Net { name, range: range.clone(), end }));
        let mut k = p.i + 1;
        while let Some(t) = p.t.get(k) {
            match &t.tok {
                Tok::Ident(n) if NET_WORDS.contains(&n.as_str()) => k += 1,
                Tok::Punct('[') => k = p.skip_group(k),
                _ => break,
            }
        }
        if let (Some(name), Some(next)) = (p.ident_at(k), p.t.get(k + 1)) {
            // Another name, or an instance's `#(`/`(`, where the declaration needs a `,`,
            // `=`, `[` or `;`.
            let what = match &next.tok {
                Tok::Ident(other) if !other.starts_with('`') => Some(format!("`{other}`")),
                Tok::Punct(c @ ('#' | '(')) => Some(format!("`{c}`")),
                _ => None,
            };
            if let (Some(what), None) = (what, &p.trouble) {
                let word = p.ident(0).unwrap_or_default();
                p.trouble = Some((
                    next.line,
                    next.col,
                    format!("{what} right after `{name}` in a declaration (a `,` or `;` missing, or a stray `{word}`?): this does not parse"),
                ));
            }
        }
        p.i += 1;
        self.stmt_start = false;
    }

    /// `begin` (with its label), `generate`, `end`..., `else`: the nesting they open or close.
    fn block_word(&mut self, p: &mut Parser) {
        match p.ident(0) {
            Some("begin" | "generate") => self.nest += 1,
            Some("end" | "endgenerate" | "endcase") => self.nest = (self.nest - 1).max(0),
            Some("else") => self.guarded = true,
            _ => {}
        }
        // `begin : label` — skip the label.
        p.i += 1;
        if p.is(0, ':') && p.ident(1).is_some() {
            p.i += 2;
        }
        self.stmt_start = true;
    }

    /// `assign NAME = ...;` outside any alternative: an assignment to the whole net, and
    /// whether it can float (`'bz`).
    fn whole_assign(&mut self, p: &Parser, semi: usize) {
        let (Some(target), true) = (p.ident(1), p.is(2, '=')) else { return };
        let tristate = p.t[p.i + 3..semi].iter().any(
            |t| matches!(&t.tok, Tok::Num(n) if n.split_once('\'').is_some_and(|(_, v)| v.contains(['z', 'Z', '?']))),
        );
        let t = &p.t[p.i + 1];
        self.assigns.push(Assign {
            target: target.to_string(),
            at: t.at..t.at + target.len(),
            line: t.line,
            col: t.col,
            tristate,
        });
    }
}

fn direction(w: &str) -> Dir {
    match w {
        "input" => Dir::Input,
        "output" => Dir::Output,
        _ => Dir::Inout,
    }
}

fn param_names(p: &Parser, from: usize, to: usize) -> Vec<String> {
    // Names are the identifiers right before a top-level `=`.
    let mut names = Vec::new();
    let mut depth = 0;
    for k in from..to {
        match &p.t[k].tok {
            Tok::Punct('(') | Tok::Punct('[') | Tok::Punct('{') => depth += 1,
            Tok::Punct(')') | Tok::Punct(']') | Tok::Punct('}') => depth -= 1,
            Tok::Punct('=') if depth == 0 && k > from => {
                if let Tok::Ident(n) = &p.t[k - 1].tok {
                    names.push(n.clone());
                }
            }
            _ => {}
        }
    }
    names
}

/// A range `[msb:lsb]` starting at token `k`, when both are integers: (msb, lsb, index past).
fn range(p: &Parser, k: usize) -> (Option<(i64, i64)>, usize) {
    if p.t.get(k).map(|t| &t.tok) != Some(&Tok::Punct('[')) {
        return (None, k);
    }
    let end = p.skip_group(k);
    let num = |t: &Tok| match t {
        Tok::Num(s) => s.replace('_', "").parse::<i64>().ok(),
        _ => None,
    };
    let r = if end == k + 5 && p.t[k + 2].tok == Tok::Punct(':') {
        num(&p.t[k + 1].tok).zip(num(&p.t[k + 3].tok))
    } else {
        None
    };
    (r, end)
}

fn width_of(r: Option<(i64, i64)>) -> u32 {
    r.map_or(1, |(m, l)| ((m - l).unsigned_abs() + 1) as u32)
}

const NET_WORDS: &[&str] = &["wire", "reg", "logic", "signed", "unsigned", "tri", "var", "integer", "wand", "wor"];

fn ansi_ports(p: &Parser, from: usize, to: usize, ports: &mut Vec<Port>, order: &mut Vec<String>) {
    let mut dir: Option<Dir> = None;
    let mut rng = None;
    let mut k = from;
    while k < to {
        match &p.t[k].tok {
            Tok::Ident(w) if matches!(w.as_str(), "input" | "output" | "inout") => {
                dir = Some(direction(w));
                rng = None;
                k += 1;
            }
            Tok::Ident(w) if NET_WORDS.contains(&w.as_str()) => k += 1,
            Tok::Punct('[') => {
                let (r, e) = range(p, k);
                rng = r.or(Some((0, 0))).filter(|_| r.is_some());
                if r.is_none() {
                    rng = Some((-1, -1)); // unknown width
                }
                k = e;
            }
            Tok::Ident(name) => {
                match dir {
                    Some(d) => {
                        let (range, width) = match rng {
                            Some((-1, -1)) => (None, 0),
                            r => (r, width_of(r)),
                        };
                        let (line, col) = (p.t[k].line, p.t[k].col);
                        ports.push(Port { name: name.clone(), dir: d, width, range, line, col })
                    }
                    None => order.push(name.clone()),
                }
                // Skip to the next comma at this level.
                k += 1;
                while k < to && p.t[k].tok != Tok::Punct(',') {
                    k = if matches!(p.t[k].tok, Tok::Punct('(') | Tok::Punct('[') | Tok::Punct('{')) {
                        p.skip_group(k)
                    } else {
                        k + 1
                    };
                }
            }
            _ => k += 1,
        }
    }
}

fn non_ansi_ports(p: &Parser, dir: Dir, from: usize, to: usize, ports: &mut Vec<Port>) {
    let mut rng = None;
    let mut unknown = false;
    let mut k = from;
    while k < to {
        match &p.t[k].tok {
            Tok::Ident(w) if NET_WORDS.contains(&w.as_str()) => k += 1,
            Tok::Punct('[') => {
                let (r, e) = range(p, k);
                rng = r;
                unknown = r.is_none();
                k = e;
            }
            Tok::Ident(name) => {
                let width = if unknown { 0 } else { width_of(rng) };
                ports.retain(|pt| pt.name != *name);
                let (line, col) = (p.t[k].line, p.t[k].col);
                ports.push(Port { name: name.clone(), dir, width, range: rng, line, col });
                k += 1;
            }
            _ => k += 1,
        }
    }
}

/// `module_name [#(params)] inst [range] (conns) [, inst2 (conns)] ;` — returns the index of the `;`.
fn instance_statement(p: &mut Parser, body_end: usize, out: &mut Vec<Instance>) -> usize {
    let mtok = p.t[p.i].clone();
    let module = p.ident(0).unwrap_or_default().to_string();
    let mut k = p.i + 1;
    let mut params = Vec::new();
    if p.t.get(k).map(|t| &t.tok) == Some(&Tok::Punct('#')) {
        if p.t.get(k + 1).map(|t| &t.tok) == Some(&Tok::Punct('(')) {
            let end = p.skip_group(k + 1);
            p.unclosed(&mtok, &module, k + 1, end);
            params = connections(p, k + 2, end - 1).0;
            k = end;
        } else {
            k += 2; // #5 delay or #N
        }
    }
    // An instance without a name: botsim names it after the module and its line.
    if p.t.get(k).map(|t| &t.tok) == Some(&Tok::Punct('(')) {
        let end = p.skip_group(k);
        p.unclosed(&mtok, &module, k, end);
        let (connections, spans) = connections(p, k + 1, end - 1);
        out.push(Instance {
            module: module.clone(),
            name: format!("{module}_{}", mtok.line),
            line: mtok.line,
            col: mtok.col,
            connections,
            spans,
            params,
            unnamed_at: Some(p.t[k].at),
            guarded: false,
        });
        return (end..body_end).find(|&j| p.t[j].tok == Tok::Punct(';')).unwrap_or(body_end);
    }
    while let Some(Tok::Ident(name)) = p.t.get(k).map(|t| t.tok.clone()) {
        k += 1;
        if p.t.get(k).map(|t| &t.tok) == Some(&Tok::Punct('[')) {
            k = p.skip_group(k);
        }
        if p.t.get(k).map(|t| &t.tok) != Some(&Tok::Punct('(')) {
            break;
        }
        let end = p.skip_group(k);
        p.unclosed(&mtok, &module, k, end);
        let (connections, spans) = connections(p, k + 1, end - 1);
        out.push(Instance {
            module: module.clone(),
            name,
            line: mtok.line,
            col: mtok.col,
            connections,
            spans,
            params: params.clone(),
            unnamed_at: None,
            guarded: false,
        });
        k = end;
        if p.t.get(k).map(|t| &t.tok) == Some(&Tok::Punct(',')) {
            k += 1;
            continue;
        }
        break;
    }
    (k..body_end).find(|&j| p.t[j].tok == Tok::Punct(';')).unwrap_or(body_end)
}

/// `.name(expr), ...` or `expr, expr, ...` between tokens `[from, to)`: `(port, expression)`
/// each, positional ones named `#0`, `#1`..., and the bytes of each expression in the source
/// (empty where it is empty or implicit).
fn connections(p: &Parser, from: usize, to: usize) -> (Vec<(String, String)>, Vec<Range<usize>>) {
    let span = |a: usize, b: usize| -> Range<usize> {
        if a >= b {
            let at = p.t.get(a).map_or(p.src.len(), |t| t.at);
            return at..at;
        }
        p.t[a].at..p.t[b - 1].at + token_len(p.src, &p.t[b - 1])
    };
    let (mut out, mut spans) = (Vec::new(), Vec::new());
    let mut k = from;
    let mut n = 0;
    while k < to {
        if p.t[k].tok == Tok::Punct(',') {
            k += 1;
            continue;
        }
        if p.t[k].tok == Tok::Punct('.') {
            if let Some(Tok::Ident(name)) = p.t.get(k + 1).map(|t| t.tok.clone()) {
                if p.t.get(k + 2).map(|t| &t.tok) == Some(&Tok::Punct('(')) {
                    let end = p.skip_group(k + 2);
                    out.push((name, p.text(k + 3, end - 1)));
                    spans.push(span(k + 3, end - 1));
                    k = end;
                } else {
                    // `.name` (implicit) connection
                    out.push((name.clone(), name));
                    spans.push(p.t[k + 1].at..p.t[k + 1].at);
                    k += 2;
                }
                continue;
            }
        }
        let s = k;
        while k < to && p.t[k].tok != Tok::Punct(',') {
            k = if matches!(p.t[k].tok, Tok::Punct('(') | Tok::Punct('[') | Tok::Punct('{')) {
                p.skip_group(k)
            } else {
                k + 1
            };
        }
        out.push((format!("#{n}"), p.text(s, k)));
        spans.push(span(s, k));
        n += 1;
    }
    (out, spans)
}

/// The names a declaration statement `[from, semi)` declares (after `wire`), with the text of
/// its range.
fn declared_names(p: &Parser, from: usize, semi: usize) -> (Vec<String>, Option<String>) {
    let mut names = Vec::new();
    let mut range = None;
    let mut k = from;
    let mut want_name = true;
    while k < semi {
        match &p.t[k].tok {
            Tok::Ident(w) if NET_WORDS.contains(&w.as_str()) => k += 1,
            Tok::Punct('[') => {
                let end = p.skip_group(k);
                if names.is_empty() && range.is_none() {
                    range = Some(p.text(k, end));
                }
                k = end;
            }
            Tok::Punct('(') | Tok::Punct('{') => k = p.skip_group(k),
            Tok::Punct(',') => {
                want_name = true;
                k += 1;
            }
            Tok::Ident(n) if want_name => {
                names.push(n.clone());
                want_name = false;
                k += 1;
            }
            _ => k += 1,
        }
    }
    (names, range)
}

/// The keywords SystemVerilog (IEEE 1800-2017) adds to Verilog-2005: in a `.v` file, which
/// Vivado reads as Verilog, they are ordinary names.
pub const SV_KEYWORDS: &[&str] = &[
    "accept_on",
    "alias",
    "always_comb",
    "always_ff",
    "always_latch",
    "assert",
    "assume",
    "before",
    "bind",
    "bins",
    "binsof",
    "bit",
    "break",
    "byte",
    "chandle",
    "checker",
    "class",
    "clocking",
    "const",
    "constraint",
    "context",
    "continue",
    "cover",
    "covergroup",
    "coverpoint",
    "cross",
    "dist",
    "do",
    "endchecker",
    "endclass",
    "endclocking",
    "endgroup",
    "endinterface",
    "endpackage",
    "endprogram",
    "endproperty",
    "endsequence",
    "enum",
    "eventually",
    "expect",
    "export",
    "extends",
    "extern",
    "final",
    "first_match",
    "foreach",
    "forkjoin",
    "global",
    "iff",
    "ignore_bins",
    "illegal_bins",
    "implements",
    "implies",
    "import",
    "inside",
    "int",
    "interconnect",
    "interface",
    "intersect",
    "join_any",
    "join_none",
    "let",
    "local",
    "logic",
    "longint",
    "matches",
    "modport",
    "nettype",
    "new",
    "nexttime",
    "null",
    "package",
    "packed",
    "priority",
    "program",
    "property",
    "protected",
    "pure",
    "rand",
    "randc",
    "randcase",
    "randsequence",
    "ref",
    "reject_on",
    "restrict",
    "return",
    "s_always",
    "s_eventually",
    "s_nexttime",
    "s_until",
    "s_until_with",
    "sequence",
    "shortint",
    "shortreal",
    "soft",
    "solve",
    "static",
    "string",
    "strong",
    "struct",
    "super",
    "sync_accept_on",
    "sync_reject_on",
    "tagged",
    "this",
    "throughout",
    "timeprecision",
    "timeunit",
    "type",
    "typedef",
    "union",
    "unique",
    "unique0",
    "until",
    "until_with",
    "untyped",
    "var",
    "virtual",
    "void",
    "wait_order",
    "weak",
    "wildcard",
    "with",
    "within",
];

/// Every name of `src` that is a SystemVerilog keyword (`bit`, `byte`, `do`...): where it is
/// and the name. In a Verilog file they are names; written as escaped identifiers
/// (`\bit `) they stay names for a SystemVerilog parser too.
///
/// ```
/// use botsim_core::frontend::scan::sv_keywords_as_names;
/// let found = sv_keywords_as_names("wire [7:0] byte = x; // int\nassign y = byte;");
/// let words: Vec<_> = found.iter().map(|(at, line, _, w)| (at.start, *line, w.as_str())).collect();
/// assert_eq!(words, [(11, 1, "byte"), (39, 2, "byte")]);
/// ```
pub fn sv_keywords_as_names(src: &str) -> Vec<(Range<usize>, u32, u32, String)> {
    let (tokens, _) = tokenize(src);
    tokens
        .iter()
        .filter_map(|t| match &t.tok {
            Tok::Ident(w) if SV_KEYWORDS.binary_search(&w.as_str()).is_ok() && !src[t.at..].starts_with('\\') => {
                Some((t.at..t.at + w.len(), t.line, t.col, w.clone()))
            }
            _ => None,
        })
        .collect()
}

/// A port of a module with an ANSI header (`module spi(output SS, ...)`) declared again as a
/// net in its body (`wire SS, SCLK, MOSI;`), which Vivado accepts and Verilog does not: the
/// byte ranges to blank (the names, with a comma each, or the whole declaration when every
/// name is such a port), where the declaration is, and the names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Redeclared {
    pub blank: Vec<Range<usize>>,
    pub line: u32,
    pub col: u32,
    pub module: String,
    pub names: Vec<String>,
}

/// Every [`Redeclared`] port of `src`.
///
/// ```
/// use botsim_core::frontend::scan::redeclared_ansi_ports;
/// let src = "module spi(input clk, output SS, output SCLK);\n  wire SS, x, SCLK;\nendmodule\n";
/// let r = redeclared_ansi_ports(src);
/// assert_eq!((r[0].line, r[0].names.clone()), (2, vec!["SS".to_string(), "SCLK".to_string()]));
/// let mut fixed = src.to_string();
/// for b in r[0].blank.iter().rev() {
///     fixed.replace_range(b.clone(), &" ".repeat(b.len()));
/// }
/// assert_eq!(fixed.lines().nth(1), Some("  wire     x      ;"));
/// ```
pub fn redeclared_ansi_ports(src: &str) -> Vec<Redeclared> {
    let (t, _) = tokenize(src);
    let word = |k: usize| match t.get(k).map(|x| &x.tok) {
        Some(Tok::Ident(w)) => Some(w.as_str()),
        _ => None,
    };
    let punct = |k: usize, c: char| t.get(k).map(|x| &x.tok) == Some(&Tok::Punct(c));
    let group_end = |from: usize| {
        let mut depth = 0i32;
        for (j, x) in t.iter().enumerate().skip(from) {
            match x.tok {
                Tok::Punct('(' | '[' | '{') => depth += 1,
                Tok::Punct(')' | ']' | '}') => {
                    depth -= 1;
                    if depth == 0 {
                        return j + 1;
                    }
                }
                _ => {}
            }
        }
        t.len()
    };
    let mut out = Vec::new();
    let mut i = 0;
    while i < t.len() {
        if !matches!(word(i), Some("module" | "macromodule")) {
            i += 1;
            continue;
        }
        let module = word(i + 1).unwrap_or_default().to_string();
        let mut k = i + 2;
        if punct(k, '#') && punct(k + 1, '(') {
            k = group_end(k + 1);
        }
        if !punct(k, '(') {
            i = k;
            continue;
        }
        let header_end = group_end(k);
        // The header's names, when it declares directions (an ANSI header).
        let ansi = (k..header_end).any(|j| matches!(word(j), Some("input" | "output" | "inout")));
        let ports: Vec<&str> = (k..header_end)
            .filter(|&j| word(j).is_some() && (punct(j + 1, ',') || punct(j + 1, ')')))
            .filter_map(word)
            .collect();
        let mut j = header_end;
        let mut depth = 0i32;
        let mut stmt_start = true;
        while j < t.len() && !matches!(word(j), Some("endmodule" | "module" | "macromodule")) {
            match word(j) {
                Some("begin" | "generate" | "function" | "task") => depth += 1,
                Some("end" | "endgenerate" | "endfunction" | "endtask") => depth -= 1,
                _ => {}
            }
            if ansi && depth == 0 && stmt_start && word(j) == Some("wire") {
                // `wire [range] a, b, c;`: names and commas only.
                let mut n = j + 1;
                if punct(n, '[') {
                    n = group_end(n);
                }
                let mut names = Vec::new();
                while let Some(w) = word(n) {
                    names.push((n, w));
                    if punct(n + 1, ',') {
                        n += 2;
                    } else {
                        n += 1;
                        break;
                    }
                }
                if punct(n, ';') && !names.is_empty() {
                    let again: Vec<usize> = (0..names.len()).filter(|&q| ports.contains(&names[q].1)).collect();
                    if !again.is_empty() {
                        let span = |a: usize, b: usize| t[a].at..t[b].at + token_len(src, &t[b]);
                        let blank = if again.len() == names.len() {
                            vec![span(j, n)]
                        } else {
                            again
                                .iter()
                                .map(|&q| {
                                    let at = names[q].0;
                                    // With the comma after it, or before it for the last.
                                    if q + 1 < names.len() {
                                        span(at, at + 1)
                                    } else {
                                        span(at - 1, at)
                                    }
                                })
                                .collect()
                        };
                        out.push(Redeclared {
                            blank,
                            line: t[j].line,
                            col: t[j].col,
                            module: module.clone(),
                            names: again.iter().map(|&q| names[q].1.to_string()).collect(),
                        });
                    }
                }
            }
            stmt_start = punct(j, ';') || matches!(word(j), Some("begin" | "end" | "endgenerate" | "generate"));
            j += 1;
        }
        i = j;
    }
    out
}

/// `text` with its comments replaced by a space (strings kept whole).
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(['/', '"']) {
        out.push_str(&rest[..at]);
        rest = &rest[at..];
        let end = if rest.starts_with("//") {
            out.push(' ');
            rest.find('\n').unwrap_or(rest.len())
        } else if let Some(body) = rest.strip_prefix("/*") {
            out.push(' ');
            body.find("*/").map_or(rest.len(), |k| k + 4)
        } else if let Some(body) = rest.strip_prefix('"') {
            let k = body.find('"').map_or(rest.len(), |k| k + 2);
            out.push_str(&rest[..k]);
            k
        } else {
            out.push('/');
            1
        };
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// The length of a token's text in `src`.
fn token_len(src: &str, t: &Token) -> usize {
    match &t.tok {
        Tok::Ident(w) | Tok::Num(w) => src[t.at..].find(w.as_str()).map_or(w.len(), |k| k + w.len()),
        Tok::Punct(_) => 1,
        Tok::Str => src[t.at + 1..].find('"').map_or(1, |k| k + 2),
    }
}

/// The module at `span` of `src` with comments and layout taken out: two copies of a module
/// that differ in nothing else have the same normalized text.
pub fn normalized(src: &str, span: Range<usize>) -> String {
    let text = &src[span];
    let (tokens, _) = tokenize(text);
    let mut out = String::new();
    for (k, t) in tokens.iter().enumerate() {
        match &t.tok {
            Tok::Ident(s) | Tok::Num(s) => out.push_str(s),
            Tok::Punct(c) => out.push(*c),
            Tok::Str => {
                let end = tokens.get(k + 1).map_or(text.len(), |n| n.at);
                out.push_str(text[t.at..end].trim_end());
            }
        }
        out.push(' ');
    }
    out
}

/// A based literal with more digits than its width holds (`8'h1FF`, `4'b10101`), which
/// Vivado truncates to its width and Verilator refuses: where it is, and the same literal
/// with the digits the width keeps.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Oversized {
    pub at: Range<usize>,
    pub line: u32,
    pub col: u32,
    pub text: String,
    pub fixed: String,
}

/// Every oversized literal of `src` (comments and strings skipped).
///
/// ```
/// use botsim_core::frontend::scan::oversized_literals;
/// // 6'hFF and 4'b0_1010 fit (their extra bits are in a digit the width needs, or zeros).
/// let o = oversized_literals("assign a = 8'h1FF; // 8'h1FF\nassign b = 6'hFF + 4'b0_1010 + 4'b1_1010;");
/// let fixed: Vec<_> = o.iter().map(|o| (o.line, o.text.as_str(), o.fixed.as_str())).collect();
/// assert_eq!(fixed, [(1, "8'h1FF", "8'hFF"), (2, "4'b1_1010", "4'b1010")]);
/// // A typo is no literal to fix.
/// assert!(oversized_literals("assign c = 1'shift;").is_empty());
/// ```
pub fn oversized_literals(src: &str) -> Vec<Oversized> {
    let (tokens, _) = tokenize(src);
    tokens
        .iter()
        .filter_map(|t| {
            let Tok::Num(text) = &t.tok else { return None };
            let fixed = truncated_literal(text)?;
            Some(Oversized { at: t.at..t.at + text.len(), line: t.line, col: t.col, text: text.clone(), fixed })
        })
        .collect()
}

/// The last `begin` still open before line `line` (where Verilator met what only a module
/// holds), counted from the `module` before it: its line and column. Read with the
/// scanner's tokens, so comments and strings do not count.
///
/// ```
/// use botsim_core::frontend::scan::unclosed_begin;
/// let text = "module m(input a);\n  reg x; // begin\n  always @* begin\n    if (a) begin x = 1; end\n    $display(\"end\");\n  /* end */\nendmodule\n";
/// assert_eq!(unclosed_begin(text, 7), Some((3, 13)));
/// assert_eq!(unclosed_begin("module m;\n always @* begin\n end\nendmodule\n", 4), None);
/// ```
pub fn unclosed_begin(src: &str, line: u32) -> Option<(u32, u32)> {
    let (tokens, _) = tokenize(src);
    let mut open: Vec<(u32, u32)> = Vec::new();
    for t in tokens.iter().take_while(|t| t.line < line) {
        match &t.tok {
            Tok::Ident(w) if w == "module" || w == "macromodule" => open.clear(),
            Tok::Ident(w) if w == "begin" => open.push((t.line, t.col)),
            Tok::Ident(w) if w == "end" => {
                open.pop();
            }
            _ => {}
        }
    }
    open.last().copied()
}

/// `8'h1FF` -> `8'hFF`: the digits a literal's width keeps, when it has more (an unsized
/// literal is 32 bits wide).
fn truncated_literal(text: &str) -> Option<String> {
    let (size_text, rest) = text.split_once('\'')?;
    let size: u32 = if size_text.is_empty() { 32 } else { size_text.replace('_', "").parse().ok()? };
    let (signed, rest) = match rest.strip_prefix(['s', 'S']) {
        Some(r) => (&rest[..1], r),
        None => ("", rest),
    };
    let base = rest.chars().next()?;
    let bits_per_digit = match base.to_ascii_lowercase() {
        'b' => 1,
        'o' => 3,
        'h' => 4,
        _ => return None,
    };
    let digits: String = rest[1..].chars().filter(|c| *c != '_').collect();
    // Only a literal that is one (`1'shift` is the user's typo, left for the compiler to
    // point at, not "fixed" into another).
    let valid = |c: char| matches!(c.to_ascii_lowercase(), 'x' | 'z' | '?') || c.is_digit(1 << bits_per_digit);
    if digits.is_empty() || !digits.chars().all(valid) {
        return None;
    }
    let significant = digits.trim_start_matches('0');
    let allowed = size.div_ceil(bits_per_digit) as usize;
    if size == 0 || significant.len() <= allowed {
        return None;
    }
    Some(format!("{size_text}'{signed}{base}{}", &significant[significant.len() - allowed..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_the_scanner_cannot_read_is_said_where_it_is() {
        // A keyword where a port's name should be.
        let m = &scan("module t(input clk,\n  endmodule\n  output led);\nendmodule\n")[0];
        assert_eq!(m.unreadable.as_ref().map(|u| (u.0, u.1)), Some((2, 3)), "{m:?}");
        // A stray `endmodule`: what follows is outside any module.
        let m = &scan("module t(input clk);\n  wire a;\nendmodule\n  always @(posedge clk) a <= 1;\nendmodule\nmodule u; endmodule\n")[0];
        let u = m.unreadable.as_ref().unwrap();
        assert_eq!((u.0, u.1), (4, 3));
        assert!(u.2.contains("the `endmodule` at line 3 ends `t` before it"), "{}", u.2);
        // An instance whose `)` is missing: the `;` inside its group.
        let m = &scan("module t(input clk);\n  sub a (.x(clk),\n  sub b (.x(clk));\nendmodule\n")[0];
        let u = m.unreadable.as_ref().unwrap();
        assert_eq!(
            (u.0, u.2.as_str()),
            (2, "the `(` of this `sub` does not close before the `;` at line 3: this does not parse")
        );
        // A stray `wire` before an instance: the declaration says so.
        let m = &scan("module t(input clk);\n  wire\n  sub a (.x(clk));\nendmodule\n")[0];
        let u = m.unreadable.as_ref().unwrap();
        assert_eq!((u.0, u.1), (3, 7), "{}", u.2);
        let m = &scan("module t(input clk);\n  wire\n  sub #(.N(1)) a (.x(clk));\nendmodule\n")[0];
        let u = m.unreadable.as_ref().unwrap();
        assert_eq!((u.0, u.1), (3, 7), "{}", u.2);
        // Nothing of the kind in good Verilog, UDPs and packages after a module included.
        for good in [
            "module t(input clk);\n  wire signed [7:0] a = 8'd1, b;\n  reg [3:0] m [0:15];\n  wire #1 c;\n  sub a (.x(clk));\nendmodule\nprimitive p (o, i);\n output o; input i;\n table 0:1; endtable\nendprimitive\n",
            "`timescale 1ns/1ps\nmodule t(input clk);\nendmodule\n`MY_MACRO(x)\n",
        ] {
            assert!(scan(good).iter().all(|m| m.unreadable.is_none()), "{good}");
        }
    }

    #[test]
    fn a_connections_text_leaves_out_the_comments_around_and_inside_it() {
        let m = scan("module t(input clk);\n  rom r (.instruction(instruction /* x */), .address( // y\n  a[11:0] /* z */ + 1 ), .s(\"//\"));\nendmodule\n");
        let c = &m[0].instances[0].connections;
        assert_eq!(c[0], ("instruction".to_string(), "instruction".to_string()));
        assert_eq!(c[1], ("address".to_string(), "a[11:0] + 1".to_string()));
        assert_eq!(c[2], ("s".to_string(), "\"//\"".to_string()));
    }

    /// `@(*)` in one module and `@(*)` (or an attribute) in a later one: the text between is
    /// no attribute (it was, from the first `(*` to the later `*)`: the modules between were
    /// lost, "2 modules of the design are missing").
    #[test]
    fn a_star_event_control_is_no_attribute_whatever_follows() {
        for (first, later) in [
            ("always @(*) half = 18'd5;", "always @(*) x = 1;"),
            ("always @(* ) begin half = 5; end", "(* keep = \"true\" *) wire w;"),
            ("always @( * ) half = 5;", "always @(*)\n case (a) 1: x = 1; endcase"),
        ] {
            let src = format!(
                "module t(input clk);\n  reg [17:0] half;\n  {first}\n  d D1 (.clk(clk));\nendmodule\n\
                 module d(input clk);\n  {later}\nendmodule\nmodule e; endmodule\n"
            );
            let m = scan(&src);
            let names: Vec<_> = m.iter().map(|m| m.name.as_str()).collect();
            assert_eq!(names, ["t", "d", "e"], "{first} / {later}");
            assert_eq!(m[0].instances.len(), 1, "{first}");
        }
    }

    #[test]
    fn non_ansi_ports_keep_their_order_and_widths() {
        let m = &scan("module t(a, b, c);\ninput [3:0] a;\noutput reg b;\ninout c;\nendmodule")[0];
        let got: Vec<_> = m.ports.iter().map(|p| (p.name.as_str(), p.dir, p.width)).collect();
        assert_eq!(got, [("a", Dir::Input, 4), ("b", Dir::Output, 1), ("c", Dir::Inout, 1)]);
    }

    #[test]
    fn instances_inside_generate_and_after_comments_and_directives() {
        let src = "`timescale 1ns/1ps\nmodule t(input clk);\n// foo bar (x);\n/* a b(c); */\n\
                   `ifdef X\n wire w;\n`endif\n generate if (1) begin : g\n  BUFG b0 (.I(clk), .O());\n end endgenerate\n\
                   always @(posedge clk) x <= y;\n kcpsm6 #(.hwbuild(8'h00)) cpu (.clk(clk)), cpu2 (.clk(clk));\nendmodule\n";
        let m = &scan(src)[0];
        let names: Vec<_> = m.instances.iter().map(|i| (i.module.as_str(), i.name.as_str(), i.line)).collect();
        assert_eq!(names, [("BUFG", "b0", 9), ("kcpsm6", "cpu", 12), ("kcpsm6", "cpu2", 12)]);
        assert_eq!(m.instances[0].connections[1], ("O".into(), "".into()));
        assert_eq!(m.instances[1].params[0], ("hwbuild".into(), "8'h00".into()));
    }

    #[test]
    fn an_instance_right_after_the_end_of_a_block() {
        // No `;` between `endgenerate` (or `endcase`, `endfunction`) and the next instance.
        for end in [
            "generate if (1) begin : g\n assign a = 1'b0;\n end endgenerate",
            "function f; input x; f = x; endfunction",
        ] {
            let src = format!("module t(input clk);\n {end}\n bot b (.clk(clk));\nendmodule\n");
            let m = &scan(&src)[0];
            let names: Vec<_> = m.instances.iter().map(|i| i.name.as_str()).collect();
            assert_eq!(names, ["b"], "{src}");
        }
    }

    #[test]
    fn an_empty_module_declares_and_include_directives_are_found() {
        let src = "`include \"defs.vh\"\nmodule clk_wiz_0(clk_out1, clk_in1) /* synthesis syn_black_box */;\n\
                   output clk_out1;\n input clk_in1;\nendmodule\n\
                   module w(output y); assign y = 1'b0; endmodule\nmodule r(output reg q = 1'b0); endmodule\n\
                   module i(input a); sub s(.a(a)); endmodule\n";
        let empty: Vec<_> = scan(src).iter().map(|m| (m.name.clone(), m.empty)).collect();
        let want = [("clk_wiz_0", true), ("w", false), ("r", true), ("i", false)];
        assert_eq!(empty, want.map(|(n, e)| (n.to_string(), e)));
        let refs = file_references(src);
        assert_eq!((refs[0].name.as_str(), refs[0].line, refs[0].col), ("defs.vh", 1, 10));
    }

    #[test]
    fn normalized_text_ignores_comments_and_layout() {
        let a = "module m(input a); // one\n  assign y = a;\nendmodule";
        let b = "module m(input a);\n/* two */ assign y =\n a; endmodule";
        let c = "module m(input a); assign y = ~a; endmodule";
        let n = |s: &str| normalized(s, scan(s)[0].span.clone());
        assert_eq!(n(a), n(b));
        assert_ne!(n(a), n(c));
    }

    #[test]
    fn the_systemverilog_keywords_are_sorted_for_the_search() {
        assert!(SV_KEYWORDS.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn parameters_and_spans() {
        let src =
            "module a #(parameter N = 3, parameter [1:0] M = 2) (); parameter K = 1; endmodule\nmodule b; endmodule";
        let ms = scan(src);
        assert_eq!(ms[0].params, ["N", "M", "K"]);
        assert_eq!(&src[ms[1].span.clone()], "module b; endmodule");
    }
}
