//! Counters the fast-forward may move on by arithmetic instead of waiting for them to repeat:
//! found in the C++ Verilator generates, at build time.
//!
//! A team's design is full of free-running counters: the display's refresh counter, clock
//! dividers, blink counters, a 32-bit cycle count. Each repeats only after its whole range,
//! and together their state repeats after the least common multiple of their periods, far
//! longer than a bot sample. But the rest of the design sees little of them: the display
//! reads the refresh counter's top bits, a divider's own comparison with its terminal count
//! says when its toggle flips. A **counter** here is a variable of the root whose every write
//! in the evaluation
//! - adds a constant to it, or subtracts one (`x = (0x3ffffU & ((IData)(1U) + x))`), always in
//!   the same direction, directly or through Verilator's delayed copy (`__Vdly__x`); or
//! - sets it to a constant (a reset, a wrap at a terminal count),
//!
//! and whose every other read needs only some of its bits or compares it with a constant (or,
//! plus a constant, with another root variable: a tone generator's `count + 1 >= half`; that
//! variable is the counter's [`Counter::bounds`], read by the harness at the mark, and must
//! hold while the counter counts), as
//! [`super::demand`] finds for any expression around the read: a shift then a mask
//! (`7U & (x >> 0xfU)`: bits 15-17), a value stored into fewer bits (a port's read mux into
//! an 8-bit register: bits 0-7), a comparison with a constant (`0x7a11fU == x`). A read of
//! every bit spoils it (it is then plain state). Between two values at which such a read
//! could change (the next multiple of 2^shift, a compared constant, the wrap), nothing else in
//! the design can tell the counter's value: the harness (harness.cpp) then proves the rest
//! periodic, confirms that each counter moved by the same amount in two periods in a row, and
//! moves it on by that amount per skipped period, up to just before the first value that could
//! be told apart. Reads of its low bits alone ([`Counter::split`]) let those repeat as state
//! while the rest counts.
//!
//! ```
//! let root = "class Vboard___024root final : public VerilatedModule {\n  public:\n    struct {\n        VL_IN8(clk,0,0);\n        VL_OUT8(an,7,0);\n        IData/*17:0*/ refresh;\n    };\n};\n";
//! let nba = "void f(Vboard___024root* vlSelf) {\n    vlSelf->refresh = (0x3ffffU & ((IData)(1U) + vlSelf->refresh));\n    vlSelf->an = (7U & (vlSelf->refresh >> 0xfU));\n}\n";
//! let found = botsim::fastforward::counters::find(root, &[nba], &["f".to_string()], &[], &|_| true);
//! assert_eq!(found.len(), 1);
//! assert_eq!((found[0].name.as_str(), found[0].bits, found[0].step, found[0].shift), ("refresh", 18, 1, Some(15)));
//! ```

use std::collections::{BTreeMap, BTreeSet, HashSet};

use super::cpp::{closing, functions, strip_comments, tokens, Tok};
use super::demand::{demands, Cmp, Demand, GuardValue};

/// A counter of the root, as the harness moves it on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Counter {
    pub name: String,
    /// Its width in bits (it wraps at 2^bits).
    pub bits: u32,
    /// It counts down (every step subtracts).
    pub down: bool,
    /// The largest step of one write.
    pub step: u64,
    /// The lowest bit a shifted read sees, if any read shifts it.
    pub shift: Option<u32>,
    /// The constants it is compared with.
    pub consts: Vec<u64>,
    /// Where its bits split in two that no shifted or masked read sees both of, the low ones
    /// read by masks alone (a 32-bit counter whose low byte a PWM compares with a variable,
    /// whose bit 26 blinks an LED; a wrap counter whose low byte a port reads): the low part
    /// then repeats with a short period while the whole value counts, up to the next
    /// compared constant. `None` when no read leaves such a split.
    pub split: Option<u32>,
    /// The lowest bit a read above the split sees, if any read does.
    pub split_shift: Option<u32>,
    /// The root variables it is compared with, each with the constant added to the counter
    /// first (`(x + 1) >= half`: `("half", 1)`): while one holds, its value tells the
    /// counter apart only there (and where the sum wraps).
    pub bounds: Vec<(String, u64)>,
    /// Reads that happen only where a comparison of the counter holds (a sprite's row
    /// within its window, [`Demand::Guarded`]), by the lowest bit each sees: they count
    /// (as [`Counter::shift`]'s reads do) only in an interval where the guard holds.
    pub guarded: Vec<GuardedRead>,
    /// The constants it may be set to (a reset, a wrap at a terminal count; a delayed
    /// copy's initialisation too): a period in which it never took one of them cannot have
    /// set it to one, so every period after moves it as far (the harness's one-period proof).
    pub sets: Vec<u64>,
}

/// A read of a counter's bits from `lo` up that happens only where each of `guards` holds:
/// the counter compared so with a constant or one of its [`Counter::bounds`] (its index).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GuardedRead {
    pub lo: u32,
    pub guards: Vec<(Cmp, GuardedBy)>,
}

/// What a [`GuardedRead`]'s guard compares the counter with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GuardedBy {
    Const(u64),
    Bound(usize),
}

