//! Which bits of each variable the generated code reads, read by read: a small parser for the
//! statements and expressions Verilator writes, and a walk from each consumer down to the
//! variables it reads, carrying the bits of the value that matter.
//!
//! A value assigned to an 8-bit variable needs only its low 8 bits; so do both operands of a
//! sum whose low 8 bits are needed (a carry only goes up), both branches of a choice, both
//! sides of a bitwise operation; a mask with a constant keeps those bits; a shift by a
//! constant moves them; anything else (a comparison with a variable, a product, a call, an
//! index) needs all. A comparison of a variable with a constant is kept apart: it tells the
//! variable apart only at the constant. [`super::counters`] asks this of every read of a
//! candidate counter, whatever shape the expression around it has (a port's read mux that
//! Verilator writes as a chain of choices, a sum shown on a digit).
//!
//! ```
//! use botsim::fastforward::cpp::tokens;
//! use botsim::fastforward::demand::{demands, Demand};
//! let code = "vlSelf->an = (0xffU & (vlSelf->sel ? vlSelf->cnt : vlSelf->other));\n\
//!             if ((0x1fU == vlSelf->cnt)) { vlSelf->x = 1U; }\n";
//! let toks = tokens(code).unwrap();
//! let d = demands(&toks, &|name| (name == "an" || name == "x").then_some(8));
//! let mut cnt: Vec<(usize, Demand)> =
//!     d.into_iter().filter(|(i, _)| toks[*i + 2] == botsim::fastforward::cpp::Tok::Id("cnt")).collect();
//! cnt.sort_by_key(|(i, _)| *i);
//! assert_eq!(cnt.iter().map(|(_, d)| *d).collect::<Vec<_>>(), [Demand::Bits(0xff), Demand::Compare(0x1f)]);
//! ```

use std::collections::HashMap;

use super::cpp::Tok;

/// What a read needs of the variable it reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Demand {
    /// These bits of its value.
    Bits(u64),
    /// Whether it equals, or is above or below, this constant (all its bits, but only the
    /// constant tells it apart).
    Compare(u64),
    /// Whether it plus `offset` (taken modulo `wrap` + 1) equals, or is above or below, the
    /// root variable read at token `bound_at`: only that variable's value (and the sum's wrap)
    /// tells it apart, while the variable holds.
    CompareVar { bound_at: usize, offset: u64, wrap: u64 },
    /// Whether it plus `offset` (taken modulo `wrap` + 1) equals, or is above or below, one of
    /// the first `n` of `consts`: a tone generator's `count + 1 >= half` with `half` a choice
    /// of constants (`case` on the switches, which Verilator inlines as `?:`). Only those
    /// constants (and the sum's wrap) tell it apart.
    CompareConsts { consts: [u64; MAX_CHOICES], n: u8, offset: u64, wrap: u64 },
    /// These bits of its value, read only where `guard` holds of it: a read inside
    /// `if (x >= start && x <= end) { ... x - start ... }` (a sprite's row within its
    /// window), or in the arm of a `?:` so chosen. The guard's comparison is a read of its
    /// own, so a counter's interval never straddles where the guard turns.
    Guarded { bits: u64, guards: Guards },
}

/// The most comparisons of one variable a guarded read keeps (the innermost).
pub const MAX_GUARDS: usize = 4;

/// The comparisons that all hold where a guarded read happens ([`Demand::Guarded`]): the
/// first `n` of `all`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Guards {
    pub all: [Guard; MAX_GUARDS],
    pub n: u8,
}

impl Guards {
    pub fn iter(&self) -> impl Iterator<Item = &Guard> {
        self.all[..self.n as usize].iter()
    }
}

/// A comparison of a variable that must hold where a read happens ([`Demand::Guarded`]):
/// the variable `op` the constant or root variable `with`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Guard {
    pub op: Cmp,
    pub with: GuardValue,
}

/// What a guard compares its variable with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GuardValue {
    Const(u64),
    /// A root variable, by the index of its read's first token (as
    /// [`Demand::CompareVar`]'s `bound_at`).
    Var(usize),
}

/// A comparison, the guarded variable on its left.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cmp {
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
}

impl Cmp {
    fn of(op: &str) -> Option<Cmp> {
        Some(match op {
            "<" => Cmp::Lt,
            "<=" => Cmp::Le,
            ">" => Cmp::Gt,
            ">=" => Cmp::Ge,
            "==" => Cmp::Eq,
            "!=" => Cmp::Ne,
            _ => return None,
        })
    }
    /// The same comparison with its sides swapped (`c < x` is `x > c`).
    fn swapped(self) -> Cmp {
        match self {
            Cmp::Lt => Cmp::Gt,
            Cmp::Le => Cmp::Ge,
            Cmp::Gt => Cmp::Lt,
            Cmp::Ge => Cmp::Le,
            c => c,
        }
    }
    /// What holds where it does not.
    fn negated(self) -> Cmp {
        match self {
            Cmp::Lt => Cmp::Ge,
            Cmp::Le => Cmp::Gt,
            Cmp::Gt => Cmp::Le,
            Cmp::Ge => Cmp::Lt,
            Cmp::Eq => Cmp::Ne,
            Cmp::Ne => Cmp::Eq,
        }
    }
    /// Whether `a op b`.
    pub fn holds(self, a: u64, b: u64) -> bool {
        match self {
            Cmp::Lt => a < b,
            Cmp::Le => a <= b,
            Cmp::Gt => a > b,
            Cmp::Ge => a >= b,
            Cmp::Eq => a == b,
            Cmp::Ne => a != b,
        }
    }
}

