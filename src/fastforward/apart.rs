//! Which KCPSM6 models may run apart from the board while their firmware keeps to itself:
//! found in the C++ Verilator generates, at build time.
//!
//! A core in a software delay (BotSim's firmware waits out its 50 ms main loop in four nested
//! loops) changes only its own registers; what it shows in every cycle (`address`, `port_id`,
//! `out_port`, `bram_enable`) changes with them. If the design reads those only under a strobe
//! (`if (write_strobe) case (port_id) ...`, quiet while no port is written or read) or into
//! its **followers**, the variables that only feed the core's own `instruction` and `in_port`
//! (its program ROM's output register, a registered read mux), then nothing else in the board
//! can tell where the core is in its delay: the board's fast-forward may leave the core out
//! of the period it looks for, run the core on its own up to its next port access, and skip
//! the board as if the core were still. A follower left out of the comparison is stale after
//! a skip, so each must be written in full at every edge of the core's clock (its value a
//! function of the last edge's outputs and the rest of the board, never of its own past): an
//! unconditional write, an `if`/`else` written in every branch, a chain of `==` tests that
//! covers every value of what it tests (a `case` without a `default`), or the ROM's
//! `if (bram_enable)` (1 in the first cycle of every instruction of a running core: the word
//! at the next instruction's decode is always the fetch's, and the host leaves the decoded
//! word unchecked for the cycles after a skip). And it must be read by nothing
//! but the core's data pins: not its `reset`, `sleep` or `interrupt`, which the core's run on
//! its own holds as they are.
//!
//! ```
//! let root = "class Vboard___024root final {\n  QData/*63:0*/ u__DOT__cpu__DOT__botsim_iss_q;\n  \
//!             CData/*7:0*/ u__DOT__in_port;\n  CData/*7:0*/ u__DOT__led;\n};\n";
//! let q = "vlSelf->u__DOT__cpu__DOT__botsim_iss_q";
//! let code = format!(
//!     "void Vboard___024root___eval_nba(Vboard___024root* vlSelf) {{\n    \
//!      if (vlSelf->__VnbaTriggered.at(0U)) {{\n        Vboard___024root___nba_sequent__TOP__0(vlSelf);\n    }}\n}}\n\
//!      void Vboard___024root___nba_sequent__TOP__0(Vboard___024root* vlSelf) {{\n    if ((1U & (IData)(({q} >> 0x15U)))) {{\n        \
//!      vlSelf->u__DOT__in_port = 1U;\n    }} else {{\n        vlSelf->u__DOT__in_port = 2U;\n    }}\n    \
//!      if ((1U & (IData)(({q} >> 0x1dU)))) {{\n        vlSelf->u__DOT__led = (0xffU & (IData)(({q} >> 0xdU)));\n    }}\n    \
//!      botsim_iss_tick_TOP(vlSelf->u__DOT__cpu__DOT__botsim_iss_cpu, ((QData)((IData)(vlSelf->u__DOT__in_port)) << 0x12U), x);\n}}\n"
//! );
//! let apart = botsim::fastforward::apart::cores_apart(root, &[&code]);
//! assert_eq!(apart[0].core, "u__DOT__cpu");
//! assert_eq!(apart[0].followers, ["u__DOT__in_port"]);
//! ```

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::ops::Range;

use super::cpp::{closing, functions, tokens, Tok};
use super::demand::{demands, number, Demand};
use super::strobes::{drop_casts, guards, member, parse, strobe, Cond, ALL_STROBES, OUTPUTS};

/// A core that may run apart, by its instance's Verilator name, and its followers (root
/// variables, with their delayed copies kept in the root).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Apart {
    pub core: String,
    pub followers: Vec<String>,
    /// The followers written in full only for some values of `port_id` (a read mux whose
    /// `case` leaves ports out: it keeps its value there): the core may run apart only if
    /// every INPUT of its program reads a port they are written at (where the core samples
    /// `in_port`, the edge before wrote it for that port, whatever came before).
    pub ports: Vec<Ports>,
}

/// The ports a follower is written at: a set of `port_id` values, a bit each.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ports {
    pub values: Cover,
}

/// A set of `port_id` values (bit `p % 64` of word `p / 64`).
pub type Cover = [u64; 4];
const ALL: Cover = [u64::MAX; 4];
const NONE: Cover = [0; 4];

fn and(a: Cover, b: Cover) -> Cover {
    [a[0] & b[0], a[1] & b[1], a[2] & b[2], a[3] & b[3]]
}
fn or(a: Cover, b: Cover) -> Cover {
    [a[0] | b[0], a[1] | b[1], a[2] | b[2], a[3] | b[3]]
}
fn not(a: Cover) -> Cover {
    [!a[0], !a[1], !a[2], !a[3]]
}

impl std::fmt::Display for Ports {
    /// Four words in hexadecimal, `:` between (the lowest ports first), as the harness hands
    /// it to the host.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = &self.values;
        write!(f, "{:x}:{:x}:{:x}:{:x}", v[0], v[1], v[2], v[3])
    }
}