/// The smallest bit `e` (0 < e < bits) at which every shifted or masked read's bits
/// (`lo..=hi`) lie wholly below or wholly at and above it, with some read below; and the
/// lowest bit a read above it sees. (A comparison with a constant is no read here: it tells
/// the counter apart only at the constant, which bounds its interval at any split.)
///
/// ```
/// use botsim::fastforward::counters::split;
/// // A PWM reads bits 0-7, an LED bit 26: the low byte repeats, the rest counts.
/// assert_eq!(split(32, &[(0, 7), (26, 26)]), Some((8, Some(26))));
/// // A shift by 4 reads bits 4-31: it straddles bit 8.
/// assert_eq!(split(32, &[(0, 7), (4, 31)]), None);
/// ```
pub fn split(bits: u32, reads: &[(u32, u32)]) -> Option<(u32, Option<u32>)> {
    let mut candidates: Vec<u32> = reads.iter().map(|&(_, hi)| hi + 1).filter(|&e| e < bits).collect();
    candidates.sort_unstable();
    let e = candidates.into_iter().find(|&e| reads.iter().all(|&(lo, hi)| hi < e || lo >= e))?;
    Some((e, reads.iter().filter(|&&(lo, _)| lo >= e).map(|&(lo, _)| lo).min()))
}

/// The counters among the root's scalar variables (its header `root`), from the evaluation's
/// files `code`, reading the functions named `reached` (those the evaluation runs); `exclude`:
/// variables the harness writes or reads itself; `observed`: whether a run observes a
/// variable (a read that only computes one it does not, such as a VGA pin, is no read).
pub fn find(
    root: &str,
    code: &[&str],
    reached: &[String],
    exclude: &[String],
    observed: &dyn Fn(&str) -> bool,
) -> Vec<Counter> {
    let widths = scalar_widths(root);
    let ports = port_widths(root);
    let mut bodies: BTreeMap<&str, &str> = BTreeMap::new();
    for c in code {
        for (name, body) in functions(c) {
            bodies.insert(name, body);
        }
    }
    let mut seen: BTreeMap<String, Seen> = BTreeMap::new();
    let mut spoiled: HashSet<String> = exclude.iter().cloned().collect();
    for f in reached {
        let Some(body) = bodies.get(f.as_str()) else { continue };
        let Ok(toks) = tokens(body) else {
            // Nothing in a function the tokenizer cannot read may be trusted.
            return Vec::new();
        };
        scan(&toks, &widths, &ports, observed, &mut seen, &mut spoiled);
    }
    let found: Vec<Counter> = seen
        .into_iter()
        .filter(|(name, s)| !spoiled.contains(name) && s.step > 0)
        .map(|(name, mut s)| {
            let bits = widths[&name];
            let consts: Vec<u64> =
                s.consts.into_iter().collect::<std::collections::BTreeSet<_>>().into_iter().collect();
            let bounds: Vec<(String, u64)> =
                s.bounds.into_iter().collect::<std::collections::BTreeSet<_>>().into_iter().collect();
            // A guarded read counts as such only where the counter's interval stops at the
            // guard's value (the guard's own comparison is among its reads); else always.
            let mut guarded = Vec::new();
            // (A read needs all its guards to hold: one that does not stop the interval is
            // left out, and the read counts where the others hold.)
            for (lo, hi, guards) in s.guarded {
                let guards: Vec<(Cmp, GuardedBy)> = guards
                    .into_iter()
                    .filter_map(|(op, with)| {
                        let with = match with {
                            Guarding::Const(k) => consts.binary_search(&k).ok().map(|_| GuardedBy::Const(k)),
                            Guarding::Var(v) => {
                                bounds.iter().position(|(b, off)| *b == v && *off == 0).map(GuardedBy::Bound)
                            }
                        };
                        with.map(|w| (op, w))
                    })
                    .collect();
                let read = GuardedRead { lo, guards };
                if read.guards.is_empty() {
                    s.shift = Some(s.shift.map_or(lo, |x| x.min(lo)));
                } else if !guarded.contains(&read) {
                    guarded.push(read);
                }
                s.reads.push((lo, hi));
            }
            let cut = split(bits, &s.reads);
            Counter {
                bits,
                name,
                down: s.down,
                step: s.step,
                shift: s.shift,
                consts,
                split: cut.map(|(e, _)| e),
                split_shift: cut.and_then(|(_, lo)| lo),
                bounds,
                guarded,
                sets: s.sets.into_iter().collect(),
            }
        })
        .collect();
    // A delayed copy in the root counts with its variable (equal after every evaluation):
    // moved on by the same amount, it is a counter too.
    let mut out = Vec::with_capacity(found.len());
    for c in found {
        let twin = format!("__Vdly__{}", c.name);
        if widths.contains_key(&twin) {
            out.push(Counter { name: twin, ..c.clone() });
        }
        out.push(c);
    }
    out
}

/// The root variable whose delayed copy `name` is (`__Vdly__x`: `x`), local or kept in the
/// root.
fn delayed<'a>(name: &'a str, widths: &BTreeMap<String, u32>) -> Option<&'a str> {
    name.strip_prefix("__Vdly__").filter(|v| widths.contains_key(*v))
}