/// The most constants a compared choice may have ([`Demand::CompareConsts`]).
pub const MAX_CHOICES: usize = 8;

/// Every read of a variable in `toks` (a function body) whose statement the parser knows, by
/// the index of its first token (`vlSelf` of `vlSelf->x`, or a local's name): the bits it
/// needs. `width`: a root variable's width in bits, when it is a scalar. Reads in statements
/// the parser does not know are not in the map (a caller takes them as needing all).
pub fn demands(toks: &[Tok], width: &dyn Fn(&str) -> Option<u32>) -> HashMap<usize, Demand> {
    let mut p = Parser { t: toks, i: 0, locals: HashMap::new(), width, out: HashMap::new(), guards: Vec::new() };
    while p.i < toks.len() {
        let start = p.i;
        let mut stmt = Parser {
            t: toks,
            i: start,
            locals: std::mem::take(&mut p.locals),
            width,
            out: HashMap::new(),
            guards: Vec::new(),
        };
        let ok = stmt.statement().is_some();
        p.locals = std::mem::take(&mut stmt.locals);
        if ok && stmt.i > start {
            p.out.extend(stmt.out);
            p.i = stmt.i;
        } else {
            // A statement the parser does not know: skipped whole, its reads unknown.
            p.i = skip_statement(toks, start);
        }
    }
    p.out
}

/// The index after the statement that starts at `i` (its `;` at the same depth, or its
/// braced block).
fn skip_statement(t: &[Tok], mut i: usize) -> usize {
    let mut depth = 0i32;
    let start = i;
    while i < t.len() {
        match t[i] {
            Tok::P("(" | "[" | "{") => depth += 1,
            Tok::P(")" | "]" | "}") => {
                depth -= 1;
                if depth <= 0 && t[i] == Tok::P("}") {
                    return i + 1;
                }
                if depth < 0 {
                    return (i + 1).max(start + 1);
                }
            }
            Tok::P(";") if depth <= 0 => return i + 1,
            _ => {}
        }
        i += 1;
    }
    t.len().max(start + 1)
}

/// An expression, as far as the demand walk needs it.
#[derive(Debug)]
enum Expr {
    /// A variable read: the index of its first token and its name.
    Var(usize, String),
    Num(u64),
    /// A cast to an integer type of this many bits.
    Cast(u32, Box<Expr>),
    Bin(&'static str, Box<Expr>, Box<Expr>),
    Not(Box<Expr>),
    /// `~x`, `-x`: bit by bit (a negation's low bits need only the low bits).
    Bitwise(Box<Expr>),
    Choice(Box<Expr>, Box<Expr>, Box<Expr>),
    /// Anything else (a call, an index, a member of something else): its parts need all.
    Opaque(Vec<Expr>),
}

/// The bits below and at the highest bit of `d`.
fn low(d: u64) -> u64 {
    if d == 0 {
        0
    } else {
        u64::MAX >> d.leading_zeros()
    }
}

fn mask(bits: u32) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

const TYPES: &[(&str, u32)] = &[
    ("CData", 8),
    ("SData", 16),
    ("IData", 32),
    ("QData", 64),
    ("uint8_t", 8),
    ("uint16_t", 16),
    ("uint32_t", 32),
    ("uint64_t", 64),
    ("vluint8_t", 8),
    ("vluint16_t", 16),
    ("vluint32_t", 32),
    ("vluint64_t", 64),
    ("int", 32),
    ("bool", 1),
];

/// Comparisons that hold somewhere, by the variable each compares.
type Held = Vec<(String, Guard)>;

struct Parser<'a, 't> {
    t: &'t [Tok<'a>],
    i: usize,
    /// Locals declared so far, with their types' widths.
    locals: HashMap<&'a str, u32>,
    width: &'t dyn Fn(&str) -> Option<u32>,
    out: HashMap<usize, Demand>,
    /// The comparisons that hold where the parser is (the conditions of the `if`s and `?:`s
    /// around it), by the variable they compare.
    guards: Held,
}