impl Ports {
    /// Parse [`Ports`]'s `Display`.
    pub fn parse(s: &str) -> Option<Ports> {
        let words: Vec<u64> = s.split(':').map(|w| u64::from_str_radix(w, 16).ok()).collect::<Option<_>>()?;
        Some(Ports { values: words.try_into().ok()? })
    }

    /// Port `port` is one the follower is written at.
    pub fn has(&self, port: u8) -> bool {
        self.values[port as usize / 64] >> (port % 64) & 1 == 1
    }
}

/// How fully a statement sequence writes a variable at an edge.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Written {
    No,
    /// For some ports only.
    At(Ports),
    Full,
}

/// The outputs that change while a core only computes: `address`, `bram_enable`, `out_port`,
/// `port_id` (kcpsm6_iss.v's outputs register, bits 0-28; the strobes and `interrupt_ack`
/// above them stay 0).
const QUIET: u64 = (1 << 29) - 1;
/// `bram_enable`'s bit.
const BRAM_ENABLE: u64 = 1 << 12;
/// The pins' data bits (`instruction`, `in_port`) and the rest (`interrupt`, `sleep`, `reset`).
const PIN_DATA: u64 = (1 << 26) - 1;

/// The functions of the scheduler's nba region: the triggers each runs under (none: always).
type Schedule = HashMap<String, Option<BTreeSet<String>>>;

/// The KCPSM6 models of the evaluation `code` (the root's functions) that may run apart.
pub fn cores_apart(root: &str, code: &[&str]) -> Vec<Apart> {
    let widths = super::counters::scalar_widths(root);
    let mut bodies: Vec<(&str, Vec<Tok>)> = Vec::new();
    for c in code {
        for (name, body) in functions(c) {
            match tokens(body) {
                Ok(t) => bodies.push((name, t)),
                Err(_) => return Vec::new(),
            }
        }
    }
    let Some(schedule) = schedule(&bodies) else { return Vec::new() };
    let cores: Vec<&str> =
        widths.keys().filter(|n| !n.starts_with("__V")).filter_map(|n| n.strip_suffix(OUTPUTS)).collect();
    let toks: Vec<Vec<Tok>> = bodies.iter().map(|(_, t)| t.clone()).collect();
    cores.into_iter().filter_map(|core| apart(core, &bodies, &toks, &schedule, &widths)).collect()
}

/// `core`'s followers, if the design reads its changing outputs only under a strobe or into
/// them.
fn apart(
    core: &str,
    bodies: &[(&str, Vec<Tok>)],
    toks: &[Vec<Tok>],
    schedule: &Schedule,
    widths: &BTreeMap<String, u32>,
) -> Option<Apart> {
    let q = format!("{core}{OUTPUTS}");
    let cpu = format!("{core}__DOT__botsim_iss_cpu");
    let (tick_fn, args) = tick_call(bodies, &cpu)?;
    let tick_triggers = schedule.get(bodies[tick_fn].0)?.clone();
    let (data, ctl) = pin_reads(&bodies[tick_fn].1[args.clone()], widths);
    let mut followers: BTreeSet<String> = BTreeSet::new();
    let mut ports = Vec::new();
    for v in data.difference(&ctl) {
        if !v.contains("__DOT__") || v.as_str() == q || !only_read_by_the_core(v, bodies, tick_fn, &args) {
            continue;
        }
        match written_at_every_edge(v, &q, bodies, schedule, &tick_triggers) {
            Written::No => continue,
            Written::At(p) => ports.push(p),
            Written::Full => {}
        }
        followers.insert(v.clone());
        followers.insert(format!("__Vdly__{v}"));
    }
    let guards = guards(toks, &q, ALL_STROBES);
    let width = |n: &str| widths.get(n).copied();
    for (_, t) in bodies {
        let reads = demands(t, &width);
        let ctx = Ctx { q: &q, guards: &guards, followers: &followers, reads: &reads };
        if !ctx.quiet(t, 0..t.len(), false, false) {
            return None;
        }
    }
    let followers = followers.into_iter().filter(|f| widths.contains_key(f) || !f.starts_with("__Vdly__")).collect();
    Some(Apart { core: core.to_string(), followers, ports })
}

/// The scheduler's nba region: each function it calls and the triggers (`at(k)`) it is
/// called under; `None` when the region is not of the shape known.
fn schedule(bodies: &[(&str, Vec<Tok>)]) -> Option<Schedule> {
    let (_, t) = bodies.iter().find(|(n, _)| *n == "Vboard___024root___eval_nba")?;
    let mut out = Schedule::new();
    let mut i = 0;
    while i < t.len() {
        if t[i] == Tok::Id("if") && t.get(i + 1) == Some(&Tok::P("(")) {
            let close = closing(t, i + 1)?;
            let mut at = BTreeSet::new();
            for j in i + 2..close {
                if let (Tok::Id("at"), Some(Tok::P("(")), Some(Tok::Num(k))) = (t[j], t.get(j + 1), t.get(j + 2)) {
                    at.insert(k.trim_end_matches(['U', 'L']).to_string());
                }
            }
            if t.get(close + 1) != Some(&Tok::P("{")) {
                return None;
            }
            let end = closing(t, close + 1)?;
            if at.is_empty() {
                // (`if (false && vlSelf) {}`: no call under a test of no trigger.)
                if t[close + 2..end].iter().any(|x| matches!(x, Tok::Id(f) if f.starts_with("Vboard___024root___"))) {
                    return None;
                }
                i = end + 1;
                continue;
            }
            for j in close + 2..end {
                if let (Tok::Id(f), Some(Tok::P("("))) = (t[j], t.get(j + 1)) {
                    if f.starts_with("Vboard___024root___") {
                        out.insert(f.to_string(), Some(at.clone()));
                    }
                }
            }
            i = end + 1;
            continue;
        }
        if let (Tok::Id(f), Some(Tok::P("("))) = (t[i], t.get(i + 1)) {
            if f.starts_with("Vboard___024root___") {
                out.insert(f.to_string(), None);
            }
        }
        i += 1;
    }
    Some(out)
}

