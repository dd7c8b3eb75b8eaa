//! Which KCPSM6 models' `out_port` the design reads only under a write strobe: found in the
//! C++ Verilator generates, at build time.
//!
//! A KCPSM6 shows sX on `out_port` in every cycle, not only in an OUTPUT's. A core counting in
//! a software delay shows its count there; the board's fast-forward may skip the delay
//! (`counts`) only if nothing in the design can tell what `out_port` shows between
//! OUTPUTs. The course's designs read it as `if (write_strobe) case (port_id) ...` (or
//! `k_write_strobe`, or through a wire `write_strobe & port_id[..]`): every read of
//! `out_port`'s bits of kcpsm6_iss.v's outputs register (`botsim_iss_q`, bits 13-20) must sit
//! in an `if` whose condition is true only with bit 29 or 30 (the strobes) set, directly
//! (`1U & (q >> 0x1dU)`, `(0x20200000ULL == (0x20200000ULL & q))`, conjunctions of them) or
//! through a **guard**: a root variable every write of which is such a condition, computed
//! from the outputs register after it takes its new value (a combinational wire; a guard
//! registered at the edge would hold the last cycle's strobe, and is not one).
//!
//! ```
//! let root = "class Vboard___024root final {\n  QData/*63:0*/ u__DOT__cpu__DOT__botsim_iss_q;\n  CData/*7:0*/ led;\n};\n";
//! let gated = "void f(Vboard___024root* vlSelf) {\n    if ((1U & (IData)((vlSelf->u__DOT__cpu__DOT__botsim_iss_q >> 0x1dU)))) {\n        vlSelf->led = (0xffU & (IData)((vlSelf->u__DOT__cpu__DOT__botsim_iss_q >> 0xdU)));\n    }\n}\n";
//! assert_eq!(botsim::fastforward::strobes::out_port_free(root, &[gated]), ["u__DOT__cpu"]);
//! let shown = "void f(Vboard___024root* vlSelf) {\n    vlSelf->led = (0xffU & (IData)((vlSelf->u__DOT__cpu__DOT__botsim_iss_q >> 0xdU)));\n}\n";
//! assert!(botsim::fastforward::strobes::out_port_free(root, &[shown]).is_empty());
//! ```

use std::collections::{BTreeMap, BTreeSet};

use super::cpp::{closing, functions, tokens, Tok};
use super::demand::{demands, Demand};

/// The outputs register's name in a kcpsm6_iss.v instance (after its instance's name).
pub const OUTPUTS: &str = "__DOT__botsim_iss_q";
/// Its `out_port` bits, and the write strobes' (`write_strobe`, `k_write_strobe`).
const OUT_PORT: u64 = 0xFF << 13;
pub(super) const STROBES: u64 = 3 << 29;
/// Every strobe: the write strobes and `read_strobe` (bit 31).
pub(super) const ALL_STROBES: u64 = 7 << 29;

/// The KCPSM6 models (their instances' Verilator names) whose `out_port` the evaluation
/// `code` (the root's functions) reads only under a write strobe.
pub fn out_port_free(root: &str, code: &[&str]) -> Vec<String> {
    let widths = super::counters::scalar_widths(root);
    let mut bodies: Vec<Vec<Tok>> = Vec::new();
    for c in code {
        for (_, body) in functions(c) {
            match tokens(body) {
                Ok(t) => bodies.push(t),
                // Nothing in code the analysis cannot read may be trusted.
                Err(_) => return Vec::new(),
            }
        }
    }
    // (A delayed copy kept in the root, `__Vdly__...`, is no core.)
    let cores: Vec<&str> =
        widths.keys().filter(|n| !n.starts_with("__V")).filter_map(|n| n.strip_suffix(OUTPUTS)).collect();
    cores
        .into_iter()
        .filter(|core| {
            let q = format!("{core}{OUTPUTS}");
            let guards = guards(&bodies, &q, STROBES);
            bodies.iter().all(|t| gated(t, &q, &guards, &widths))
        })
        .map(str::to_string)
        .collect()
}

/// `vlSelf->name` (or `vlSelfRef.name`) at `i`: the name.
pub(super) fn member<'a>(t: &[Tok<'a>], i: usize) -> Option<&'a str> {
    match (t.get(i)?, t.get(i + 1)?, t.get(i + 2)?) {
        (Tok::Id("vlSelf" | "vlSelfRef"), Tok::P("->" | "."), Tok::Id(n)) => Some(n),
        _ => None,
    }
}