impl<'a, 't> Parser<'a, 't> {
    fn peek(&self, k: usize) -> Tok<'a> {
        self.t.get(self.i + k).copied().unwrap_or(Tok::P(""))
    }
    fn eat(&mut self, p: &str) -> Option<()> {
        (self.peek(0) == Tok::P(p)).then(|| self.i += 1)
    }

    fn statement(&mut self) -> Option<()> {
        match self.peek(0) {
            Tok::P(";") => {
                self.i += 1;
                Some(())
            }
            Tok::P("{") => {
                self.i += 1;
                while self.peek(0) != Tok::P("}") {
                    if self.i >= self.t.len() {
                        return None;
                    }
                    self.statement()?;
                }
                self.i += 1;
                Some(())
            }
            Tok::Id("if") | Tok::Id("while") | Tok::Id("switch") => {
                let switch = self.peek(0) == Tok::Id("switch");
                let is_if = self.peek(0) == Tok::Id("if");
                self.i += 1;
                self.eat("(")?;
                let c = self.expr()?;
                self.eat(")")?;
                self.demand(&c, u64::MAX);
                if switch {
                    return self.switch_body();
                }
                // (A `while`'s body runs where its condition holds too, but it may change it.)
                let (then, otherwise) = if is_if { self.guards_of(&c) } else { (Vec::new(), Vec::new()) };
                self.guarded(then, |p| p.statement())?;
                if self.peek(0) == Tok::Id("else") {
                    self.i += 1;
                    self.guarded(otherwise, |p| p.statement())?;
                }
                Some(())
            }
            Tok::Id("return") => {
                self.i += 1;
                if self.eat(";").is_some() {
                    return Some(());
                }
                let e = self.expr()?;
                self.demand(&e, u64::MAX);
                self.eat(";")
            }
            Tok::Id("break" | "continue") => {
                self.i += 1;
                self.eat(";")
            }
            Tok::Id(ty) if TYPES.iter().any(|(n, _)| *n == ty) && matches!(self.peek(1), Tok::Id(_)) => {
                // A local: `IData __Vdly__x;` or `CData x = e;`.
                let bits = TYPES.iter().find(|(n, _)| *n == ty).map(|(_, b)| *b).unwrap_or(64);
                let Tok::Id(name) = self.peek(1) else { return None };
                self.i += 2;
                self.locals.insert(name, bits);
                if self.eat("=").is_some() {
                    let e = self.expr()?;
                    self.demand(&e, mask(bits));
                }
                self.eat(";")
            }
            _ => {
                // An expression statement, most often an assignment.
                let lhs = self.expr()?;
                let op = match self.peek(0) {
                    Tok::P(op @ ("=" | "|=" | "&=" | "^=" | "+=" | "-=")) => op,
                    Tok::P(";") => {
                        self.demand(&lhs, u64::MAX);
                        self.i += 1;
                        return Some(());
                    }
                    _ => return None,
                };
                self.i += 1;
                let rhs = self.expr()?;
                self.eat(";")?;
                // The destination's width bounds what its value needs; its index is read.
                let bits = match &lhs {
                    Expr::Var(_, name) => self.var_width(name),
                    Expr::Opaque(parts) => {
                        for p in parts {
                            self.demand(p, u64::MAX);
                        }
                        None
                    }
                    _ => None,
                };
                let d = bits.map_or(u64::MAX, mask);
                if op != "=" {
                    // `x |= e` reads x as well.
                    self.demand(&lhs, d);
                }
                self.demand(&rhs, d);
                Some(())
            }
        }
    }

    fn switch_body(&mut self) -> Option<()> {
        self.eat("{")?;
        loop {
            match self.peek(0) {
                Tok::P("}") => {
                    self.i += 1;
                    return Some(());
                }
                Tok::Id("case") => {
                    self.i += 1;
                    self.expr()?;
                    self.eat(":")?;
                }
                Tok::Id("default") => {
                    self.i += 1;
                    self.eat(":")?;
                }
                _ => {
                    if self.i >= self.t.len() {
                        return None;
                    }
                    self.statement()?
                }
            }
        }
    }

    /// A variable's width: a local's type, or the root's scalar.
    fn var_width(&self, name: &str) -> Option<u32> {
        self.locals.get(name).copied().or_else(|| (self.width)(name))
    }

    /// Run `f` with `guards` holding (pushed, then popped).
    fn guarded<T>(&mut self, guards: Held, f: impl FnOnce(&mut Self) -> T) -> T {
        let n = self.guards.len();
        self.guards.extend(guards);
        let out = f(self);
        self.guards.truncate(n);
        out
    }

    /// What holds where condition `c` does (each comparison of a variable with a constant
    /// or a root variable that `&`s or `&&`s together: a 0 there makes it 0), and where it
    /// does not (when `c` is one such comparison).
    fn guards_of(&self, c: &Expr) -> (Held, Held) {
        let mut then = Vec::new();
        self.conjuncts(c, &mut then);
        let otherwise = self
            .comparison(c)
            .map(|(name, g)| vec![(name, Guard { op: g.op.negated(), with: g.with })])
            .unwrap_or_default();
        (then, otherwise)
    }

    fn conjuncts(&self, c: &Expr, out: &mut Vec<(String, Guard)>) {
        match c {
            Expr::Bin("&" | "&&", a, b) => {
                self.conjuncts(a, out);
                self.conjuncts(b, out);
            }
            Expr::Cast(_, x) => self.conjuncts(x, out),
            _ => out.extend(self.comparison(c)),
        }
    }

    /// `c` as a root variable (under casts) compared with a constant or another root
    /// variable, the variable on the left.
    fn comparison(&self, c: &Expr) -> Option<(String, Guard)> {
        let Expr::Bin(op, a, b) = c else { return None };
        let op = Cmp::of(op)?;
        // (Under casts that keep all its bits: a narrowing one compares its low bits only.)
        let root_var = |e: &Expr| -> Option<(usize, String)> {
            let mut e = e;
            let mut kept = u32::MAX;
            while let Expr::Cast(bits, x) = e {
                kept = kept.min(*bits);
                e = x;
            }
            match e {
                Expr::Var(at, name) if !self.locals.contains_key(name.as_str()) => {
                    (self.width)(name).filter(|w| *w <= kept).map(|_| (*at, name.clone()))
                }
                _ => None,
            }
        };
        match (root_var(a), root_var(b), constant(a), constant(b)) {
            (Some((_, x)), _, _, Some(k)) => Some((x, Guard { op, with: GuardValue::Const(k) })),
            (_, Some((_, x)), Some(k), _) => Some((x, Guard { op: op.swapped(), with: GuardValue::Const(k) })),
            (Some((_, x)), Some((at, y)), _, _) if x != y => Some((x, Guard { op, with: GuardValue::Var(at) })),
            _ => None,
        }
    }

    /// Record what `e`'s reads need when `d` of its value's bits are needed.
    fn demand(&mut self, e: &Expr, d: u64) {
        match e {
            Expr::Var(at, name) => {
                let d = self.var_width(name).map_or(d, |w| d & mask(w));
                // The guards of the variable that hold here, the innermost first.
                let none = Guard { op: Cmp::Eq, with: GuardValue::Const(0) };
                let mut guards = Guards { all: [none; MAX_GUARDS], n: 0 };
                for (_, g) in self.guards.iter().rev().filter(|(v, _)| v == name).take(MAX_GUARDS) {
                    guards.all[guards.n as usize] = *g;
                    guards.n += 1;
                }
                match guards.n {
                    0 => self.record(*at, Demand::Bits(d)),
                    _ => self.record(*at, Demand::Guarded { bits: d, guards }),
                }
            }
            Expr::Num(_) => {}
            Expr::Cast(bits, x) => self.demand(x, d & mask(*bits)),
            Expr::Not(x) => self.demand(x, u64::MAX),
            Expr::Bitwise(x) => self.demand(x, low(d)),
            Expr::Choice(c, a, b) => {
                self.demand(c, u64::MAX);
                let (then, otherwise) = self.guards_of(c);
                self.guarded(then, |p| p.demand(a, d));
                self.guarded(otherwise, |p| p.demand(b, d));
            }
            Expr::Opaque(parts) => {
                for p in parts {
                    self.demand(p, u64::MAX);
                }
            }
            Expr::Bin(op, a, b) => match *op {
                "&" => match (constant(a), constant(b)) {
                    (Some(m), _) => self.demand(b, d & m),
                    (_, Some(m)) => self.demand(a, d & m),
                    _ => {
                        self.demand(a, d);
                        self.demand(b, d);
                    }
                },
                "|" | "^" => {
                    self.demand(a, d);
                    self.demand(b, d);
                }
                "+" | "-" => {
                    self.demand(a, low(d));
                    self.demand(b, low(d));
                }
                "<<" | ">>" => match constant(b) {
                    Some(k) if k < 64 => {
                        let moved = if *op == "<<" {
                            d >> k
                        } else if d == u64::MAX {
                            u64::MAX << k
                        } else {
                            d << k
                        };
                        self.demand(a, moved);
                    }
                    _ => {
                        self.demand(a, u64::MAX);
                        self.demand(b, u64::MAX);
                    }
                },
                "==" | "!=" | "<" | ">" | "<=" | ">=" => match (constant(a), constant(b)) {
                    (Some(c), None) => self.compare(b, c),
                    (None, Some(c)) => self.compare(a, c),
                    // Each side a counter the other may bound (a variable, or a choice of
                    // constants), or all of it.
                    _ => {
                        for (x, bound) in [(a, b), (b, a)] {
                            if !self.compare_consts(x, bound) && !self.compare_var(x, bound) {
                                self.demand(x, u64::MAX);
                            }
                        }
                    }
                },
                _ => {
                    self.demand(a, u64::MAX);
                    self.demand(b, u64::MAX);
                }
            },
        }
    }

    /// `e` compared with the constant `c`: a variable (under casts) keeps the constant; a
    /// variable plus a constant, masked, keeps it with the sum's offset and wrap.
    fn compare(&mut self, e: &Expr, c: u64) {
        match e {
            Expr::Var(at, _) => self.record(*at, Demand::Compare(c)),
            // A cast that keeps all the variable's bits (a narrowing one compares its low bits,
            // which repeat: all of it is needed then).
            Expr::Cast(bits, x)
                if matches!(&**x, Expr::Var(_, name) if self.var_width(name).is_some_and(|w| w <= *bits))
                    && c <= mask(*bits) =>
            {
                self.compare(x, c)
            }
            _ => {
                if !self.compare_consts(e, &Expr::Num(c)) {
                    self.demand(e, u64::MAX);
                }
            }
        }
    }

    /// `e` (a variable plus a constant, masked or cast, not the variable alone) compared with
    /// `other`, a constant or a choice of constants: recorded as such when it is one (the
    /// choice's conditions are the other side's business).
    fn compare_consts(&mut self, e: &Expr, other: &Expr) -> bool {
        if matches!(e, Expr::Var(..)) && matches!(other, Expr::Num(_)) {
            return false;
        }
        let mut consts = [0; MAX_CHOICES];
        let mut n = 0;
        if !choices(other, &mut consts, &mut n) {
            return false;
        }
        let Some((at, offset, wrap)) = offset_of(e) else { return false };
        self.record(at, Demand::CompareConsts { consts, n: n as u8, offset, wrap });
        true
    }

    /// `e` (a variable, plus a constant, masked or cast) compared with `bound` (a root
    /// variable, under casts): recorded as such when it is one (the bound's own read is the
    /// other side's business).
    fn compare_var(&mut self, e: &Expr, bound: &Expr) -> bool {
        let mut b = bound;
        while let Expr::Cast(_, x) = b {
            b = x;
        }
        let Expr::Var(bound_at, name) = b else { return false };
        if self.locals.contains_key(name.as_str()) || (self.width)(name).is_none() {
            return false;
        }
        let Some((at, offset, wrap)) = offset_of(e) else { return false };
        self.record(at, Demand::CompareVar { bound_at: *bound_at, offset, wrap });
        true
    }

    fn record(&mut self, at: usize, d: Demand) {
        // A read met twice (never, in a tree) keeps what needs more.
        let d = match (self.out.get(&at), d) {
            (Some(Demand::Bits(a)), Demand::Bits(b)) => Demand::Bits(a | b),
            (Some(Demand::Guarded { bits: a, guards: g }), Demand::Guarded { bits: b, guards: h }) if *g == h => {
                Demand::Guarded { bits: a | b, guards: h }
            }
            (Some(_), _) => Demand::Bits(u64::MAX),
            (None, d) => d,
        };
        self.out.insert(at, d);
    }

    // Expressions, by C's precedence.
    fn expr(&mut self) -> Option<Expr> {
        let c = self.binary(0)?;
        if self.eat("?").is_some() {
            let a = self.expr()?;
            self.eat(":")?;
            let b = self.expr()?;
            return Some(Expr::Choice(Box::new(c), Box::new(a), Box::new(b)));
        }
        Some(c)
    }

    fn binary(&mut self, level: usize) -> Option<Expr> {
        const LEVELS: &[&[&str]] = &[
            &["||"],
            &["&&"],
            &["|"],
            &["^"],
            &["&"],
            &["==", "!="],
            &["<", ">", "<=", ">="],
            &["<<", ">>"],
            &["+", "-"],
            &["*", "/", "%"],
        ];
        if level == LEVELS.len() {
            return self.unary();
        }
        let mut a = self.binary(level + 1)?;
        while let Tok::P(op) = self.peek(0) {
            let Some(op) = LEVELS[level].iter().find(|o| **o == op) else { break };
            self.i += 1;
            let b = self.binary(level + 1)?;
            a = Expr::Bin(op, Box::new(a), Box::new(b));
        }
        Some(a)
    }

    fn unary(&mut self) -> Option<Expr> {
        match self.peek(0) {
            Tok::P("!") => {
                self.i += 1;
                Some(Expr::Not(Box::new(self.unary()?)))
            }
            Tok::P("~" | "-") => {
                self.i += 1;
                Some(Expr::Bitwise(Box::new(self.unary()?)))
            }
            Tok::P("(") => {
                if let (Tok::Id(ty), Tok::P(")")) = (self.peek(1), self.peek(2)) {
                    if let Some((_, bits)) = TYPES.iter().find(|(n, _)| *n == ty) {
                        self.i += 3;
                        return Some(Expr::Cast(*bits, Box::new(self.unary()?)));
                    }
                }
                self.postfix()
            }
            _ => self.postfix(),
        }
    }

    fn postfix(&mut self) -> Option<Expr> {
        let mut e = self.primary()?;
        loop {
            match self.peek(0) {
                Tok::P("[") => {
                    self.i += 1;
                    let idx = self.expr()?;
                    self.eat("]")?;
                    e = Expr::Opaque(vec![e, idx]);
                }
                Tok::P("(") => {
                    self.i += 1;
                    let mut parts = vec![e];
                    if self.eat(")").is_none() {
                        loop {
                            parts.push(self.expr()?);
                            if self.eat(")").is_some() {
                                break;
                            }
                            self.eat(",")?;
                        }
                    }
                    e = Expr::Opaque(parts);
                }
                Tok::P("." | "->") if matches!(self.peek(1), Tok::Id(_)) => {
                    self.i += 2;
                    e = Expr::Opaque(vec![e]);
                }
                _ => return Some(e),
            }
        }
    }

    fn primary(&mut self) -> Option<Expr> {
        let at = self.i;
        match (self.peek(0), self.peek(1), self.peek(2)) {
            (Tok::Id("vlSelf" | "vlSelfRef"), Tok::P("->" | "."), Tok::Id(name)) => {
                self.i += 3;
                Some(Expr::Var(at, name.to_string()))
            }
            (Tok::Num(n), _, _) => {
                self.i += 1;
                Some(number(n).map_or(Expr::Opaque(Vec::new()), Expr::Num))
            }
            (Tok::Str, _, _) => {
                self.i += 1;
                Some(Expr::Opaque(Vec::new()))
            }
            (Tok::Id(name), _, _) => {
                self.i += 1;
                Some(if self.locals.contains_key(name) || name.starts_with("__V") {
                    Expr::Var(at, name.to_string())
                } else {
                    // A function's or a constant's name.
                    Expr::Opaque(Vec::new())
                })
            }
            (Tok::P("("), _, _) => {
                self.i += 1;
                let e = self.expr()?;
                self.eat(")")?;
                Some(e)
            }
            _ => None,
        }
    }
}