/// The function that calls `cpu`'s tick, and its pins argument's tokens.
fn tick_call(bodies: &[(&str, Vec<Tok>)], cpu: &str) -> Option<(usize, Range<usize>)> {
    let mut found = None;
    for (f, (_, t)) in bodies.iter().enumerate() {
        for i in 0..t.len() {
            let Tok::Id(name) = t[i] else { continue };
            if !name.contains("botsim_iss_tick") || t.get(i + 1) != Some(&Tok::P("(")) || member(t, i + 2) != Some(cpu)
            {
                continue;
            }
            if t.get(i + 5) != Some(&Tok::P(",")) || found.is_some() {
                return None; // (one call, of the shape kcpsm6_iss.v's)
            }
            let start = i + 6;
            let mut depth = 0usize;
            let mut end = None;
            for (j, tok) in t.iter().enumerate().skip(start) {
                match tok {
                    Tok::P("(" | "[" | "{") => depth += 1,
                    Tok::P(")" | "]" | "}") if depth == 0 => return None,
                    Tok::P(")" | "]" | "}") => depth -= 1,
                    Tok::P(",") if depth == 0 => {
                        end = Some(j);
                        break;
                    }
                    _ => {}
                }
            }
            found = Some((f, start..end?));
        }
    }
    found
}

/// The root variables the pins argument `arg` reads into its data bits and into the rest.
fn pin_reads(arg: &[Tok], widths: &BTreeMap<String, u32>) -> (BTreeSet<String>, BTreeSet<String>) {
    let read_into = |mask: &'static str| {
        // `vlSelf->botsim_pins = (mask & (arg));`, whose reads carry the bits it needs.
        let mut t = vec![
            Tok::Id("vlSelf"),
            Tok::P("->"),
            Tok::Id("botsim_pins"),
            Tok::P("="),
            Tok::P("("),
            Tok::Num(mask),
            Tok::P("&"),
            Tok::P("("),
        ];
        t.extend_from_slice(arg);
        t.extend([Tok::P(")"), Tok::P(")"), Tok::P(";")]);
        let width = |n: &str| if n == "botsim_pins" { Some(64) } else { widths.get(n).copied() };
        let reads = demands(&t, &width);
        let mut out = BTreeSet::new();
        for i in 8..t.len() {
            let Some(name) = member(&t, i) else { continue };
            let needed = match reads.get(&i) {
                Some(Demand::Bits(b) | Demand::Guarded { bits: b, .. }) => *b != 0,
                _ => true,
            };
            if needed {
                out.insert(name.to_string());
            }
        }
        out
    };
    debug_assert_eq!(number("0x3ffffffULL"), Some(PIN_DATA));
    (read_into("0x3ffffffULL"), read_into("0xfffffffffc000000ULL"))
}

/// The statement around token `i`: from after the `;`, `{` or `}` before it to its `;`.
fn statement_around(t: &[Tok], i: usize) -> Range<usize> {
    let start = (0..i).rev().find(|&j| matches!(t[j], Tok::P(";" | "{" | "}"))).map_or(0, |j| j + 1);
    let end = (i..t.len()).find(|&j| t[j] == Tok::P(";")).unwrap_or(t.len());
    start..end
}

/// The statement counts a coverage point of a build with Verilator's coverage
/// (`++(vlSymsp->__Vcoverage[3]);`): no state of the design.
fn coverage_point(t: &[Tok], s: &Range<usize>) -> bool {
    t.get(s.start) == Some(&Tok::P("++"))
        && t[s.clone()].iter().any(|x| matches!(x, Tok::Id(n) if n.starts_with("__Vcoverage")))
}

/// The variable a statement assigns with `=` (a root variable, or a local), if it is one.
fn target<'a>(t: &[Tok<'a>], s: &Range<usize>) -> Option<&'a str> {
    if let Some(n) = member(t, s.start) {
        return (t.get(s.start + 3) == Some(&Tok::P("="))).then_some(n);
    }
    match (t.get(s.start), t.get(s.start + 1)) {
        (Some(Tok::Id(n)), Some(Tok::P("="))) => Some(n),
        _ => None,
    }
}