/// What the scan found of one variable so far.
#[derive(Default)]
struct Seen {
    up: bool,
    down: bool,
    step: u64,
    shift: Option<u32>,
    consts: Vec<u64>,
    /// The bits each shifted or masked read sees (`lo..=hi`).
    reads: Vec<(u32, u32)>,
    /// The root variables it is compared with, and the constant added to it first.
    bounds: Vec<(String, u64)>,
    /// The bits each guarded read sees (`lo..=hi`), and its guard.
    guarded: Vec<SeenGuarded>,
    /// The constants written to it.
    sets: BTreeSet<u64>,
}

/// A guarded read as the scan finds it: the bits it sees (`lo`, `hi`) and its guards.
type SeenGuarded = (u32, u32, Vec<(Cmp, Guarding)>);

/// What a guard compares a candidate with, as the scan finds it.
enum Guarding {
    Const(u64),
    Var(String),
}

/// The root's scalar integer variables (`CData`..`QData`, not ports) and their widths, from
/// the `/*H:L*/` comment Verilator writes beside each.
pub(super) fn scalar_widths(root: &str) -> BTreeMap<String, u32> {
    let mut out = BTreeMap::new();
    for line in root.lines() {
        let t = line.trim();
        let Some(ty) = ["CData/*", "SData/*", "IData/*", "QData/*"].iter().find(|p| t.starts_with(**p)) else {
            continue;
        };
        let rest = &t[ty.len()..];
        let Some((range, decl)) = rest.split_once("*/") else { continue };
        let Some((hi, lo)) = range.split_once(':') else { continue };
        let (Ok(hi), Ok(0)) = (hi.parse::<u32>(), lo.parse::<u32>()) else { continue };
        let name = strip_comments(decl);
        let name = name.trim().trim_end_matches(';').trim();
        if !name.is_empty() && name.chars().all(|c| c.is_alphanumeric() || c == '_') {
            out.insert(name.to_string(), hi + 1);
        }
    }
    out
}

/// The root's ports (`VL_IN8(clk,0,0);`, `VL_OUT16(led,15,0);`) and their widths: what a
/// value written to one needs.
fn port_widths(root: &str) -> BTreeMap<String, u32> {
    let mut out = BTreeMap::new();
    for line in root.lines() {
        let t = line.trim();
        let Some(args) = ["VL_IN8(", "VL_IN16(", "VL_IN(", "VL_IN64(", "VL_OUT8(", "VL_OUT16(", "VL_OUT(", "VL_OUT64("]
            .iter()
            .find_map(|p| t.strip_prefix(p))
        else {
            continue;
        };
        let parts: Vec<&str> = args.trim_end_matches(");").split(',').map(str::trim).collect();
        if let [name, hi, lo] = parts[..] {
            if let (Ok(hi), Ok(lo)) = (hi.parse::<u32>(), lo.parse::<u32>()) {
                out.insert(name.to_string(), hi - lo + 1);
            }
        }
    }
    out
}

/// The low `bits` bits.
fn mask(bits: u32) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// A number Verilator writes (`0x3ffffU`, `15U`, `1ULL`), if it is one.
fn number(t: Tok) -> Option<u64> {
    let Tok::Num(n) = t else { return None };
    super::demand::number(n)
}