/// The constant an expression is (under casts), if it is one.
/// A variable plus a constant, under masks of low bits and casts: the variable's read, the
/// constant, and the mask of the sum (`u64::MAX`: none).
fn offset_of(e: &Expr) -> Option<(usize, u64, u64)> {
    match e {
        Expr::Var(at, _) => Some((*at, 0, u64::MAX)),
        Expr::Cast(bits, x) => offset_of(x).map(|(at, k, w)| (at, k, w & mask(*bits))),
        Expr::Bin("&", a, b) => {
            let (m, x) = match (constant(a), constant(b)) {
                (Some(m), None) => (m, b),
                (None, Some(m)) => (m, a),
                _ => return None,
            };
            // Only a mask of low bits keeps the sum a sum.
            if m == 0 || m & m.wrapping_add(1) != 0 {
                return None;
            }
            offset_of(x).map(|(at, k, w)| (at, k, w & m))
        }
        Expr::Bin("+", a, b) => {
            let (k, x) = match (constant(a), constant(b)) {
                (Some(k), None) => (k, b),
                (None, Some(k)) => (k, a),
                _ => return None,
            };
            offset_of(x).map(|(at, k0, w)| (at, k0.wrapping_add(k), w))
        }
        _ => None,
    }
}

/// The constants `e` may take when it is a constant or a choice (`?:`) of them, into
/// `out[*n..]`; false when it is not, or has more than [`MAX_CHOICES`].
fn choices(e: &Expr, out: &mut [u64; MAX_CHOICES], n: &mut usize) -> bool {
    match e {
        Expr::Choice(_, a, b) => choices(a, out, n) && choices(b, out, n),
        Expr::Cast(_, x) => choices(x, out, n),
        _ => match constant(e) {
            Some(c) if *n < MAX_CHOICES => {
                out[*n] = c;
                *n += 1;
                true
            }
            _ => false,
        },
    }
}