/// The statement `s` is `__Vdly__v = v;` (a delayed copy taken before the edge's writes).
fn is_hold(t: &[Tok], s: &Range<usize>, v: &str) -> bool {
    let twin = format!("__Vdly__{v}");
    target(t, s) == Some(twin.as_str()) && {
        let value = if member(t, s.start).is_some() { s.start + 4 } else { s.start + 2 };
        member(t, value) == Some(v) && value + 3 == s.end
    }
}

/// The statement `s` is `v = __Vdly__v;` (a delayed copy's commit).
fn is_commit(t: &[Tok], s: &Range<usize>, v: &str) -> bool {
    let twin = format!("__Vdly__{v}");
    target(t, s) == Some(v) && {
        let value = s.start + 4;
        member(t, value).map_or(t.get(value) == Some(&Tok::Id(twin.as_str())) && value + 1 == s.end, |n| {
            n == twin && value + 3 == s.end
        })
    }
}

/// Nothing reads `v` but `cpu`'s tick (its delayed copy's hold and commit aside).
fn only_read_by_the_core(v: &str, bodies: &[(&str, Vec<Tok>)], tick_fn: usize, args: &Range<usize>) -> bool {
    let twin = format!("__Vdly__{v}");
    for (f, (_, t)) in bodies.iter().enumerate() {
        for i in 0..t.len() {
            let name = member(t, i).or(match t[i] {
                Tok::Id(n) if n == twin && (i == 0 || t[i - 1] != Tok::P("->")) => Some(n),
                _ => None,
            });
            let Some(name) = name else { continue };
            if name != v && name != twin {
                continue;
            }
            let s = statement_around(t, i);
            if s.start == i && target(t, &s).is_some() {
                continue; // (a write)
            }
            let ok = (f == tick_fn && args.contains(&i)) || is_hold(t, &s, v) || is_commit(t, &s, v);
            if !ok {
                return false;
            }
        }
    }
    true
}

/// `v` is written in full at every edge of the core's clock (`tick_triggers`): in one function
/// run at each, on every path through it (or for some ports), its delayed copy's commit
/// unconditional.
fn written_at_every_edge(
    v: &str,
    q: &str,
    bodies: &[(&str, Vec<Tok>)],
    schedule: &Schedule,
    tick_triggers: &Option<BTreeSet<String>>,
) -> Written {
    let twin = format!("__Vdly__{v}");
    let mut writer: Option<usize> = None;
    for (f, (name, t)) in bodies.iter().enumerate() {
        // Start-up and settling functions run once, before any edge.
        if name.contains("_initial") || name.contains("_settle") || name.contains("_ctor") || name.contains("_static") {
            continue;
        }
        for i in 0..t.len() {
            let s = statement_around(t, i);
            if s.start != i {
                continue;
            }
            let Some(n) = target(t, &s).or_else(|| compound_target(t, &s)) else { continue };
            if n != v && n != twin {
                continue;
            }
            if is_hold(t, &s, v) {
                continue;
            }
            if is_commit(t, &s, v) {
                // Unconditional: at the function's top level.
                let depth = t[..i].iter().fold(0i64, |d, tok| match tok {
                    Tok::P("{") => d + 1,
                    Tok::P("}") => d - 1,
                    _ => d,
                });
                if depth != 0 {
                    return Written::No;
                }
                continue;
            }
            if writer.is_some_and(|w| w != f) {
                return Written::No;
            }
            writer = Some(f);
        }
    }
    let Some(w) = writer else { return Written::No };
    let (name, t) = &bodies[w];
    // Run at every edge the core ticks at.
    let runs = match (schedule.get(*name), tick_triggers) {
        (Some(None), _) => true,
        (Some(Some(at)), Some(tick)) => tick.is_subset(at),
        _ => false,
    };
    if !runs {
        return Written::No;
    }
    match written(t, 0..t.len(), &[v, twin.as_str()], q) {
        ALL => Written::Full,
        NONE => Written::No,
        values => Written::At(Ports { values }),
    }
}

/// A compound assignment's target (`x |= ...`): a write that keeps part of the old value.
fn compound_target<'a>(t: &[Tok<'a>], s: &Range<usize>) -> Option<&'a str> {
    let (n, op) = match member(t, s.start) {
        Some(n) => (n, t.get(s.start + 3)),
        None => match t.get(s.start) {
            Some(Tok::Id(n)) => (*n, t.get(s.start + 1)),
            _ => return None,
        },
    };
    matches!(op, Some(Tok::P("|=" | "&=" | "^=" | "+=" | "-=" | "<<=" | ">>=" | "[" | "*=" | "/=" | "%="))).then_some(n)
}

/// One statement of a function body.
enum Stmt {
    /// `if (cond) { .. } else if (cond) { .. } else { .. }`: each test and its block's
    /// tokens (inside the braces); the last test `None` for a final `else`.
    If(Vec<(Option<Range<usize>>, Range<usize>)>),
    Block(Range<usize>),
    /// Up to its `;`.
    Simple(Range<usize>),
    /// Anything else (a loop), whole.
    Other(Range<usize>),
}