/// Scan one function's tokens.
fn scan(
    toks: &[Tok],
    widths: &BTreeMap<String, u32>,
    ports: &BTreeMap<String, u32>,
    observed: &dyn Fn(&str) -> bool,
    seen: &mut BTreeMap<String, Seen>,
    spoiled: &mut HashSet<String>,
) {
    let tok = |i: usize| toks.get(i).copied().unwrap_or(Tok::P(""));
    // The right-hand sides of writes to variables no run observes: what they read is no read.
    let mut unobserved = vec![false; toks.len()];
    let mut j = 0;
    while j + 3 < toks.len() {
        let start = j == 0 || matches!(tok(j - 1), Tok::P(";" | "{" | "}" | ")") | Tok::Id("else"));
        if let (true, Tok::Id("vlSelf"), Tok::P("->"), Tok::Id(y), Tok::P("=")) =
            (start, tok(j), tok(j + 1), tok(j + 2), tok(j + 3))
        {
            if !observed(y) {
                let end = (j + 4..toks.len()).find(|&k| tok(k) == Tok::P(";")).unwrap_or(toks.len());
                unobserved[j + 4..end].iter_mut().for_each(|u| *u = true);
                j = end;
                continue;
            }
        }
        j += 1;
    }
    // What each read needs of the variable it reads.
    let reads = demands(toks, &|n| widths.get(n).or_else(|| ports.get(n)).copied());
    // Every use of a candidate: `vlSelf->x` (3 tokens) or its delayed copy `__Vdly__x`.
    let use_at = |i: usize| -> Option<(&str, usize)> {
        match (tok(i), tok(i + 1), tok(i + 2)) {
            // A delayed copy kept in the root (a variable tested in several always blocks):
            // a use of the variable itself, whose twin it is after every evaluation.
            (Tok::Id("vlSelf"), Tok::P("->"), Tok::Id(m)) if delayed(m, widths).is_some() => {
                delayed(m, widths).map(|v| (v, 3))
            }
            (Tok::Id("vlSelf"), Tok::P("->"), Tok::Id(m)) if widths.contains_key(m) => Some((m, 3)),
            (Tok::Id(l), _, _) if i == 0 || tok(i - 1) != Tok::P("->") => delayed(l, widths).map(|m| (m, 1)),
            _ => None,
        }
    };
    // The extent of a use with the parentheses and casts around it: `((IData)(vlSelf->x))`.
    let wrapped = |mut a: usize, mut b: usize| -> (usize, usize) {
        loop {
            if a >= 1 && tok(a - 1) == Tok::P("(") && tok(b) == Tok::P(")") {
                a -= 1;
                b += 1;
            } else if a >= 3
                && tok(a - 1) == Tok::P(")")
                && matches!(tok(a - 2), Tok::Id("CData" | "SData" | "IData" | "QData"))
                && tok(a - 3) == Tok::P("(")
            {
                a -= 3;
            } else {
                return (a, b);
            }
        }
    };
    let mut consumed: HashSet<usize> = HashSet::new();
    let mut i = 0;
    while i < toks.len() {
        let Some((name, len)) = use_at(i) else {
            i += 1;
            continue;
        };
        if consumed.contains(&i) || unobserved[i] {
            i += len;
            continue;
        }
        // A declaration of the delayed copy: `IData/*17:0*/ __Vdly__x;`.
        if i >= 1 && matches!(tok(i - 1), Tok::Id("CData" | "SData" | "IData" | "QData")) && tok(i + len) == Tok::P(";")
        {
            i += len;
            continue;
        }
        let (a, b) = wrapped(i, i + len);
        let s = seen.entry(name.to_string()).or_default();
        let statement_start = a == 0 || matches!(tok(a - 1), Tok::P(";" | "{" | "}" | ")") | Tok::Id("else"));
        if tok(b) == Tok::P("=") && statement_start && a == i {
            // A write: what may it be?
            let end = (b + 1..toks.len()).find(|&j| tok(j) == Tok::P(";")).unwrap_or(toks.len());
            match write_kind(&toks[b + 1..end], name, widths) {
                Some(writes) => {
                    for w in writes {
                        match w {
                            Write::Const(k) => {
                                s.sets.insert(k & mask(widths[name]));
                            }
                            Write::Copy { at } => {
                                consumed.insert(b + 1 + at);
                            }
                            Write::Step { by, down, at } => {
                                if down {
                                    s.down = true;
                                } else {
                                    s.up = true;
                                }
                                s.step = s.step.max(by);
                                consumed.insert(b + 1 + at);
                            }
                        }
                    }
                }
                None => {
                    spoiled.insert(name.to_string());
                }
            }
            if s.up && s.down {
                spoiled.insert(name.to_string());
            }
            // Reads of other variables on the right are classified as any read.
            i = b + 1;
            continue;
        }
        // A read: the bits of it that matter there (src/fastforward/demand.rs).
        let bits = widths[name];
        match reads.get(&i) {
            Some(Demand::Compare(c)) => s.consts.push(*c),
            // Compared with another root variable (not itself): the sum must wrap no sooner
            // than the counter does.
            Some(&Demand::CompareVar { bound_at, offset, wrap }) => match use_at(bound_at) {
                Some((bound, 3)) if bound != name && wrap >= mask(bits) => {
                    s.bounds.push((bound.to_string(), offset & mask(bits)))
                }
                _ => {
                    spoiled.insert(name.to_string());
                }
            },
            // Compared, plus a constant, with constants (a choice of them): told apart only
            // at each (less the constant) and where the sum wraps, which must be no sooner
            // than the counter does.
            Some(&Demand::CompareConsts { consts, n, offset, wrap }) if wrap >= mask(bits) => {
                let m = mask(bits);
                s.consts.extend(consts[..n as usize].iter().map(|c| c.wrapping_sub(offset) & m));
                if offset & m != 0 {
                    s.consts.push(0u64.wrapping_sub(offset) & m);
                }
            }
            Some(Demand::CompareConsts { .. }) => {
                spoiled.insert(name.to_string());
            }
            Some(Demand::Bits(m)) => {
                let m = m & if bits >= 64 { u64::MAX } else { (1u64 << bits) - 1 };
                let (lo, hi) = (m.trailing_zeros(), 63 - m.leading_zeros().min(63));
                if m == 0 {
                    // Nothing of it matters there.
                } else if lo == 0 && hi + 1 >= bits {
                    // All of it: a counter's every step shows.
                    spoiled.insert(name.to_string());
                } else {
                    s.shift = Some(s.shift.map_or(lo, |x| x.min(lo)));
                    s.reads.push((lo, hi));
                }
            }
            Some(&Demand::Guarded { bits: m, guards }) => {
                let m = m & mask(bits);
                let guards: Vec<(Cmp, Guarding)> = guards
                    .iter()
                    .filter_map(|g| match g.with {
                        GuardValue::Const(k) => Some((g.op, Guarding::Const(k))),
                        GuardValue::Var(at) => match use_at(at) {
                            Some((bound, 3)) if bound != name => Some((g.op, Guarding::Var(bound.to_string()))),
                            _ => None,
                        },
                    })
                    .collect();
                if m != 0 {
                    let (lo, hi) = (m.trailing_zeros(), 63 - m.leading_zeros().min(63));
                    if !guards.is_empty() {
                        s.guarded.push((lo, hi, guards));
                    } else if lo == 0 && hi + 1 >= bits {
                        spoiled.insert(name.to_string());
                    } else {
                        s.shift = Some(s.shift.map_or(lo, |x| x.min(lo)));
                        s.reads.push((lo, hi));
                    }
                }
            }
            // In a statement the parser does not know.
            None => {
                spoiled.insert(name.to_string());
            }
        }
        i += len;
    }
}