fn constant(e: &Expr) -> Option<u64> {
    match e {
        Expr::Num(n) => Some(*n),
        Expr::Cast(bits, x) => constant(x).map(|v| v & mask(*bits)),
        _ => None,
    }
}

/// A number Verilator writes (`0x3ffffU`, `15U`, `1ULL`), if it is one.
pub fn number(n: &str) -> Option<u64> {
    let n = n.trim_end_matches(['U', 'L', 'u', 'l']);
    match n.strip_prefix("0x").or_else(|| n.strip_prefix("0X")) {
        Some(h) => u64::from_str_radix(h, 16).ok(),
        None => n.parse().ok(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fastforward::cpp::tokens;

    /// The demands of the reads of `x` in `code`, in order.
    fn of_x(code: &str, widths: &[(&str, u32)]) -> Vec<Demand> {
        let toks = tokens(code).unwrap();
        let w = |n: &str| widths.iter().find(|(m, _)| *m == n).map(|(_, b)| *b);
        let d = demands(&toks, &w);
        let mut v: Vec<(usize, Demand)> =
            d.into_iter().filter(|(i, _)| toks.get(i + 2) == Some(&Tok::Id("x")) || toks[*i] == Tok::Id("x")).collect();
        v.sort_by_key(|(i, _)| *i);
        v.into_iter().map(|(_, d)| d).collect()
    }

    /// A tone generator's `count + 1 >= half` with `half` a `case` on the switches, which
    /// Verilator writes as a choice of constants: the count is told apart only at those (less
    /// one), as with a constant alone; the switches are read whole.
    #[test]
    fn a_counter_compared_with_a_choice_of_constants() {
        let w = [("x", 18), ("sw", 16)];
        let code = "if (((0x3ffffU & ((IData)(1U) + vlSelf->x)) >= ((0U == (7U & (IData)(vlSelf->sw))) \
                    ? 0x2e978U : ((5U == (7U & (IData)(vlSelf->sw))) ? 0x1bbe4U : 0x1f23fU)))) { vlSelf->y = 0U; }";
        let mut consts = [0; MAX_CHOICES];
        consts[..3].copy_from_slice(&[0x2e978, 0x1bbe4, 0x1f23f]);
        assert_eq!(of_x(code, &w), [Demand::CompareConsts { consts, n: 3, offset: 1, wrap: 0x3ffff }]);
        // With one constant, plus one and masked.
        let code = "vlSelf->y = ((0x3ffffU & ((IData)(1U) + vlSelf->x)) == 0x1f23fU);";
        let mut one = [0; MAX_CHOICES];
        one[0] = 0x1f23f;
        assert_eq!(of_x(code, &w), [Demand::CompareConsts { consts: one, n: 1, offset: 1, wrap: 0x3ffff }]);
        // A choice with a variable in it is no choice of constants: all of it.
        let code = "vlSelf->y = (vlSelf->x >= ((1U & vlSelf->sw) ? 5U : vlSelf->sw));";
        assert_eq!(of_x(code, &w), [Demand::Bits(0x3ffff)]);
    }

    fn guards(g: &[Guard]) -> Guards {
        let mut all = [Guard { op: Cmp::Eq, with: GuardValue::Const(0) }; MAX_GUARDS];
        all[..g.len()].copy_from_slice(g);
        Guards { all, n: g.len() as u8 }
    }

    /// A sprite's row inside its window (Verilator's `&` of the comparisons, as it writes an
    /// `if` of `&&`s): the row's low bits are read only where both of its comparisons hold;
    /// each comparison is a read of its own. A choice's arms are guarded alike, the other arm
    /// by the comparison's negation; a condition that is no comparison of it guards nothing.
    #[test]
    fn a_read_inside_a_comparison_of_its_variable_is_guarded_by_it() {
        let w = [("x", 10), ("start", 10), ("end", 10), ("col", 10), ("a", 4)];
        let code = "if ((((IData)(vlSelf->x) >= (IData)(vlSelf->start)) & ((IData)(vlSelf->x) <= 0x1f0U)) \
                    & (vlSelf->col >= vlSelf->start)) { vlSelf->a = (0xfU & ((IData)(vlSelf->x) - (IData)(vlSelf->start))); } \
                    else { vlSelf->a = (0xfU & vlSelf->x); }";
        let toks = tokens(code).unwrap();
        let at = |n: usize| toks.iter().enumerate().filter(|(_, t)| **t == Tok::Id("start")).nth(n).unwrap().0 - 2;
        let d = of_x(code, &w);
        assert_eq!(d[0], Demand::CompareVar { bound_at: at(0), offset: 0, wrap: 0xffff_ffff });
        assert_eq!(d[1], Demand::Compare(0x1f0));
        // Both comparisons of x, the innermost (its last) first.
        let le = Guard { op: Cmp::Le, with: GuardValue::Const(0x1f0) };
        let ge = Guard { op: Cmp::Ge, with: GuardValue::Var(at(0)) };
        assert_eq!(d[2], Demand::Guarded { bits: 0xf, guards: guards(&[le, ge]) });
        // Not one comparison: the else arm is not guarded.
        assert_eq!(d[3], Demand::Bits(0xf));
        assert_eq!(d.len(), 4);
        // One comparison (the constant on the left, or a choice's condition): each arm is
        // guarded by its side of it.
        let two_sided = |code: &str, k: u64, op: Cmp, then: u64, otherwise: u64| {
            let g = |op: Cmp| guards(&[Guard { op, with: GuardValue::Const(k) }]);
            let want = [
                Demand::Compare(k),
                Demand::Guarded { bits: then, guards: g(op) },
                Demand::Guarded { bits: otherwise, guards: g(op.negated()) },
            ];
            assert_eq!(of_x(code, &w), want, "{code}");
        };
        let code = "if ((0x20U < vlSelf->x)) { vlSelf->a = vlSelf->x; } else { vlSelf->a = (vlSelf->x >> 2U); }";
        two_sided(code, 0x20, Cmp::Gt, 0xf, 0x3c);
        let code = "vlSelf->a = ((0x1fU == vlSelf->x) ? vlSelf->x : (vlSelf->x >> 4U));";
        two_sided(code, 0x1f, Cmp::Eq, 0xf, 0xf0);
        // A narrowing cast compares the low bits only: no guard of the variable, and the
        // comparison is of a sum that wraps at 8 bits (which spoils a wider counter).
        let code = "if (((CData)(vlSelf->x) < 3U)) { vlSelf->a = vlSelf->x; }";
        let mut three = [0; MAX_CHOICES];
        three[0] = 3;
        assert_eq!(
            of_x(code, &w),
            [Demand::CompareConsts { consts: three, n: 1, offset: 0, wrap: 0xff }, Demand::Bits(0xf)]
        );
        // An `|` of comparisons, or a comparison of another variable only: nothing guarded.
        let code = "if (((vlSelf->x < 3U) | (vlSelf->col > 5U))) { vlSelf->a = vlSelf->x; }";
        assert_eq!(of_x(code, &w), [Demand::Compare(3), Demand::Bits(0xf)]);
        let code = "if ((vlSelf->col > 5U)) { vlSelf->a = vlSelf->x; }";
        assert_eq!(of_x(code, &w), [Demand::Bits(0xf)]);
    }

    #[test]
    fn each_shape_of_read_needs_the_bits_it_uses() {
        let w = [("x", 27), ("an", 8), ("wide", 32), ("y", 27)];
        // Into an 8-bit variable, through a choice (a port's read mux).
        assert_eq!(of_x("vlSelf->an = (vlSelf->s ? vlSelf->x : vlSelf->y);", &w), [Demand::Bits(0xff)]);
        // A shift then a mask: bits 15-17.
        assert_eq!(of_x("vlSelf->an = (7U & (vlSelf->x >> 0xfU));", &w), [Demand::Bits(7 << 15)]);
        // A sum shown on 8 bits needs the low 8 bits only.
        assert_eq!(of_x("vlSelf->an = ((IData)(1U) + vlSelf->x);", &w), [Demand::Bits(0xff)]);
        // A mask, either side.
        assert_eq!(of_x("vlSelf->wide = (vlSelf->x & 0x80000U);", &w), [Demand::Bits(0x80000)]);
        // Plus a constant, masked, compared with another root variable: that variable bounds it.
        let toks = crate::fastforward::cpp::tokens(
            "if (((0xffffffU & ((IData)(1U) + vlSelf->x)) >= vlSelf->half)) { vlSelf->an = 0U; }",
        )
        .unwrap();
        let widths = |n: &str| (n == "x" || n == "half" || n == "an").then_some(24);
        let d = demands(&toks, &widths);
        let at = |name: &str| toks.iter().position(|t| *t == Tok::Id(name)).unwrap() - 2;
        assert_eq!(d.get(&at("x")), Some(&Demand::CompareVar { bound_at: at("half"), offset: 1, wrap: 0xffffff }));
        assert_eq!(d.get(&at("half")), Some(&Demand::Bits(0xffffff)));
        // Two variables: each bounds the other.
        let toks = crate::fastforward::cpp::tokens("vlSelf->an = (vlSelf->x == vlSelf->half);").unwrap();
        let d = demands(&toks, &widths);
        assert_eq!(d.get(&2), None);
        assert_eq!(d.get(&5), Some(&Demand::CompareVar { bound_at: 9, offset: 0, wrap: u64::MAX }));
        assert_eq!(d.get(&9), Some(&Demand::CompareVar { bound_at: 5, offset: 0, wrap: u64::MAX }));
        // Compared with a constant (under a cast), or with a variable.
        assert_eq!(of_x("vlSelf->an = (0x16eb4eU == (IData)(vlSelf->x));", &w), [Demand::Compare(0x16eb4e)]);
        assert_eq!(
            of_x("vlSelf->an = (vlSelf->x < vlSelf->y);", &w),
            [Demand::CompareVar { bound_at: 9, offset: 0, wrap: u64::MAX }]
        );
        // With something that is not a root variable: all of it.
        assert_eq!(of_x("vlSelf->an = (vlSelf->x < (vlSelf->y + vlSelf->an));", &w), [Demand::Bits((1 << 27) - 1)]);
        // In a condition, a call, an index: all of it.
        assert_eq!(of_x("if (vlSelf->x) { vlSelf->an = 1U; }", &w), [Demand::Bits((1 << 27) - 1)]);
        assert_eq!(of_x("vlSelf->an = VL_REDXOR_32(vlSelf->x);", &w), [Demand::Bits((1 << 27) - 1)]);
        // Into a local: its type's width.
        assert_eq!(of_x("CData t; t = vlSelf->x; vlSelf->an = t;", &w), [Demand::Bits(0xff)]);
    }

    #[test]
    fn a_statement_it_does_not_know_leaves_its_reads_unknown_and_goes_on() {
        let toks = tokens("for (i = 0; i < 4; ++i) { vlSelf->an = vlSelf->x; }\nvlSelf->an = vlSelf->x;").unwrap();
        let d = demands(&toks, &|n| (n == "an").then_some(8).or((n == "x").then_some(27)));
        let reads: Vec<usize> = d.keys().copied().filter(|i| toks[i + 2] == Tok::Id("x")).collect();
        // Only the second read, after the loop the parser does not follow.
        assert_eq!(reads.len(), 1);
        assert!(reads[0] > toks.iter().position(|t| *t == Tok::P("}")).unwrap());
    }
}