/// A write of a root variable: its function, the index of its first token, its value's tokens.
type Write = (usize, usize, std::ops::Range<usize>);

/// The guards of outputs register `q`: root variables whose every write is a strobe's
/// condition (a strobe of `strobes`), each after `q`'s last write in its function.
pub(super) fn guards(bodies: &[Vec<Tok>], q: &str, strobes: u64) -> BTreeSet<String> {
    // Every write `vlSelf->g = ...;`: its function, where, and its value's tokens.
    let mut writes: BTreeMap<&str, Vec<Write>> = BTreeMap::new();
    let mut q_last: Vec<Option<usize>> = vec![None; bodies.len()];
    for (f, t) in bodies.iter().enumerate() {
        for i in 0..t.len() {
            let Some(name) = member(t, i) else { continue };
            if t.get(i + 3) != Some(&Tok::P("=")) || (i > 0 && !matches!(t[i - 1], Tok::P(";" | "{" | "}"))) {
                continue;
            }
            let end = (i + 4..t.len()).find(|&j| t[j] == Tok::P(";")).unwrap_or(t.len());
            if name == q {
                q_last[f] = Some(i);
            } else {
                writes.entry(name).or_default().push((f, i, i + 4..end));
            }
        }
    }
    let mut guards = BTreeSet::new();
    // A guard may be written from another (a wire of wires): until none is added.
    loop {
        let before = guards.len();
        for (name, ws) in &writes {
            if guards.contains(*name) {
                continue;
            }
            let all = ws.iter().all(|(f, at, value)| {
                q_last[*f].is_some_and(|q_at| q_at < *at)
                    && strobe(&parse(&bodies[*f][value.clone()], q), &guards, strobes)
            });
            if all {
                guards.insert(name.to_string());
            }
        }
        if guards.len() == before {
            return guards;
        }
    }
}

/// Every read of `out_port`'s bits of `q` in the function `t` is under a strobe's `if`:
/// walked token by token, with a stack of the open blocks (whether each runs only under a
/// strobe), each `if`'s condition checked as a read and then opening its block.
fn gated(t: &[Tok], q: &str, guards: &BTreeSet<String>, widths: &BTreeMap<String, u32>) -> bool {
    let width = |n: &str| widths.get(n).copied();
    let reads = demands(t, &width);
    let mut blocks: Vec<bool> = Vec::new();
    let mut i = 0;
    while i < t.len() {
        match t[i] {
            Tok::Id("if") if t.get(i + 1) == Some(&Tok::P("(")) => {
                let Some(close) = closing(t, i + 1) else { return false };
                if !(i + 2..close).all(|j| read_ok(t, j, q, &reads, &blocks)) {
                    return false;
                }
                if t.get(close + 1) == Some(&Tok::P("{")) {
                    blocks.push(strobe(&parse(&t[i + 2..close], q), guards, STROBES));
                    i = close + 2;
                } else {
                    i = close + 1;
                }
                continue;
            }
            Tok::P("{") => blocks.push(false),
            Tok::P("}") => {
                blocks.pop();
            }
            _ if own_delayed_copy(t, i, q) => {}
            _ if !read_ok(t, i, q, &reads, &blocks) => return false,
            _ => {}
        }
        i += 1;
    }
    true
}

/// The token at `i` is the register's own delayed copy being taken (`__Vdly__q = vlSelf->q;`),
/// which is no read.
fn own_delayed_copy(t: &[Tok], i: usize, q: &str) -> bool {
    i >= 2 && t[i - 1] == Tok::P("=") && matches!(t[i - 2], Tok::Id(n) if n.strip_prefix("__Vdly__") == Some(q))
}

/// The token at `i` is no read of `q`'s `out_port` bits, or one under a strobe.
fn read_ok(t: &[Tok], i: usize, q: &str, reads: &std::collections::HashMap<usize, Demand>, blocks: &[bool]) -> bool {
    // (A write of the register, its commit, is no read.)
    if member(t, i) != Some(q) || t.get(i + 3) == Some(&Tok::P("=")) {
        return true;
    }
    let bits = match reads.get(&i) {
        Some(Demand::Bits(b) | Demand::Guarded { bits: b, .. }) => *b,
        _ => u64::MAX,
    };
    bits & OUT_PORT == 0 || blocks.iter().any(|&b| b)
}