/// What a write to a candidate gives it.
#[derive(Debug, PartialEq, Eq)]
enum Write {
    /// A constant.
    Const(u64),
    /// The variable itself or its delayed copy (`__Vdly__x = vlSelf->x`, `vlSelf->x = __Vdly__x`);
    /// `at`: where that read is in the right-hand side.
    Copy { at: usize },
    /// Itself plus or minus `by`; `at`: where its own read is.
    Step { by: u64, down: bool, at: usize },
}

/// What the right-hand side `rhs` of a write to `name` gives it: one [`Write`], or one for
/// each branch of a choice (`c ? 0U : (0xfffffU & (1U + x))`, Verilator's `if`); `None`
/// for anything else. The choice's condition is read as any expression is.
fn write_kind(rhs: &[Tok], name: &str, widths: &BTreeMap<String, u32>) -> Option<Vec<Write>> {
    let mut out = Vec::new();
    kinds(rhs, 0, rhs.len(), name, widths, &mut out)?;
    Some(out)
}

fn kinds(
    rhs: &[Tok],
    from: usize,
    to: usize,
    name: &str,
    widths: &BTreeMap<String, u32>,
    out: &mut Vec<Write>,
) -> Option<()> {
    let (from, to) = strip(rhs, from, to);
    // A choice at the top level: its branches.
    let mut depth = 0i32;
    let (mut question, mut nested) = (None, 0);
    for (j, t) in rhs[from..to].iter().enumerate() {
        match t {
            Tok::P("(" | "[") => depth += 1,
            Tok::P(")" | "]") => depth -= 1,
            Tok::P("?") if depth == 0 => {
                if question.is_none() {
                    question = Some(from + j);
                } else {
                    nested += 1;
                }
            }
            Tok::P(":") if depth == 0 && question.is_some() => {
                if nested > 0 {
                    nested -= 1;
                } else {
                    let q = question?;
                    kinds(rhs, q + 1, from + j, name, widths, out)?;
                    return kinds(rhs, from + j + 1, to, name, widths, out);
                }
            }
            _ => {}
        }
    }
    out.push(one_kind(rhs, from, to, name, widths)?);
    Some(())
}

/// `from..to` without the parentheses that enclose all of it.
fn strip(rhs: &[Tok], mut from: usize, mut to: usize) -> (usize, usize) {
    while to >= from + 2 && rhs[from] == Tok::P("(") && rhs[to - 1] == Tok::P(")") && closing(rhs, from) == Some(to - 1)
    {
        from += 1;
        to -= 1;
    }
    (from, to)
}