/// The statements of `t[range]`.
fn statements(t: &[Tok], range: Range<usize>) -> Option<Vec<Stmt>> {
    let mut out = Vec::new();
    let mut i = range.start;
    while i < range.end {
        match t[i] {
            Tok::Id("if") => {
                let mut chain = Vec::new();
                let mut j = i;
                loop {
                    if t.get(j + 1) != Some(&Tok::P("(")) {
                        return None;
                    }
                    let close = closing(t, j + 1)?;
                    if t.get(close + 1) != Some(&Tok::P("{")) {
                        return None;
                    }
                    let end = closing(t, close + 1)?;
                    chain.push((Some(j + 2..close), close + 2..end));
                    j = end + 1;
                    if t.get(j) != Some(&Tok::Id("else")) {
                        break;
                    }
                    match t.get(j + 1) {
                        Some(Tok::Id("if")) => j += 1,
                        Some(Tok::P("{")) => {
                            let end = closing(t, j + 1)?;
                            chain.push((None, j + 2..end));
                            j = end + 1;
                            break;
                        }
                        _ => return None,
                    }
                }
                out.push(Stmt::If(chain));
                i = j;
            }
            Tok::P("{") => {
                let end = closing(t, i)?;
                out.push(Stmt::Block(i + 1..end));
                i = end + 1;
            }
            Tok::Id("for" | "while" | "do" | "switch") => {
                let open = (i..range.end).find(|&j| t[j] == Tok::P("{"))?;
                let end = closing(t, open)?;
                out.push(Stmt::Other(i..end + 1));
                i = end + 1;
            }
            _ => {
                let end = (i..range.end).find(|&j| t[j] == Tok::P(";"))?;
                out.push(Stmt::Simple(i..end));
                i = end + 1;
            }
        }
    }
    Some(out)
}

/// For which values of `port_id` a statement sequence writes one of `unit` on every path (a
/// hold of the delayed copy is no write): all of them for an unconditional write, an
/// `if`/`else` written in every branch, a `case` covering every value, the ROM's `if
/// (bram_enable)`; some when a chain of tests of `port_id` alone (a `case` on it or its low
/// bits, as `==` tests or as a tree of its bits) leaves values out. `q`: the core's outputs
/// register.
fn written(t: &[Tok], range: Range<usize>, unit: &[&str], q: &str) -> Cover {
    let Some(stmts) = statements(t, range) else { return NONE };
    let mut cover = NONE;
    for s in stmts {
        let w = match s {
            Stmt::Simple(r) if target(t, &r).is_some_and(|n| unit.contains(&n)) && !is_hold(t, &r, unit[0]) => ALL,
            Stmt::Block(r) => written(t, r, unit, q),
            Stmt::If(chain) => written_if(t, &chain, unit, q),
            _ => NONE,
        };
        cover = or(cover, w);
    }
    cover
}

/// [`written`] for an `if` chain.
fn written_if(t: &[Tok], chain: &[(Option<Range<usize>>, Range<usize>)], unit: &[&str], q: &str) -> Cover {
    let blocks: Vec<Cover> = chain.iter().map(|(_, b)| written(t, b.clone(), unit, q)).collect();
    let final_else = chain.last().is_some_and(|(c, _)| c.is_none());
    // Tests of port_id alone: each value follows the first test it passes.
    let tests: Option<Vec<Cover>> =
        chain.iter().filter_map(|(c, _)| c.as_ref()).map(|c| port_test(&t[c.clone()], q)).collect();
    if let Some(tests) = tests {
        let (mut left, mut cover) = (ALL, NONE);
        for (i, b) in blocks.iter().enumerate() {
            let taken = tests.get(i).map_or(left, |&p| and(left, p));
            cover = or(cover, and(taken, *b));
            left = and(left, not(taken));
        }
        return cover;
    }
    if blocks.iter().all(|b| *b == ALL)
        && (final_else
            || (chain.len() == 1 && chain[0].0.as_ref().is_some_and(|c| bram_enable(t, c, q)))
            || covers(t, chain))
    {
        return ALL;
    }
    // Tests of anything else: written whichever branch is taken.
    if final_else {
        blocks.into_iter().fold(ALL, and)
    } else {
        NONE
    }
}

/// The values of `port_id` for which a test of it alone holds, or none when it tests anything
/// else.
fn port_test(c: &[Tok], q: &str) -> Option<Cover> {
    let cond = parse(c, q);
    let mut cover = NONE;
    for port in 0..256u64 {
        if eval(&cond, port)? != 0 {
            cover[port as usize / 64] |= 1 << (port % 64);
        }
    }
    Some(cover)
}

/// A condition's value with `port_id` at `port`: only bits 21-28 of the outputs register
/// (masked) may be read, and constants.
fn eval(c: &Cond, port: u64) -> Option<u64> {
    let q = port << 21;
    Some(match c {
        Cond::Const(k) => *k,
        Cond::And(a, b) => match (&**a, &**b) {
            (Cond::Const(m), Cond::Q(s)) | (Cond::Q(s), Cond::Const(m)) => {
                if *s >= 64 || (m << s) >> s != *m || ((m << s) & !(0xFF << 21)) != 0 {
                    return None;
                }
                (q >> s) & m
            }
            _ => eval(a, port)? & eval(b, port)?,
        },
        Cond::Or(a, b) => eval(a, port)? | eval(b, port)?,
        Cond::Eq(a, b) => (eval(a, port)? == eval(b, port)?) as u64,
        Cond::Ne(a, b) => (eval(a, port)? != eval(b, port)?) as u64,
        _ => return None,
    })
}