/// A condition, as much of it as tells a strobe.
#[derive(Debug)]
pub(super) enum Cond {
    /// The outputs register shifted right.
    Q(u32),
    Const(u64),
    Var(String),
    /// `&` or `&&`; `|` or `||`; `==`.
    And(Box<Cond>, Box<Cond>),
    Or(Box<Cond>, Box<Cond>),
    Eq(Box<Cond>, Box<Cond>),
    /// `!=`.
    Ne(Box<Cond>, Box<Cond>),
    Other,
}

/// True only with a strobe of `strobes` set.
pub(super) fn strobe(c: &Cond, guards: &BTreeSet<String>, strobes: u64) -> bool {
    let within = |m: u64| m != 0 && m & !strobes == 0;
    match c {
        Cond::And(a, b) => match (&**a, &**b) {
            (Cond::Const(m), Cond::Q(s)) | (Cond::Q(s), Cond::Const(m)) => *s < 64 && within(m << s),
            _ => strobe(a, guards, strobes) || strobe(b, guards, strobes),
        },
        Cond::Or(a, b) => strobe(a, guards, strobes) && strobe(b, guards, strobes),
        Cond::Eq(a, b) => {
            // k == (m & q): the bits of k within m are all set.
            let (k, x) = match (&**a, &**b) {
                (Cond::Const(k), x) | (x, Cond::Const(k)) => (*k, x),
                _ => return false,
            };
            match x {
                Cond::And(l, r) => match (&**l, &**r) {
                    (Cond::Const(m), Cond::Q(s)) | (Cond::Q(s), Cond::Const(m)) => {
                        *s < 64 && ((k & m) << s) & strobes != 0
                    }
                    _ => false,
                },
                Cond::Q(s) => *s < 64 && (k << s) & strobes != 0,
                _ => false,
            }
        }
        // 0 != x: x is not zero.
        Cond::Ne(a, b) => match (&**a, &**b) {
            (Cond::Const(0), x) | (x, Cond::Const(0)) => strobe(x, guards, strobes),
            _ => false,
        },
        Cond::Var(g) => guards.contains(g),
        _ => false,
    }
}

/// The tokens without Verilator's casts (`(IData)`).
pub(super) fn drop_casts<'a>(t: &[Tok<'a>]) -> Vec<Tok<'a>> {
    let mut toks: Vec<Tok> = Vec::with_capacity(t.len());
    let mut i = 0;
    while i < t.len() {
        if let (Tok::P("("), Some(Tok::Id("CData" | "SData" | "IData" | "QData")), Some(Tok::P(")"))) =
            (t[i], t.get(i + 1), t.get(i + 2))
        {
            i += 3;
            continue;
        }
        toks.push(t[i]);
        i += 1;
    }
    toks
}

/// Parse a condition's tokens (casts dropped).
pub(super) fn parse(t: &[Tok], q: &str) -> Cond {
    let toks = drop_casts(t);
    let mut p = Parser { t: &toks, i: 0, q };
    let c = p.or();
    if p.i == toks.len() {
        c
    } else {
        Cond::Other
    }
}

struct Parser<'a, 't> {
    t: &'a [Tok<'t>],
    i: usize,
    q: &'a str,
}