/// One branch: a constant, a copy, or a step (under a mask as wide as the variable).
fn one_kind(rhs: &[Tok], from: usize, to: usize, name: &str, widths: &BTreeMap<String, u32>) -> Option<Write> {
    let (mut from, mut to) = strip(rhs, from, to);
    if to == from + 1 && number(rhs[from]).is_some() {
        return number(rhs[from]).map(Write::Const);
    }
    let is_self = |a: usize, b: usize| -> bool {
        let m = |t: &Tok| matches!(t, Tok::Id(x) if *x == name);
        match &rhs[a..b] {
            [Tok::Id("vlSelf"), Tok::P("->"), x] => m(x) || matches!(x, Tok::Id(v) if delayed(v, widths) == Some(name)),
            [Tok::Id(l)] => delayed(l, widths) == Some(name),
            _ => false,
        }
    };
    // A cast `(IData)` and parentheses around an operand.
    let operand = |mut a: usize, mut b: usize| -> (usize, usize) {
        loop {
            if b >= a + 3
                && rhs[a] == Tok::P("(")
                && matches!(rhs[a + 1], Tok::Id("CData" | "SData" | "IData" | "QData"))
                && rhs[a + 2] == Tok::P(")")
            {
                a += 3;
            } else if b >= a + 2 && rhs[a] == Tok::P("(") && closing(rhs, a) == Some(b - 1) {
                a += 1;
                b -= 1;
            } else {
                return (a, b);
            }
        }
    };
    let (a, b) = operand(from, to);
    if is_self(a, b) {
        return Some(Write::Copy { at: a });
    }
    if to > from + 2 && number(rhs[from]).is_some() && rhs[from + 1] == Tok::P("&") {
        // A mask as wide as the variable: the sum wraps as the variable does.
        let mask = number(rhs[from])?;
        let bits = widths[name];
        if bits < 64 && mask != (1u64 << bits) - 1 {
            return None;
        }
        (from, to) = strip(rhs, from + 2, to);
    }
    // `A + B` or `A - B` at the top level.
    let mut depth = 0i32;
    let mut op = None;
    for (j, t) in rhs[from..to].iter().enumerate() {
        match t {
            Tok::P("(") => depth += 1,
            Tok::P(")") => depth -= 1,
            Tok::P(p @ ("+" | "-")) if depth == 0 => {
                if op.is_some() {
                    return None;
                }
                op = Some((from + j, *p));
            }
            Tok::P(p) if depth == 0 && *p != "->" => return None,
            _ => {}
        }
    }
    let (at, op) = op?;
    let (la, lb) = operand(from, at);
    let (ra, rb) = operand(at + 1, to);
    let constant = |a: usize, b: usize| if b == a + 1 { number(rhs[a]) } else { None };
    match op {
        "+" if is_self(la, lb) => constant(ra, rb).filter(|&c| c > 0).map(|by| Write::Step { by, down: false, at: la }),
        "+" if is_self(ra, rb) => constant(la, lb).filter(|&c| c > 0).map(|by| Write::Step { by, down: false, at: ra }),
        "-" if is_self(la, lb) => constant(ra, rb).filter(|&c| c > 0).map(|by| Write::Step { by, down: true, at: la }),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROOT: &str = include_str!("fixtures/counters_root.h");
    const NBA: &str = include_str!("fixtures/counters_nba.cpp");

    fn found(nba: &str) -> Vec<Counter> {
        find(ROOT, &[nba], &["Vtop___024root___nba_sequent__TOP__0".to_string()], &[], &|_| true)
    }

    #[test]
    fn a_delayed_copy_kept_in_the_root_counts_with_its_variable() {
        // A comparison tested in two always blocks (the Nexys3 release's debounce): Verilator
        // keeps the delayed copy in the root (`vlSelf->__Vdly__x`), copied from the variable,
        // stepped, and copied back, in two functions.
        let root = ROOT.replace(
            "    IData/*21:0*/ top__DOT__div;\n",
            "    IData/*21:0*/ top__DOT__div;\n    IData/*21:0*/ __Vdly__top__DOT__div;\n",
        );
        let pre = "void Vtop___024root___nba_sequent__TOP__0(Vtop___024root* vlSelf) {\n    vlSelf->__Vdly__top__DOT__div = vlSelf->top__DOT__div;\n    vlSelf->__Vdly__top__DOT__div = ((0x3d0900U == vlSelf->top__DOT__div) ? 0U : (0x3fffffU & ((IData)(1U) + vlSelf->top__DOT__div)));\n    if ((0x3d0900U == vlSelf->top__DOT__div)) {\n        vlSelf->led = (1U & (IData)(vlSelf->d0));\n    }\n}\n";
        let post = "void Vtop___024root___nba_sequent__TOP__1(Vtop___024root* vlSelf) {\n    vlSelf->top__DOT__div = vlSelf->__Vdly__top__DOT__div;\n}\n";
        let reached =
            ["Vtop___024root___nba_sequent__TOP__0".to_string(), "Vtop___024root___nba_sequent__TOP__1".to_string()];
        let c = find(&root, &[pre, post], &reached, &[], &|_| true);
        let names: Vec<&str> = c.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["__Vdly__top__DOT__div", "top__DOT__div"], "{c:?}");
        assert!(c.iter().all(|c| (c.bits, c.step, c.consts.clone()) == (22, 1, vec![0x3d0900])), "{c:?}");
        // A copy of it anywhere else is a read of every bit: state.
        let read = pre.replace(
            "vlSelf->led = (1U & (IData)(vlSelf->d0));",
            "vlSelf->top__DOT__copy = vlSelf->__Vdly__top__DOT__div;",
        );
        assert!(find(&root, &[&read, post], &reached, &[], &|_| true).iter().all(|c| !c.name.ends_with("div")));
    }

    #[test]
    fn verilators_counters_are_found_with_what_reads_them() {
        let c = found(NBA);
        let by = |n: &str| c.iter().find(|c| c.name.ends_with(n)).unwrap_or_else(|| panic!("{n} not found: {c:?}"));
        // The display's refresh counter: its top three bits are read.
        let r = by("refresh");
        assert_eq!((r.bits, r.step, r.down, r.shift, r.consts.clone()), (18, 1, false, Some(15), vec![]));
        // A divider through its delayed copy, compared with its terminal count.
        let d = by("__DOT__div");
        assert_eq!((d.bits, d.shift, d.consts.clone()), (22, None, vec![0x1e847f]));
        // A prescaler with a reset.
        assert_eq!(by("__DOT__pre").consts, vec![0x7a11f]);
        // A 32-bit counter with no mask, its top half copied out.
        let f = by("__DOT__free");
        assert_eq!((f.bits, f.shift), (32, Some(16)));
        // Its bits tested with a mask: from the mask's lowest bit (a low one: every value).
        for (read, low) in [("(0x80000U & vlSelf->top__DOT__refresh)", 19), ("(vlSelf->top__DOT__refresh & 7U)", 0)] {
            let nba = NBA.replacen("    vlSelf->seg", &format!("    vlSelf->an = {read};\n    vlSelf->seg"), 1);
            let c = found(&nba);
            assert_eq!(
                c.iter().find(|c| c.name.ends_with("refresh")).map(|c| c.shift),
                Some(Some(low.min(15))),
                "{read}"
            );
        }
        // One bit of it, shifted and masked into place (`led = {free[26], ...}`), either way.
        for read in ["(0x8000U & (vlSelf->top__DOT__free >> 0xbU))", "((vlSelf->top__DOT__free >> 0xbU) & 0x8000U)"] {
            let nba = NBA.replacen("    vlSelf->seg", &format!("    vlSelf->an = {read};\n    vlSelf->seg"), 1);
            let c = found(&nba);
            assert_eq!(c.iter().find(|c| c.name.ends_with("__DOT__free")).map(|c| c.shift), Some(Some(16)), "{read}");
            let nba = NBA.replacen(
                "    vlSelf->seg",
                &format!("    vlSelf->an = {};\n    vlSelf->seg", read.replace("0x8000U", "0x8001U")),
                1,
            );
            let c = found(&nba);
            assert_eq!(c.iter().find(|c| c.name.ends_with("__DOT__free")).map(|c| c.shift), Some(Some(11)), "{read}");
        }
    }

    #[test]
    fn any_other_read_or_write_is_not_a_counter() {
        let names = |nba: &str| found(nba).into_iter().map(|c| c.name).collect::<Vec<_>>();
        let all = names(NBA);
        assert!(all.iter().any(|n| n.ends_with("refresh")), "{all:?}");
        // Read whole (into a variable as wide), added to on every bit, compared with a variable.
        for read in [
            "    vlSelf->top__DOT__copy = vlSelf->top__DOT__refresh;\n",
            "    vlSelf->top__DOT__copy = (1U + vlSelf->top__DOT__refresh);\n",
            "    vlSelf->an = (vlSelf->top__DOT__refresh == vlSelf->d0);\n",
        ] {
            let nba = NBA.replacen("    vlSelf->seg", &format!("{read}    vlSelf->seg"), 1);
            assert!(!names(&nba).iter().any(|n| n.ends_with("refresh")), "{read}");
        }
        // Written from something else, counted both ways, or by a variable step.
        for write in [
            "    vlSelf->top__DOT__refresh = vlSelf->d0;\n",
            "    vlSelf->top__DOT__refresh = (0x3ffffU & (vlSelf->top__DOT__refresh - 1U));\n",
            "    vlSelf->top__DOT__refresh = (0x3ffffU & (vlSelf->d0 + vlSelf->top__DOT__refresh));\n",
            "    vlSelf->top__DOT__refresh = (0x3fffU & ((IData)(1U) + vlSelf->top__DOT__refresh));\n",
        ] {
            let nba = NBA.replacen("    vlSelf->seg", &format!("{write}    vlSelf->seg"), 1);
            assert!(!names(&nba).iter().any(|n| n.ends_with("refresh")), "{write}");
        }
        // Excluded by the caller (a variable the harness writes).
        let c = find(
            ROOT,
            &[NBA],
            &["Vtop___024root___nba_sequent__TOP__0".to_string()],
            &["top__DOT__refresh".to_string()],
            &|_| true,
        );
        assert!(!c.iter().any(|c| c.name.ends_with("refresh")));
    }

    #[test]
    fn a_read_into_fewer_bits_reads_the_low_ones_and_splits_the_counter() {
        // Into the 8-bit `an`, whole, plus one, or through a choice (a port's read mux): the
        // low byte repeats while the rest counts.
        for read in [
            "    vlSelf->an = vlSelf->top__DOT__refresh;\n",
            "    vlSelf->an = (1U + vlSelf->top__DOT__refresh);\n",
            "    vlSelf->an = (vlSelf->rst ? vlSelf->top__DOT__refresh : (IData)(vlSelf->d0));\n",
        ] {
            let nba = NBA.replacen("    vlSelf->seg", &format!("{read}    vlSelf->seg"), 1);
            let c = found(&nba);
            let r = c.iter().find(|c| c.name.ends_with("refresh")).unwrap_or_else(|| panic!("{read}: {c:?}"));
            // Its top bits shown (15..17) stay above the split.
            assert_eq!((r.shift, r.split, r.split_shift), (Some(0), Some(8), Some(15)), "{read}");
        }
    }

    #[test]
    fn a_counter_compared_with_a_register_is_bounded_by_it() {
        // A tone generator's shape: `if (refresh + 1 >= copy) ...`: `copy` bounds the counter
        // (with the 1 added first), and is read whole itself. A sum that wraps sooner than the
        // counter, or a comparison with the counter itself, spoils it.
        let read = |cmp: &str| {
            let nba = NBA.replacen("    vlSelf->seg", &format!("    vlSelf->an = ({cmp});\n    vlSelf->seg"), 1);
            found(&nba).into_iter().find(|c| c.name.ends_with("refresh"))
        };
        let r = read("(0x3ffffU & ((IData)(1U) + vlSelf->top__DOT__refresh)) >= vlSelf->top__DOT__copy").unwrap();
        assert_eq!(r.bounds, [("top__DOT__copy".to_string(), 1)]);
        assert_eq!(
            read("vlSelf->top__DOT__copy == vlSelf->top__DOT__refresh").unwrap().bounds,
            [("top__DOT__copy".to_string(), 0)]
        );
        assert!(read("(0xffU & ((IData)(1U) + vlSelf->top__DOT__refresh)) >= vlSelf->top__DOT__copy").is_none());
        assert!(read("vlSelf->top__DOT__refresh == vlSelf->top__DOT__refresh").is_none());
    }

    #[test]
    fn a_read_inside_a_window_of_the_counter_counts_only_there() {
        // A sprite's row within its window (pdxrayw_p2video's icon): `refresh - copy` is read
        // only where `copy <= refresh <= 0x200`; both comparisons bound the counter, and the
        // read is kept with them (the lowest bit it sees, its guards) instead of spoiling it.
        let read = |code: &str| {
            let nba = NBA.replacen("    vlSelf->seg", &format!("    {code}\n    vlSelf->seg"), 1);
            found(&nba).into_iter().find(|c| c.name.ends_with("refresh"))
        };
        let window =
            "if (((vlSelf->top__DOT__refresh >= vlSelf->top__DOT__copy) & (0x200U >= vlSelf->top__DOT__refresh))) {";
        let r =
            read(&format!("{window} vlSelf->an = (0xfU & (vlSelf->top__DOT__refresh - vlSelf->top__DOT__copy)); }}"))
                .unwrap();
        assert_eq!(r.bounds, [("top__DOT__copy".to_string(), 0)]);
        assert!(r.consts.contains(&0x200), "{r:?}");
        assert_eq!(
            r.guarded,
            [GuardedRead { lo: 0, guards: vec![(Cmp::Le, GuardedBy::Const(0x200)), (Cmp::Ge, GuardedBy::Bound(0))] }]
        );
        // Read whole under the window: still a counter, told apart everywhere in it.
        let r = read(&format!("{window} vlSelf->top__DOT__copy = vlSelf->top__DOT__refresh; }}")).unwrap();
        assert_eq!(r.guarded[0].lo, 0);
        // Read whole outside any comparison of it: plain state.
        assert!(read("vlSelf->top__DOT__copy = vlSelf->top__DOT__refresh;").is_none());
    }

    #[test]
    fn a_read_that_computes_only_what_no_run_observes_is_no_read() {
        // `copy` taking the refresh counter plus one spoils it, unless no run observes `copy`.
        let nba = NBA.replacen(
            "    vlSelf->seg",
            "    vlSelf->top__DOT__copy = (1U + vlSelf->top__DOT__refresh);\n    vlSelf->seg",
            1,
        );
        let with = |observed: &dyn Fn(&str) -> bool| {
            find(ROOT, &[&nba], &["Vtop___024root___nba_sequent__TOP__0".to_string()], &[], observed)
                .iter()
                .any(|c| c.name.ends_with("refresh"))
        };
        assert!(!with(&|_| true));
        // (Nothing else reads it then but its own update.)
        assert!(with(&|n| n != "top__DOT__copy"));
    }

    #[test]
    fn a_choice_between_a_constant_and_a_step_is_a_counters_write() {
        // Verilator writes `if (reset) x <= 0; else x <= x + 1;` as a choice.
        let write = "    vlSelf->top__DOT__refresh = ((IData)(vlSelf->rst) ? 0U : ((0x3ffffU == vlSelf->top__DOT__refresh) ? 0U : (0x3ffffU & ((IData)(1U) + vlSelf->top__DOT__refresh))));\n";
        let nba = NBA.replacen("    vlSelf->seg", &format!("{write}    vlSelf->seg"), 1);
        let c = found(&nba);
        let r = c.iter().find(|c| c.name.ends_with("refresh")).unwrap_or_else(|| panic!("{c:?}"));
        // The condition's comparison is a read like any other; the constants are what it
        // may be set to.
        assert_eq!((r.step, r.consts.clone(), r.sets.clone()), (1, vec![0x3ffff], vec![0]));
        // (Each constant once, within its width.)
        let reset_to = write.replacen("? 0U :", "? 0x7fffffU :", 1);
        let nba = NBA.replacen("    vlSelf->seg", &format!("{reset_to}    vlSelf->seg"), 1);
        let c = found(&nba);
        let r = c.iter().find(|c| c.name.ends_with("refresh")).unwrap();
        assert_eq!(r.sets, vec![0, 0x3ffff]);
        // A branch that is neither spoils it.
        let nba = NBA.replacen(
            "    vlSelf->seg",
            &format!("{}    vlSelf->seg", write.replacen("? 0U :", "? vlSelf->d0 :", 1)),
            1,
        );
        assert!(!found(&nba).iter().any(|c| c.name.ends_with("refresh")));
    }

    #[test]
    fn a_down_counter_steps_down() {
        let nba = NBA.replace(
            "(0x3ffffU & ((IData)(1U) \n                                             + vlSelf->top__DOT__refresh))",
            "(0x3ffffU & (vlSelf->top__DOT__refresh - (IData)(1U)))",
        );
        let c = found(&nba);
        let r = c.iter().find(|c| c.name.ends_with("refresh")).unwrap();
        assert!(r.down);
    }
}