/// The test is the core's `bram_enable` (1 at every fetch while it runs).
fn bram_enable(t: &[Tok], c: &Range<usize>, q: &str) -> bool {
    match parse(&t[c.clone()], q) {
        Cond::And(a, b) => {
            matches!((&*a, &*b), (Cond::Const(m), Cond::Q(s)) | (Cond::Q(s), Cond::Const(m)) if *s < 64 && m << s == BRAM_ENABLE)
        }
        _ => false,
    }
}

/// The chain's tests are `k == (m & x)` with one `m` and `x` (of anything), each an `or` of
/// such, and together take every value of `m & x`: a `case` whose items cover them all.
fn covers(t: &[Tok], chain: &[(Option<Range<usize>>, Range<usize>)]) -> bool {
    let mut what: Option<(u64, String)> = None;
    let mut seen = BTreeSet::new();
    for (c, _) in chain {
        let Some(c) = c else { return false };
        let toks = uncast(&t[c.clone()]);
        for term in split_or(&toks) {
            let Some((k, m, x)) = compare(term) else { return false };
            if what.get_or_insert((m, x.clone())) != &(m, x) || k & !m != 0 {
                return false;
            }
            seen.insert(k);
        }
    }
    matches!(what, Some((m, _)) if m.count_ones() <= 12 && seen.len() as u64 == 1u64 << m.count_ones())
}

/// The tokens without casts (`(IData)`) and outer parentheses.
fn uncast<'a>(t: &[Tok<'a>]) -> Vec<Tok<'a>> {
    strip_parens(drop_casts(t))
}

fn strip_parens(mut t: Vec<Tok>) -> Vec<Tok> {
    while t.first() == Some(&Tok::P("(")) && closing(&t, 0) == Some(t.len() - 1) {
        t = t[1..t.len() - 1].to_vec();
    }
    t
}

/// The terms of a top-level `|` or `||`.
fn split_or<'a>(t: &[Tok<'a>]) -> Vec<Vec<Tok<'a>>> {
    let mut out = Vec::new();
    let mut depth = 0i32;
    let mut start = 0;
    for (i, tok) in t.iter().enumerate() {
        match tok {
            Tok::P("(" | "[") => depth += 1,
            Tok::P(")" | "]") => depth -= 1,
            Tok::P("|" | "||") if depth == 0 => {
                out.extend(split_or(&strip_parens(t[start..i].to_vec())));
                start = i + 1;
            }
            _ => {}
        }
    }
    let last = strip_parens(t[start..].to_vec());
    if start == 0 {
        out.push(last); // (no `|` at this level)
    } else {
        out.extend(split_or(&last));
    }
    out
}

/// `k == (m & x)`: (k, m, x's text).
fn compare(t: Vec<Tok>) -> Option<(u64, u64, String)> {
    let eq = t.iter().position(|x| *x == Tok::P("=="))?;
    let (l, r) = (strip_parens(t[..eq].to_vec()), strip_parens(t[eq + 1..].to_vec()));
    let (k, x) = match (l.as_slice(), r.as_slice()) {
        ([Tok::Num(k)], x) | (x, [Tok::Num(k)]) => (number(k)?, x.to_vec()),
        _ => return None,
    };
    // m & x
    let and = x.iter().position(|y| *y == Tok::P("&"))?;
    let (a, b) = (strip_parens(x[..and].to_vec()), strip_parens(x[and + 1..].to_vec()));
    let (m, rest) = match (a.as_slice(), b.as_slice()) {
        ([Tok::Num(m)], rest) | (rest, [Tok::Num(m)]) => (number(m)?, rest.to_vec()),
        _ => return None,
    };
    let text: String = rest.iter().filter(|t| !matches!(t, Tok::P("(" | ")"))).map(|t| format!("{t:?}")).collect();
    Some((k, m, text))
}

/// What the walk over a function knows: the core's outputs register, its guards, its
/// followers and the reads' demands.
struct Ctx<'a> {
    q: &'a str,
    guards: &'a BTreeSet<String>,
    followers: &'a BTreeSet<String>,
    reads: &'a HashMap<usize, Demand>,
}