impl Parser<'_, '_> {
    fn eat(&mut self, p: &str) -> bool {
        if self.t.get(self.i) == Some(&Tok::P(p)) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn or(&mut self) -> Cond {
        let mut c = self.and();
        while self.eat("||") || self.eat("|") {
            c = Cond::Or(Box::new(c), Box::new(self.and()));
        }
        c
    }

    fn and(&mut self) -> Cond {
        let mut c = self.eq();
        while self.eat("&&") || self.eat("&") {
            c = Cond::And(Box::new(c), Box::new(self.eq()));
        }
        c
    }

    fn eq(&mut self) -> Cond {
        let c = self.shift();
        if self.eat("==") {
            return Cond::Eq(Box::new(c), Box::new(self.shift()));
        }
        if self.eat("!=") {
            return Cond::Ne(Box::new(c), Box::new(self.shift()));
        }
        if self.eat("^") || self.eat("<") || self.eat(">") || self.eat("<=") || self.eat(">=") {
            self.shift();
            return Cond::Other;
        }
        c
    }

    fn shift(&mut self) -> Cond {
        let c = self.primary();
        if self.eat(">>") {
            let by = self.primary();
            return match (c, by) {
                (Cond::Q(s), Cond::Const(k)) => Cond::Q(s.saturating_add(k.min(64) as u32)),
                _ => Cond::Other,
            };
        }
        if self.eat("<<") || self.eat("+") || self.eat("-") {
            self.primary();
            return Cond::Other;
        }
        c
    }

    fn primary(&mut self) -> Cond {
        let Some(&tok) = self.t.get(self.i) else { return Cond::Other };
        if self.eat("(") {
            let c = self.or();
            return if self.eat(")") { c } else { Cond::Other };
        }
        if self.eat("~") || self.eat("!") {
            self.primary();
            return Cond::Other;
        }
        if let Some(name) = member(self.t, self.i) {
            self.i += 3;
            return if name == self.q { Cond::Q(0) } else { Cond::Var(name.to_string()) };
        }
        self.i += 1;
        match tok {
            Tok::Num(n) => super::demand::number(n).map_or(Cond::Other, Cond::Const),
            _ => Cond::Other,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROOT: &str = "class Vboard___024root final {\n  QData/*63:0*/ u__DOT__cpu__DOT__botsim_iss_q;\n  \
                        QData/*63:0*/ __Vdly__u__DOT__cpu__DOT__botsim_iss_q;\n  CData/*0:0*/ u__DOT__we;\n  \
                        CData/*7:0*/ u__DOT__led;\n  CData/*7:0*/ u__DOT__in_port;\n};\n";
    const Q: &str = "vlSelf->u__DOT__cpu__DOT__botsim_iss_q";

    fn free(body: &str) -> bool {
        // Indented, as Verilator writes a function's body.
        let body: Vec<String> = body.replace("Q", Q).lines().map(|l| format!("    {l}")).collect();
        let code = format!("void f(Vboard___024root* vlSelf) {{\n{}\n}}\n", body.join("\n"));
        !out_port_free(ROOT, &[&code]).is_empty()
    }

    #[test]
    fn reads_under_a_strobe_are_free() {
        // if (write_strobe) { if (port_id == 3) led <= out_port; }
        assert!(free(
            "if ((1U & (IData)((Q >> 0x1dU)))) {\n if ((3U == (0xffU & (IData)((Q >> 0x15U))))) {\n \
             vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n }\n}"
        ));
        // k_write_strobe, and port_id read without a strobe (a read mux): free.
        assert!(free(
            "vlSelf->u__DOT__in_port = ((1U & (IData)((Q >> 0x15U))) ? 1U : 2U);\n\
             if ((1U & (IData)((Q >> 0x1eU)))) {\n vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}"
        ));
        // Either strobe: `0 != (0x60000000 & q)`.
        assert!(free(
            "if ((IData)((0ULL != (0x60000000ULL & Q)))) {\n vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}"
        ));
        // A guard wire: we = write_strobe & port_id[1], computed after the register's commit.
        assert!(free(
            "if (vlSelf->u__DOT__we) {\n vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}\n\
             Q = __Vdly__u__DOT__cpu__DOT__botsim_iss_q;\n\
             vlSelf->u__DOT__we = (IData)((0x20400000ULL == (0x20400000ULL & Q)));"
        ));
    }

    #[test]
    fn reads_without_a_strobe_are_not() {
        // led = out_port (a design that shows it).
        assert!(!free("vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));"));
        // Under read_strobe (bit 31), or port_id alone.
        assert!(!free(
            "if ((1U & (IData)((Q >> 0x1fU)))) {\n vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}"
        ));
        assert!(!free(
            "if ((3U == (0xffU & (IData)((Q >> 0x15U))))) {\n vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}"
        ));
        // In the else branch of a strobe.
        assert!(!free(
            "if ((1U & (IData)((Q >> 0x1dU)))) {\n vlSelf->u__DOT__in_port = 0U;\n} else {\n \
             vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}"
        ));
        // A registered strobe (written before the register's commit: last cycle's) is no
        // guard.
        assert!(!free(
            "vlSelf->u__DOT__we = (IData)((0x20400000ULL == (0x20400000ULL & Q)));\n\
             if (vlSelf->u__DOT__we) {\n vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}\n\
             Q = __Vdly__u__DOT__cpu__DOT__botsim_iss_q;"
        ));
        // Any of the strobes, read_strobe among them.
        assert!(!free(
            "if ((IData)((0ULL != (0xe0000000ULL & Q)))) {\n vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}"
        ));
        // Either strobe or not: an `or` with something else.
        assert!(!free(
            "if (((1U & (IData)((Q >> 0x1dU))) | (1U & (IData)((Q >> 0x15U))))) {\n \
             vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0xdU)));\n}"
        ));
    }
}