impl Ctx<'_> {
    /// Every read of the core's changing outputs in `t[range]` is under a strobe (`strobed`)
    /// or goes to its followers alone (`into_followers`: the block writes nothing else).
    fn quiet(&self, t: &[Tok], range: Range<usize>, strobed: bool, into_followers: bool) -> bool {
        let Some(stmts) = statements(t, range.clone()) else {
            return strobed || !self.reads_q(t, range);
        };
        stmts.into_iter().all(|s| match s {
            Stmt::If(chain) => {
                let only = into_followers || self.writes_only_followers(t, &chain);
                chain.iter().all(|(c, block)| {
                    // A test true only with a strobe (`write_strobe && port_id == 9`) is false
                    // whatever else it reads while the core is quiet.
                    let gated =
                        c.as_ref().is_some_and(|c| strobe(&parse(&t[c.clone()], self.q), self.guards, ALL_STROBES));
                    let c_ok = c.as_ref().map_or(true, |c| strobed || only || gated || !self.reads_q(t, c.clone()));
                    c_ok && self.quiet(t, block.clone(), strobed || gated, only)
                })
            }
            Stmt::Block(r) => self.quiet(t, r, strobed, into_followers),
            Stmt::Simple(r) => {
                let to_followers = target(t, &r).is_some_and(|n| self.followers.contains(n));
                let own = is_hold(t, &r, self.q) || is_commit(t, &r, self.q) || target(t, &r) == Some(self.q);
                // A value that is 0 but with a strobe (`read_strobe & (port_id == 15)`).
                let value = if member(t, r.start).is_some() { r.start + 4 } else { r.start + 2 };
                let strobe_value = target(t, &r).is_some()
                    && value < r.end
                    && strobe(&parse(&t[value..r.end], self.q), self.guards, ALL_STROBES);
                strobed || into_followers || to_followers || own || strobe_value || !self.reads_q(t, r)
            }
            Stmt::Other(r) => strobed || !self.reads_q(t, r),
        })
    }

    /// `t[range]` reads the core's changing outputs.
    fn reads_q(&self, t: &[Tok], range: Range<usize>) -> bool {
        range.into_iter().any(|i| {
            member(t, i) == Some(self.q)
                && match self.reads.get(&i) {
                    Some(Demand::Bits(b) | Demand::Guarded { bits: b, .. }) => b & QUIET != 0,
                    _ => true,
                }
        })
    }

    /// Every statement of the chain's blocks writes a follower (or is a test of such).
    fn writes_only_followers(&self, t: &[Tok], chain: &[(Option<Range<usize>>, Range<usize>)]) -> bool {
        chain.iter().all(|(_, block)| self.only_followers(t, block.clone()))
    }

    fn only_followers(&self, t: &[Tok], range: Range<usize>) -> bool {
        let Some(stmts) = statements(t, range) else { return false };
        stmts.into_iter().all(|s| match s {
            Stmt::Simple(r) => target(t, &r).is_some_and(|n| self.followers.contains(n)) || coverage_point(t, &r),
            Stmt::Block(r) => self.only_followers(t, r),
            Stmt::If(chain) => self.writes_only_followers(t, &chain),
            Stmt::Other(_) => false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROOT: &str = "class Vboard___024root final {\n  QData/*63:0*/ u__DOT__cpu__DOT__botsim_iss_q;\n  \
                        CData/*7:0*/ u__DOT__in_port;\n  IData/*17:0*/ u__DOT__instruction;\n  \
                        IData/*17:0*/ __Vdly__u__DOT__instruction;\n  CData/*7:0*/ u__DOT__led;\n  \
                        CData/*7:0*/ u__DOT__loc;\n  CData/*0:0*/ u__DOT__reset;\n};\n";
    const Q: &str = "vlSelf->u__DOT__cpu__DOT__botsim_iss_q";
    const TICK: &str = "botsim_iss_tick_TOP(vlSelf->u__DOT__cpu__DOT__botsim_iss_cpu, \
                        (((QData)((IData)(vlSelf->u__DOT__reset)) << 0x1cU) | (QData)((IData)((((IData)(vlSelf->u__DOT__in_port) << 0x12U) \
                        | vlSelf->u__DOT__instruction)))), out);";
    const ROM: &str = "vlSelf->__Vdly__u__DOT__instruction = vlSelf->u__DOT__instruction;\n\
                       if ((1U & (IData)((Q >> 0xcU)))) {\n vlSelf->__Vdly__u__DOT__instruction = vlSelf->u__DOT__rom[(0xfffU & (IData)(Q))];\n}";
    const COMMIT: &str = "vlSelf->u__DOT__instruction = vlSelf->__Vdly__u__DOT__instruction;";
    const WRITES: &str = "if ((1U & (IData)((Q >> 0x1dU)))) {\n if ((1U == (0xfU & (IData)((Q >> 0x15U))))) {\n \
                          vlSelf->u__DOT__loc = (0xffU & (IData)((Q >> 0xdU)));\n }\n}";

    /// The followers of the design of `seq` (one clock's function) beside the scheduler.
    fn followers(seq: &str) -> Option<Vec<String>> {
        apart_of(seq).map(|a| a.followers)
    }

    fn apart_of(seq: &str) -> Option<Apart> {
        let body: Vec<String> = seq.replace("Q", Q).lines().map(|l| format!("    {l}")).collect();
        let code = format!(
            "void Vboard___024root___nba_sequent__TOP__0(Vboard___024root* vlSelf) {{\n{}\n}}\n\
             void Vboard___024root___nba_sequent__TOP__1(Vboard___024root* vlSelf) {{\n    {TICK}\n    {COMMIT}\n}}\n\
             void Vboard___024root___eval_nba(Vboard___024root* vlSelf) {{\n    if (vlSelf->__VnbaTriggered.at(0U)) {{\n        \
             Vboard___024root___nba_sequent__TOP__0(vlSelf);\n    }}\n    if (vlSelf->__VnbaTriggered.at(0U)) {{\n        \
             Vboard___024root___nba_sequent__TOP__1(vlSelf);\n    }}\n}}\n",
            body.join("\n")
        );
        cores_apart(ROOT, &[&code]).into_iter().next()
    }

    fn mux(cases: &[(u32, &str)], default: Option<&str>) -> String {
        let mut s = String::new();
        for (i, (k, v)) in cases.iter().enumerate() {
            let head = if i == 0 { "if" } else { "} else if" };
            s.push_str(&format!(
                "{head} (({k}U == (3U & (IData)((Q >> 0x15U))))) {{\n vlSelf->u__DOT__in_port = {v};\n"
            ));
        }
        if let Some(d) = default {
            s.push_str(&format!("}} else {{\n vlSelf->u__DOT__in_port = {d};\n"));
        }
        s.push('}');
        s
    }

    #[test]
    fn a_rom_and_a_full_read_mux_follow_the_core() {
        let full = mux(&[(0, "1U"), (1, "vlSelf->u__DOT__loc"), (2, "3U"), (3, "4U")], None);
        let f = followers(&format!("{ROM}\n{WRITES}\n{full}")).unwrap();
        assert_eq!(f, ["__Vdly__u__DOT__instruction", "u__DOT__in_port", "u__DOT__instruction"]);
        // With a default, three items are enough.
        let dflt = mux(&[(0, "1U"), (1, "vlSelf->u__DOT__loc"), (2, "3U")], Some("0U"));
        assert!(followers(&format!("{ROM}\n{WRITES}\n{dflt}")).unwrap().contains(&"u__DOT__in_port".to_string()));
    }

    #[test]
    fn a_mux_that_keeps_its_value_for_some_ports_follows_for_the_others() {
        // Port 3 keeps the last value: in_port follows for ports 0-2 (low bits) only.
        let partial = mux(&[(0, "1U"), (1, "vlSelf->u__DOT__loc"), (2, "3U")], None);
        let all = apart_of(&format!("{ROM}\n{WRITES}\n{partial}")).unwrap();
        assert!(all.followers.contains(&"u__DOT__in_port".to_string()));
        assert_eq!(all.ports.len(), 1);
        assert!((0..=255u8).all(|p| all.ports[0].has(p) == (p & 3 != 3)));
        assert_eq!(Ports::parse(&all.ports[0].to_string()).as_ref(), Some(&all.ports[0]));
        // Tested on something other than port_id: no follower (compared with the board).
        let other = partial.replace("(Q >> 0x15U)", "vlSelf->u__DOT__loc");
        let f = followers(&format!("{ROM}\n{WRITES}\n{other}")).unwrap();
        assert!(!f.contains(&"u__DOT__in_port".to_string()));
        // The same on port_id and the instruction's address both: no follower, and what is
        // not one reads the outputs: the core stays in.
        let both = partial.replace("(3U & (IData)((Q >> 0x15U)))", "(3U & (IData)(((Q >> 0x15U) ^ Q)))");
        assert_eq!(followers(&format!("{ROM}\n{WRITES}\n{both}")), None);
        // Registered only under read_strobe: no follower, but quiet (it stays as it was).
        let strobed =
            "if ((1U & (IData)((Q >> 0x1fU)))) {\n vlSelf->u__DOT__in_port = (3U & (IData)((Q >> 0x15U)));\n}";
        assert_eq!(followers(&format!("{ROM}\n{WRITES}\n{strobed}")).unwrap().len(), 2);
    }

    #[test]
    fn a_design_that_shows_what_the_core_shows_keeps_it_in() {
        let full = mux(&[(0, "1U"), (1, "2U"), (2, "3U"), (3, "4U")], None);
        // LEDs showing port_id, or the address.
        for shown in
            ["vlSelf->u__DOT__led = (0xffU & (IData)((Q >> 0x15U)));", "vlSelf->u__DOT__led = (0xffU & (IData)(Q));"]
        {
            assert_eq!(followers(&format!("{ROM}\n{WRITES}\n{full}\n{shown}")), None, "{shown}");
        }
        // A follower read by anything else is none: the LEDs show in_port.
        let f = followers(&format!("{ROM}\n{WRITES}\n{full}\nvlSelf->u__DOT__led = vlSelf->u__DOT__in_port;"));
        assert_eq!(f, None);
        // A write under a strobe in the else branch of a test is not under it.
        let els = "if ((1U & (IData)((Q >> 0x1dU)))) {\n vlSelf->u__DOT__loc = 1U;\n} else {\n vlSelf->u__DOT__loc = (0xffU & (IData)((Q >> 0xdU)));\n}";
        assert_eq!(followers(&format!("{ROM}\n{full}\n{els}")), None);
    }
}
