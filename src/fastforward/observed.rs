//! Which of Verilator's root variables a run can observe, read from the generated C++.
//!
//! A run without a waveform or VGA frames sees the board through a few of the top's outputs
//! (the display, the LEDs, the bot's registers: [`HARNESS_READS`]) and through the KCPSM6 and
//! bot models (their DPI calls). A variable is *observed* when one of those reads it, or when
//! it feeds, through any chain of assignments and conditions, a variable that is. The rest
//! (a VGA design's timing generator and colour pipeline, its pixel clock) can run on with any
//! value without changing anything the run records. The fast-forward compares and puts back
//! the observed variables only (harness.cpp), which lets a VGA design, whose frame and display
//! refresh never repeat together within a sample, skip ahead as a one-clock design does.
//!
//! The analysis is conservative: every variable named on the right of an assignment, in its
//! indices, in an enclosing condition, or in the condition under which its function is called,
//! feeds the assigned one; a call to anything but Verilator's value macros and the model's own
//! functions is an observation of everything it names; a construct the analysis does not
//! know ends it (no part of the state is left out). Verilator's scheduler (`___eval`, which
//! loops over the trigger vectors) is modelled rather than read: a function called under
//! trigger `k` runs when trigger `k` fired, and trigger `k` is computed from the variables
//! its expression names; the scheduler's own counters are scratch, written before they are
//! read in every evaluation.
//!
//! ```
//! let root = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/fastforward/fixtures/small_root.h"));
//! let eval = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/fastforward/fixtures/small_eval.cpp"));
//! let members = botsim::fastforward::observed::members(root, &[eval]).unwrap();
//! let seen = |n: &str| members.iter().find(|m| m.name == n).unwrap().observed;
//! // The LEDs show `a`, which the clock's trigger runs; nothing reads `b`.
//! assert!(seen("led") && seen("a") && seen("clk") && seen("__Vtrigrprev__TOP__clk"));
//! assert!(!seen("b"));
//! ```

use std::collections::{HashMap, HashSet};

use super::counters::{Counter, GuardedBy};
use super::cpp::{functions, squeeze, strip_comments, tokens, Tok};

/// The top's outputs the harness reads on every evaluation of a run (harness.cpp's records and
/// the fast-forward's counter); the VGA pins are read only when frames are recorded, and such
/// runs compare the whole state.
pub const HARNESS_READS: &[&str] = &[
    "an",
    "seg",
    "dp",
    "led",
    "lines",
    "uart_room",
    "uart_pending",
    "ps2_room",
    "ps2_pending",
    "bot_upd",
    "bot_locx",
    "bot_locy",
    "bot_info",
    "bot_sensors",
    "bot_lmdist",
    "bot_rmdist",
    "bot_motctl",
    "bot_cycles",
    "xbot_upd",
    "xbot_regs1",
    "xbot_regs2",
    "xbot_regs3",
];

/// A debug build's variables of each KCPSM6 that a waveform shows (the instruction text, the
/// registers and flags, in rtl/board/kcpsm6_iss.v), which a run keeps exact as if recorded:
/// the ends of their names, the first one naming the core.
const DEBUG_READS: &[&str] = &["__DOT__kcpsm6_opcode", "__DOT__active_registers", "__DOT__flags"];

/// One variable of the root object.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Member {
    pub name: String,
    /// A run without a waveform or frames can observe it.
    pub observed: bool,
    /// The observed variables its value depends on (indices among the members), through any
    /// chain of Verilator's locals, functions and triggers; empty for one not observed.
    pub reads: Vec<usize>,
    /// What it depends on or feeds leaves the model (a record of the harness, a DPI call's
    /// argument or result): its value is not the model's own to repeat.
    pub external: bool,
}

/// Every variable of the root (from its header `root`), each with whether a run observes it,
/// from the evaluation's files `code`; or why the analysis cannot tell.
pub fn members(root: &str, code: &[&str]) -> Result<Vec<Member>, String> {
    Ok(Analysis::of(root, code)?.members())
}

/// A signal of the waveform (a code of Verilator's trace, as its tracing functions number it)
/// that a run keeping only what it records cannot show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unshown {
    pub code: u32,
    pub width: u32,
}

/// The waveform's signals that a run which compares and puts back only the observed variables
/// (and does not run the clocks that drive only the rest) cannot show: each one whose value
/// reads a variable that no record observes and that the evaluation or the harness writes.
/// The rest are exact at every moment of such a run: the observed variables are, and a
/// variable nothing writes after the initial blocks (a ROM's contents, a parameter) is too.
/// `code`: the evaluation's files; `trace`: Verilator's tracing files (`Vboard__Trace__*`);
/// `syms`: its symbol table (`Vboard__Syms.cpp`: the public variables, which the harness may
/// write).
///
/// ```
/// let root = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/fastforward/fixtures/small_root.h"));
/// let eval = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/fastforward/fixtures/small_eval_nba.cpp"));
/// let trace = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/fastforward/fixtures/small_trace.cpp"));
/// let unshown = botsim::fastforward::observed::unshown(root, &[eval], &[trace], "").unwrap();
/// // `b` toggles and nothing recorded reads it; `a` is never written (a constant).
/// assert_eq!(unshown, [botsim::fastforward::observed::Unshown { code: 3, width: 1 }]);
/// ```
pub fn unshown(root: &str, code: &[&str], trace: &[&str], syms: &str) -> Result<Vec<Unshown>, String> {
    Analysis::of(root, code)?.unshown(root, trace, syms)
}

/// The dependency graph of the evaluation and what a run observes of it.
pub(super) struct Analysis {
    /// The root's variables.
    names: Vec<String>,
    g: Graph,
    /// `seen[node]`: a record depends on it.
    seen: Vec<bool>,
    /// The functions the evaluation runs, by name.
    reached: Vec<String>,
}

impl Analysis {
    pub(super) fn of(root: &str, code: &[&str]) -> Result<Analysis, String> {
        let names = root_members(root)?;
        let mut bodies: HashMap<&str, &str> = HashMap::new();
        for c in code {
            for (name, body) in functions(c) {
                bodies.insert(name, body);
            }
        }
        let eval = *bodies.get("Vboard___024root___eval").ok_or("Verilator's evaluation function was not found")?;
        let mut g = Graph::default();
        // The scheduler: the functions it calls, which run in every evaluation (each decides
        // on its triggers what else runs).
        let entries = scheduler_calls(eval)?;
        let mut todo: Vec<String> = entries.iter().map(|s| s.to_string()).collect();
        let mut done: HashSet<String> = HashSet::new();
        while let Some(f) = todo.pop() {
            if !done.insert(f.clone()) {
                continue;
            }
            let body = *bodies.get(f.as_str()).ok_or_else(|| format!("Verilator's function `{f}` was not found"))?;
            let toks = tokens(body)?;
            let mut p =
                Parser { g: &mut g, toks: &toks, fun: &f, locals: HashSet::new(), calls: Vec::new(), dumps: None };
            let mut at = 0;
            let ctrl = vec![p.g.node(&fun_node(&f))];
            p.block(&mut at, &ctrl, false)?;
            todo.append(&mut p.calls);
        }
        for r in HARNESS_READS {
            if names.iter().any(|n| n == r) {
                let id = g.node(&member_node(r));
                g.roots.push(id);
            }
        }
        // A debug build's view of each KCPSM6, kept exact so that a waveform opened after a
        // skip shows it.
        for core in names.iter().filter_map(|n| n.strip_suffix(DEBUG_READS[0])) {
            for r in DEBUG_READS {
                let name = format!("{core}{r}");
                if names.contains(&name) {
                    let id = g.node(&member_node(&name));
                    g.roots.push(id);
                }
            }
        }
        let seen = g.ancestors();
        let mut reached: Vec<String> = done.into_iter().collect();
        reached.sort();
        Ok(Analysis { names, g, seen, reached })
    }

    /// The counters a run observes (super::counters), leaving out what the harness writes
    /// (inputs, generated clocks' levels) or reads itself.
    pub(super) fn counters(&self, root: &str, code: &[&str], syms: &str) -> Vec<super::counters::Counter> {
        let mut exclude: Vec<String> = root_inputs(root);
        exclude.extend(public_rw(syms));
        exclude.extend(HARNESS_READS.iter().map(|s| s.to_string()));
        exclude.extend(self.names.iter().filter(|n| n.starts_with("__V")).cloned());
        super::counters::find(root, code, &self.reached, &exclude, &|n| self.observed(n))
            .into_iter()
            .filter(|c| self.observed(&c.name))
            .collect()
    }

    fn observed(&self, name: &str) -> bool {
        self.g.ids.get(&member_node(name)).is_some_and(|&i| self.seen[i])
    }

    /// A variable the logic computes from a clock's level (the board's `clk`, or a generated
    /// clock's, which the harness writes: the public variables of `syms`) that feeds a trigger
    /// or what a run records, if any: such a design changes at a moment when clocks only fall
    /// (an inverted or gated clock rises there), so its falling edges must be evaluated.
    pub(super) fn clock_level_feeds(&self, syms: &str) -> Option<String> {
        let mut clocks: Vec<usize> = self.g.ids.get(&member_node("clk")).copied().into_iter().collect();
        for name in public_rw(syms) {
            clocks.extend(self.g.ids.get(&member_node(&name)).copied());
        }
        // Everything a trigger or a record depends on.
        let mut roots = self.g.roots.clone();
        roots.extend(self.g.ids.iter().filter(|(k, _)| k.starts_with("t:act:")).map(|(_, &i)| i));
        let feeds = self.g.ancestors_of(&roots);
        let mut found: Vec<&str> = self
            .g
            .ids
            .iter()
            .filter(|(k, &i)| {
                // The trigger function's copy of the level (`__Vtrigrprev__`) is how a rising
                // edge is found, not logic.
                k.starts_with("m:")
                    && !k.starts_with("m:__Vtrigrprev__")
                    && !k.starts_with("m:__Vtrigprevexpr")
                    && feeds[i]
                    && !clocks.contains(&i)
                    && self.g.preds[i].iter().any(|p| clocks.contains(p))
            })
            .map(|(k, _)| &k[2..])
            .collect();
        found.sort();
        found.first().map(|s| s.to_string())
    }

    /// Every variable of the root with whether a run observes it.
    pub(super) fn members(&self) -> Vec<Member> {
        let n = self.g.preds.len();
        // Graph node -> member index, for the members; which nodes leave the model.
        let mut index = vec![usize::MAX; n];
        for (k, name) in self.names.iter().enumerate() {
            if let Some(&i) = self.g.ids.get(&member_node(name)) {
                index[i] = k;
            }
        }
        // A member the harness or a DPI call reads or writes leaves the model itself; one
        // computed from a DPI call's result (a KCPSM6 model's outputs) too.
        let (mut outside, mut result) = (vec![false; n], vec![false; n]);
        for &r in &self.g.roots {
            outside[r] = true;
        }
        for &r in &self.g.results {
            result[r] = true;
        }
        // Each observed member's reads: the members met walking back through the other nodes.
        let mut stamp = vec![usize::MAX; n];
        self.names
            .iter()
            .enumerate()
            .map(|(k, name)| {
                let observed = self.observed(name);
                let node = self.g.ids.get(&member_node(name)).copied();
                let (mut reads, mut external) = (Vec::new(), false);
                if let (true, Some(start)) = (observed, node) {
                    external = outside[start];
                    stamp[start] = k;
                    let mut stack: Vec<usize> = self.g.preds[start].clone();
                    while let Some(i) = stack.pop() {
                        if std::mem::replace(&mut stamp[i], k) == k {
                            continue;
                        }
                        if index[i] != usize::MAX {
                            reads.push(index[i]);
                        } else {
                            external |= result[i];
                            stack.extend(self.g.preds[i].iter().copied().filter(|&p| stamp[p] != k));
                        }
                    }
                    reads.sort_unstable();
                }
                Member { name: name.clone(), observed, reads, external }
            })
            .collect()
    }

    /// [`unshown`] for this analysis (its graph gains the waveform functions' locals).
    pub(super) fn unshown(mut self, root: &str, trace: &[&str], syms: &str) -> Result<Vec<Unshown>, String> {
        let a = &mut self;
        // What the harness writes: the inputs and the public variables (the clocks' levels);
        // Verilator's own variables (the scheduler's) count as written too.
        let mut written: HashSet<String> = root_inputs(root).into_iter().collect();
        written.extend(a.names.iter().filter(|n| n.starts_with("__V")).cloned());
        written.extend(public_rw(syms));
        // Shown: observed, or never written after the initial blocks (no assignment reached from
        // the evaluation gives it a predecessor: each has at least its function's).
        let shown_member: HashSet<String> = a
            .names
            .iter()
            .filter(|n| {
                a.observed(n)
                    || (!written.contains(n.as_str())
                        && !a.g.ids.get(&member_node(n)).is_some_and(|&i| !a.g.preds[i].is_empty()))
            })
            .cloned()
            .collect();
        let mut dumps = Vec::new();
        for file in trace {
            for (name, body) in functions(file) {
                if !name.starts_with("Vboard___024root__trace_full_sub_") {
                    continue;
                }
                // The function's codes are the declarations' (not the change functions' `+ 1`).
                if !squeeze(body).contains("oldpVL_ATTR_UNUSED=bufp->oldp(vlSymsp->__Vm_baseCode);") {
                    return Err(format!("Verilator's waveform function `{name}` numbers its signals another way"));
                }
                let toks = tokens(body)?;
                let mut p = Parser {
                    g: &mut a.g,
                    toks: &toks,
                    fun: name,
                    locals: HashSet::new(),
                    calls: Vec::new(),
                    dumps: Some(Vec::new()),
                };
                let mut at = 0;
                p.block(&mut at, &[], false)?;
                dumps.extend(p.dumps.take().unwrap_or_default());
            }
        }
        if dumps.is_empty() {
            return Err("Verilator's waveform functions were not found".into());
        }
        let keys: HashMap<usize, &str> = a.g.ids.iter().map(|(k, &i)| (i, k.as_str())).collect();
        // A value is shown when every variable it reads is, through the function's locals.
        let shown = |vars: &[usize]| {
            let mut stack = vars.to_vec();
            let mut seen = HashSet::new();
            while let Some(i) = stack.pop() {
                if !seen.insert(i) {
                    continue;
                }
                match keys.get(&i).copied().unwrap_or("") {
                    k if k.starts_with("m:") => {
                        if !shown_member.contains(&k[2..]) {
                            return false;
                        }
                    }
                    k if k.starts_with("l:") => stack.extend(a.g.preds[i].iter().copied()),
                    k if k.starts_with("f:Vboard___024root__trace_") => {}
                    _ => return false,
                }
            }
            true
        };
        let mut out: Vec<Unshown> = dumps
            .iter()
            .filter(|d| d.opaque || !shown(&d.vars))
            .map(|d| Unshown { code: d.code, width: d.width })
            .collect();
        out.sort_by_key(|u| u.code);
        out.dedup();
        Ok(out)
    }
}

/// The functions `___eval` calls (the scheduler's regions), checking that it touches nothing
/// but its own counters and trigger vectors.
fn scheduler_calls(eval: &str) -> Result<Vec<String>, String> {
    const SCRATCH: &[&str] = &[
        "__VicoIterCount",
        "__VactIterCount",
        "__VactContinue",
        "__VicoTriggered",
        "__VactTriggered",
        "__VnbaTriggered",
        "vlSymsp",
    ];
    const REGIONS: &[&str] = &[
        "Vboard___024root___eval_triggers__ico",
        "Vboard___024root___eval_ico",
        "Vboard___024root___eval_triggers__act",
        "Vboard___024root___eval_act",
        "Vboard___024root___eval_nba",
    ];
    let toks = tokens(eval)?;
    let mut calls = Vec::new();
    for (i, t) in toks.iter().enumerate() {
        match t {
            Tok::Id("vlSelf") if toks.get(i + 1) == Some(&Tok::P("->")) => {
                if let Some(Tok::Id(m)) = toks.get(i + 2) {
                    if !SCRATCH.contains(m) {
                        return Err(format!("Verilator's scheduler reads `{m}`"));
                    }
                }
            }
            Tok::Id(f) if f.starts_with("Vboard___024root___") && toks.get(i + 1) == Some(&Tok::P("(")) => {
                if f.starts_with("Vboard___024root___dump_triggers__") {
                    continue;
                }
                if !REGIONS.contains(f) {
                    return Err(format!("Verilator's scheduler calls `{f}`"));
                }
                calls.push(f.to_string());
            }
            _ => {}
        }
    }
    Ok(calls)
}

/// The C++ the harness includes (`botsim_observed.h`): `botsim_members` lists every variable
/// of the root with its bytes and whether a run observes it; `kObservedKnown` is false (and
/// the list empty) when the analysis could not tell, and the comment says why.
pub fn header(
    members: &Result<Vec<Member>, String>,
    counters: &[Counter],
    out_port_free: &[String],
    apart: &[super::apart::Apart],
    triggers_fn: Option<&str>,
) -> String {
    let mut h = String::from(
        "// botsim_observed.h: generated by botsim (src/fastforward/observed.rs) for this design: every\n\
         // variable of Verilator's root object, its bytes, and whether a run observes it; and\n\
         // the generated function that computes the triggers alone, when there is one.\n",
    );
    if let Some(f) = triggers_fn {
        h.push_str(&format!("#define BOTSIM_EVAL_TRIGGERS {f}\n"));
    }
    match members {
        Ok(ms) => {
            h.push_str("static const bool kObservedKnown = true;\n");
            h.push_str("static void botsim_members(const Vboard___024root* r, std::vector<BoardMember>& out) {\n");
            for m in ms {
                h.push_str(&format!(
                    "    out.push_back({{(size_t)((const char*)&r->{n} - (const char*)r), sizeof(r->{n}), {o}, \"{n}\"}});\n",
                    n = m.name,
                    o = m.observed
                ));
            }
        }
        Err(why) => {
            h.push_str(&format!("// Not known: {}\n", why.replace('\n', " ")));
            h.push_str("static const bool kObservedKnown = false;\n");
            h.push_str("static void botsim_members(const Vboard___024root*, std::vector<BoardMember>&) {\n");
        }
    }
    h.push_str("}\n");
    // Each observed variable's reads (indices among the members, from `botsim_reads_at[i]` to
    // `botsim_reads_at[i + 1]` in `botsim_reads`) and whether it touches what leaves the model
    // (the harness's free parts, harness.cpp).
    let ms: &[Member] = members.as_deref().unwrap_or(&[]);
    let mut at = vec![0usize];
    let mut reads = Vec::new();
    for m in ms {
        reads.extend(m.reads.iter().map(|r| r.to_string()));
        at.push(reads.len());
    }
    reads.push("0".into()); // (never empty)
    let list = |v: Vec<String>| v.join(", ");
    h.push_str(&format!(
        "static const uint32_t botsim_reads_at[] = {{{}}};\nstatic const uint32_t botsim_reads[] = {{{}}};\nstatic const uint8_t botsim_external[] = {{{}}};\n",
        list(at.iter().map(|a| a.to_string()).collect()),
        list(reads),
        list(ms.iter().map(|m| u8::from(m.external).to_string()).chain(["0".into()]).collect()),
    ));
    // The counters (super::counters): each one's bytes, width, direction, largest step, the
    // lowest bit a shifted read sees (64: none), the constants it is compared with, the bit
    // where no read straddles (64: none), the lowest bit a read above it sees (64: none) and
    // the variables it is compared with (their bytes and the constant added to it first), and
    // its guarded reads (the lowest bit each sees, the guard's comparison, and whether it
    // compares with a variable (by its index among those) or a constant).
    h.push_str("static void botsim_counters(const Vboard___024root* r, std::vector<BoardCounter>& out) {\n");
    for c in counters {
        let guarded: Vec<String> = c
            .guarded
            .iter()
            .map(|g| {
                let guards: Vec<String> = g
                    .guards
                    .iter()
                    .map(|(op, with)| {
                        let (bound, value) = match with {
                            GuardedBy::Const(k) => (false, *k),
                            GuardedBy::Bound(i) => (true, *i as u64),
                        };
                        format!("{{BoardCmp::{op:?}, {bound}, {value}ull}}")
                    })
                    .collect();
                format!("{{{}, {{{}}}}}", g.lo, guards.join(", "))
            })
            .collect();
        let consts: Vec<String> = c.consts.iter().map(|k| format!("{k}ull")).collect();
        let bounds: Vec<String> = c
            .bounds
            .iter()
            .map(|(v, k)| format!("{{(size_t)((const char*)&r->{v} - (const char*)r), sizeof(r->{v}), {k}ull}}"))
            .collect();
        h.push_str(&format!(
            "    out.push_back({{(size_t)((const char*)&r->{n} - (const char*)r), sizeof(r->{n}), {bits}, {down}, {step}ull, {shift}, {{{consts}}}, {split}, {split_shift}, {{{bounds}}}, {{{guarded}}}, {{{sets}}}}});\n",
            n = c.name,
            bits = c.bits,
            down = c.down,
            step = c.step,
            shift = c.shift.unwrap_or(64),
            consts = consts.join(", "),
            split = c.split.unwrap_or(64),
            split_shift = c.split_shift.unwrap_or(64),
            bounds = bounds.join(", "),
            guarded = guarded.join(", "),
            sets = c.sets.iter().map(|k| format!("{k}ull")).collect::<Vec<_>>().join(", ")
        ));
    }
    h.push_str("}\n");
    // The KCPSM6 models whose out_port the design reads only under a write strobe
    // (super::strobes), by their instance's name.
    h.push_str("static const char* const botsim_out_port_free[] = {");
    for core in out_port_free {
        h.push_str(&format!("\"{core}\", "));
    }
    h.push_str("nullptr};\n");
    // The KCPSM6 models that may run apart (super::apart): each one's instance's name, then
    // its followers, then `@` and the ports of each follower written for some ports only,
    // separated by spaces.
    h.push_str("static const char* const botsim_apart[] = {");
    for a in apart {
        let ports = a.ports.iter().map(|p| format!("@{p}"));
        let words: Vec<String> =
            std::iter::once(a.core.clone()).chain(a.followers.iter().cloned()).chain(ports).collect();
        h.push_str(&format!("\"{}\", ", words.join(" ")));
    }
    h.push_str("nullptr};\n");
    h
}

/// The root's variables, by name, in the header's order.
fn root_members(header: &str) -> Result<Vec<String>, String> {
    let start = header.find("class Vboard___024root").ok_or("Verilator's root class was not found")?;
    let mut out = Vec::new();
    for line in header[start..].lines().skip(1) {
        let code = strip_comments(line);
        let code = code.trim();
        if code.starts_with("// INTERNAL VARIABLES") || line.contains("INTERNAL VARIABLES") {
            break;
        }
        if !code.ends_with(';') || code == "};" {
            continue;
        }
        let name = if code.starts_with("VL_IN") || code.starts_with("VL_OUT") {
            code.split(['(', ',']).nth(1).unwrap_or("").trim()
        } else if code.contains('(') {
            continue;
        } else {
            code.trim_end_matches(';')
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .rfind(|s| !s.is_empty())
                .unwrap_or("")
        };
        if !name.is_empty() {
            out.push(name.to_string());
        }
    }
    if out.is_empty() {
        return Err("the root's variables were not found".into());
    }
    Ok(out)
}

/// The variables the symbol table `syms` (`Vboard__Syms.cpp`) makes public for writing: the
/// generated clocks' levels, which the harness writes.
fn public_rw(syms: &str) -> Vec<String> {
    syms.lines()
        .filter(|l| l.contains("varInsert(") && l.contains("VLVF_PUB_RW"))
        .filter_map(|l| l.split("&(TOP.").nth(1).and_then(|r| r.split(')').next()))
        .map(str::to_string)
        .collect()
}

/// The root's inputs (the harness drives them).
fn root_inputs(header: &str) -> Vec<String> {
    header
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with("VL_IN"))
        .filter_map(|l| l.split(['(', ',']).nth(1))
        .map(|n| n.trim().to_string())
        .collect()
}

fn member_node(name: &str) -> String {
    format!("m:{name}")
}

fn fun_node(name: &str) -> String {
    format!("f:{name}")
}

/// Who feeds whom: `preds[i]` are the nodes node `i`'s value depends on.
#[derive(Default)]
struct Graph {
    ids: HashMap<String, usize>,
    preds: Vec<Vec<usize>>,
    roots: Vec<usize>,
    /// What a call outside the model writes (a DPI function's result, its arguments).
    results: Vec<usize>,
}

impl Graph {
    fn node(&mut self, key: &str) -> usize {
        if let Some(&i) = self.ids.get(key) {
            return i;
        }
        let i = self.preds.len();
        self.ids.insert(key.to_string(), i);
        self.preds.push(Vec::new());
        i
    }

    /// Every node a root depends on, the roots included.
    fn ancestors(&self) -> Vec<bool> {
        self.ancestors_of(&self.roots)
    }

    /// Every node one of `roots` depends on, `roots` included.
    fn ancestors_of(&self, roots: &[usize]) -> Vec<bool> {
        let mut seen = vec![false; self.preds.len()];
        let mut stack = roots.to_vec();
        while let Some(i) = stack.pop() {
            if std::mem::replace(&mut seen[i], true) {
                continue;
            }
            stack.extend(self.preds[i].iter().copied().filter(|&p| !seen[p]));
        }
        seen
    }
}

/// Types a local declaration begins with.
const TYPES: &[&str] = &[
    "CData",
    "SData",
    "IData",
    "QData",
    "EData",
    "VlWide",
    "VlUnpacked",
    "Vboard__Syms",
    "const",
    "bool",
    "int",
    "size_t",
    "char",
    "long",
    "unsigned",
    "void",
    "uint8_t",
    "uint16_t",
    "uint32_t",
    "uint64_t",
];

/// The assignment operators.
const ASSIGN: &[&str] = &["=", "|=", "&=", "^=", "+=", "-=", "*=", "/=", "%=", "<<=", ">>="];

/// What a statement names.
#[derive(Default)]
struct Named {
    /// Variables (and triggers) read or written.
    vars: Vec<usize>,
    /// Variables that a macro with an output argument may write.
    outputs: Vec<usize>,
    /// It calls something outside the model (a DPI function, the runtime).
    outside: bool,
    /// The model's own functions it calls with `vlSelf` alone.
    calls: Vec<String>,
}

/// A signal a waveform function dumps: `bufp->fullCData(oldp+code, value, width)`.
struct Dump {
    code: u32,
    width: u32,
    /// What its value names.
    vars: Vec<usize>,
    /// Its value calls something (not a plain expression of variables).
    opaque: bool,
}

struct Parser<'a, 'g> {
    g: &'g mut Graph,
    toks: &'a [Tok<'a>],
    fun: &'a str,
    locals: HashSet<&'a str>,
    calls: Vec<String>,
    /// In a waveform function: the signals it dumps.
    dumps: Option<Vec<Dump>>,
}

impl<'a> Parser<'a, '_> {
    fn tok(&self, i: usize) -> Tok<'a> {
        self.toks.get(i).copied().unwrap_or(Tok::P(""))
    }

    fn unknown(&self, at: usize) -> String {
        let near: Vec<String> = self.toks[at.min(self.toks.len())..(at + 6).min(self.toks.len())]
            .iter()
            .map(|t| match t {
                Tok::Id(s) | Tok::Num(s) | Tok::P(s) => s.to_string(),
                Tok::Str => "\"…\"".into(),
            })
            .collect();
        format!("a construct the analysis does not know in `{}` (`{}`)", self.fun, near.join(" "))
    }

    /// The index just past the bracket that closes the one at `open`.
    fn close(&self, open: usize) -> Result<usize, String> {
        let mut depth = 0usize;
        for i in open..self.toks.len() {
            match self.tok(i) {
                Tok::P("(" | "[" | "{") => depth += 1,
                Tok::P(")" | "]" | "}") => {
                    depth -= 1;
                    if depth == 0 {
                        return Ok(i + 1);
                    }
                }
                _ => {}
            }
        }
        Err(self.unknown(open))
    }

    /// Statements up to the end of the body or (in a block) its closing brace; `ctrl`: what
    /// decides whether they run.
    fn block(&mut self, at: &mut usize, ctrl: &[usize], braced: bool) -> Result<(), String> {
        while *at < self.toks.len() {
            if self.tok(*at) == Tok::P("}") {
                if braced {
                    *at += 1;
                    return Ok(());
                }
                return Err(self.unknown(*at));
            }
            self.statement(at, ctrl)?;
        }
        if braced {
            return Err(self.unknown(*at));
        }
        Ok(())
    }

    /// A block or a single statement.
    fn body(&mut self, at: &mut usize, ctrl: &[usize]) -> Result<(), String> {
        if self.tok(*at) == Tok::P("{") {
            *at += 1;
            self.block(at, ctrl, true)
        } else {
            self.statement(at, ctrl)
        }
    }

    /// The statement at `*at`, by its kind, leaving `*at` past it; `ctrl`: the variables
    /// the conditions around it read.
    fn statement(&mut self, at: &mut usize, ctrl: &[usize]) -> Result<(), String> {
        match self.tok(*at) {
            Tok::P("{") => self.body(at, ctrl),
            Tok::P(";") => {
                *at += 1;
                Ok(())
            }
            Tok::Id("if" | "while") => self.conditional(at, ctrl),
            Tok::Id("for") => self.for_loop(at, ctrl),
            Tok::Id("return") => self.return_value(at, ctrl),
            Tok::Id("VL_DEBUG_IF") => {
                *at = self.end(*at)?;
                Ok(())
            }
            Tok::Id("else" | "switch" | "case" | "default" | "do" | "goto" | "break" | "continue") => {
                Err(self.unknown(*at))
            }
            _ => {
                let end = self.end(*at)?;
                self.simple(*at, end - 1, ctrl)?;
                *at = end;
                Ok(())
            }
        }
    }

    /// `if (c) ... else if (d) ... else ...` or `while (c) ...`: each condition feeds what
    /// its body and every later branch assign.
    fn conditional(&mut self, at: &mut usize, ctrl: &[usize]) -> Result<(), String> {
        let mut inner = ctrl.to_vec();
        loop {
            if self.tok(*at + 1) != Tok::P("(") {
                return Err(self.unknown(*at));
            }
            let end = self.close(*at + 1)?;
            let cond = self.named(*at + 2, end - 1)?;
            self.effects(&cond, &[], ctrl);
            inner.extend(cond.vars.iter().copied());
            *at = end;
            self.body(at, &inner)?;
            if self.tok(*at) != Tok::Id("else") {
                return Ok(());
            }
            *at += 1;
            if self.tok(*at) != Tok::Id("if") {
                return self.body(at, &inner);
            }
        }
    }

    /// `for (init; cond; step) ...`: the loop's own variables are declared in its head, and
    /// each depends on all of it, as does its body.
    fn for_loop(&mut self, at: &mut usize, ctrl: &[usize]) -> Result<(), String> {
        if self.tok(*at + 1) != Tok::P("(") {
            return Err(self.unknown(*at));
        }
        let end = self.close(*at + 1)?;
        for i in *at + 2..end - 1 {
            if let (Tok::Id(t), Tok::Id(n)) = (self.tok(i), self.tok(i + 1)) {
                if TYPES.contains(&t) {
                    self.locals.insert(n);
                }
            }
        }
        let head = self.named(*at + 2, end - 1)?;
        let vars = head.vars.clone();
        self.effects(&head, &vars, ctrl);
        let mut inner = ctrl.to_vec();
        inner.extend(head.vars.iter().copied());
        *at = end;
        self.body(at, &inner)
    }

    /// `return x;`: what the function returns depends on `x`.
    fn return_value(&mut self, at: &mut usize, ctrl: &[usize]) -> Result<(), String> {
        let end = self.end(*at)?;
        let named = self.named(*at + 1, end - 1)?;
        let ret = self.g.node(&format!("r:{}", self.fun));
        self.effects(&named, &[ret], ctrl);
        *at = end;
        Ok(())
    }

    /// The index just past the `;` that ends the statement at `from`.
    fn end(&self, from: usize) -> Result<usize, String> {
        let mut i = from;
        while i < self.toks.len() {
            match self.tok(i) {
                Tok::P("(" | "[" | "{") => i = self.close(i)?,
                Tok::P(";") => return Ok(i + 1),
                Tok::P("}") => return Err(self.unknown(from)),
                _ => i += 1,
            }
        }
        Err(self.unknown(from))
    }

    /// A declaration, an assignment or a call: tokens `from..to` (the `;` excluded). In a
    /// waveform function, a dump of a signal.
    fn simple(&mut self, from: usize, to: usize, ctrl: &[usize]) -> Result<(), String> {
        if self.dumps.is_some() {
            if let (Tok::Id("bufp"), Tok::P("->"), Tok::Id(f), Tok::P("(")) =
                (self.tok(from), self.tok(from + 1), self.tok(from + 2), self.tok(from + 3))
            {
                if f.starts_with("full") && self.close(from + 3)? == to {
                    return self.dump(f, from + 4, to - 1);
                }
            }
        }
        let op = self.assignment_operator(from, to)?;
        if matches!(self.tok(from), Tok::Id(t) if TYPES.contains(&t)) {
            return self.declaration(from, to, op, ctrl);
        }
        match op {
            Some(op) => {
                let lhs = self.named(from, op)?;
                let target = *lhs.vars.first().ok_or_else(|| self.unknown(from))?;
                let mut rhs = self.named(op + 1, to)?;
                rhs.vars.extend(lhs.vars[1..].iter().copied());
                rhs.outputs.extend(lhs.outputs.iter().copied());
                rhs.outside |= lhs.outside;
                rhs.calls.extend(lhs.calls);
                self.effects(&rhs, &[target], ctrl);
            }
            None => {
                let named = self.named(from, to)?;
                // A member function on a variable (`x.clear()`) writes it.
                let targets = named.vars.clone();
                self.effects(&named, &targets, ctrl);
            }
        }
        Ok(())
    }

    /// The top-level assignment operator of tokens `from..to` (outside brackets), if any.
    fn assignment_operator(&self, from: usize, to: usize) -> Result<Option<usize>, String> {
        let mut i = from;
        while i < to {
            match self.tok(i) {
                Tok::P("(" | "[" | "{") => {
                    i = self.close(i)?;
                    continue;
                }
                Tok::P(p) if ASSIGN.contains(&p) => return Ok(Some(i)),
                _ => {}
            }
            i += 1;
        }
        Ok(None)
    }

    /// A local declaration, `T name [= value]`: the local, fed by its value.
    fn declaration(&mut self, from: usize, to: usize, op: Option<usize>, ctrl: &[usize]) -> Result<(), String> {
        let name = self.toks[from..op.unwrap_or(to)]
            .iter()
            .rev()
            .find_map(|t| match t {
                Tok::Id(n) if !n.starts_with("VL_") && *n != "__restrict" && *n != "const" => Some(*n),
                _ => None,
            })
            .ok_or_else(|| self.unknown(from))?;
        self.locals.insert(name);
        if let Some(op) = op {
            let target = self.g.node(&format!("l:{}:{name}", self.fun));
            let rhs = self.named(op + 1, to)?;
            self.effects(&rhs, &[target], ctrl);
        }
        Ok(())
    }

    /// A waveform function's `bufp->full*(oldp+code, value[, width])`, its arguments `from..to`.
    fn dump(&mut self, f: &str, from: usize, to: usize) -> Result<(), String> {
        // The arguments, split at the commas outside brackets.
        let mut args = Vec::new();
        let (mut start, mut i) = (from, from);
        while i < to {
            match self.tok(i) {
                Tok::P("(" | "[" | "{") => i = self.close(i)?,
                Tok::P(",") => {
                    args.push((start, i));
                    i += 1;
                    start = i;
                }
                _ => i += 1,
            }
        }
        args.push((start, to));
        let num = |t: Tok| match t {
            Tok::Num(n) => n.trim_end_matches(['U', 'L']).parse::<u32>().ok(),
            _ => None,
        };
        let code = match (args.first(), args.len()) {
            (Some(&(a, b)), 2 | 3)
                if b == a + 3 && self.tok(a) == Tok::Id("oldp") && self.tok(a + 1) == Tok::P("+") =>
            {
                num(self.tok(a + 2))
            }
            _ => None,
        };
        let width = match (f, args.get(2)) {
            ("fullBit", None) => Some(1),
            ("fullDouble", None) => Some(64),
            (_, Some(&(a, b))) if b == a + 1 => num(self.tok(a)),
            _ => None,
        };
        let (Some(code), Some(width)) = (code, width) else { return Err(self.unknown(from - 4)) };
        let value = self.named(args[1].0, args[1].1)?;
        let opaque = value.outside || !value.calls.is_empty() || !value.outputs.is_empty();
        self.dumps.get_or_insert_with(Vec::new).push(Dump { code, width, vars: value.vars, opaque });
        Ok(())
    }

    /// Record a statement: `targets` (and any macro outputs) depend on everything it names and
    /// on `ctrl`; a call outside the model observes all of that; the model's functions it
    /// calls run under `ctrl`.
    fn effects(&mut self, named: &Named, targets: &[usize], ctrl: &[usize]) {
        let sources: Vec<usize> = named.vars.iter().chain(ctrl).copied().collect();
        for &t in targets.iter().chain(&named.outputs) {
            self.g.preds[t].extend(sources.iter().copied().filter(|&s| s != t));
        }
        if named.outside {
            self.g.roots.extend(sources.iter().copied());
            self.g.roots.extend(targets.iter().copied());
            self.g.results.extend(targets.iter().chain(&named.outputs).copied());
        }
        for f in &named.calls {
            let node = self.g.node(&fun_node(f));
            self.g.preds[node].extend(ctrl.iter().copied());
            self.g.preds[node].extend(named.vars.iter().copied());
            self.calls.push(f.clone());
        }
    }

    /// What tokens `from..to` name.
    fn named(&mut self, from: usize, to: usize) -> Result<Named, String> {
        let mut n = Named::default();
        let mut i = from;
        while i < to {
            match self.tok(i) {
                Tok::Id("vlSelf") if self.tok(i + 1) == Tok::P("->") => {
                    let Tok::Id(m) = self.tok(i + 2) else { return Err(self.unknown(i)) };
                    i += 3;
                    if m.ends_with("Triggered") {
                        // A trigger, one bit at a time: `.at(k)`; the NBA region's are the
                        // active region's.
                        let kind = match m {
                            "__VactTriggered" | "__VnbaTriggered" => "act",
                            "__VicoTriggered" => "ico",
                            _ => return Err(format!("Verilator's trigger vector `{m}` in `{}`", self.fun)),
                        };
                        let (Tok::P("."), Tok::Id("at"), Tok::P("("), Tok::Num(k), Tok::P(")")) =
                            (self.tok(i), self.tok(i + 1), self.tok(i + 2), self.tok(i + 3), self.tok(i + 4))
                        else {
                            return Err(self.unknown(i - 3));
                        };
                        let k = k.trim_end_matches(['U', 'L']);
                        n.vars.push(self.g.node(&format!("t:{kind}:{k}")));
                        i += 5;
                    } else if m == "vlSymsp" {
                        // The symbol table's pointer, kept in a local (its uses are below).
                    } else {
                        n.vars.push(self.g.node(&member_node(m)));
                    }
                }
                Tok::Id("vlSymsp") if self.tok(i + 1) == Tok::P("->") => {
                    n.outside = true;
                    i += 2;
                }
                Tok::P(".") | Tok::P("->") => {
                    // A member function or field of what came before (`.at`, `.m_storage`).
                    i += 2;
                }
                Tok::Id(f) if self.tok(i + 1) == Tok::P("(") => {
                    let end = self.close(i + 1)?;
                    // The model itself as an argument (not one of its variables).
                    let passes_self =
                        (i + 2..end).any(|j| self.tok(j) == Tok::Id("vlSelf") && self.tok(j + 1) != Tok::P("->"));
                    if f.starts_with("Vboard___024root___") && end == i + 4 && passes_self {
                        n.calls.push(f.to_string());
                        let ret = self.g.node(&format!("r:{f}"));
                        n.vars.push(ret);
                    } else if passes_self {
                        // A function given the model and more: its writes are not read here.
                        return Err(self.unknown(i));
                    } else if let Some(rest) = f.strip_prefix("VL_") {
                        const SIDE: &[&str] = &[
                            "FINISH", "FATAL", "STOP", "WRITE", "READ", "PRINT", "DBG", "FOPEN", "FCLOSE", "FFLUSH",
                            "SYSTEM", "TIME", "RAND", "SFORMAT", "SCANF", "PLUSARGS",
                        ];
                        if SIDE.iter().any(|s| rest.contains(s)) {
                            n.outside = true;
                        } else if rest.rsplit('_').next().is_some_and(|s| s.contains('W'))
                            || ["ASSIGN", "CONST", "ZERO", "SET", "ALLONES"].iter().any(|s| rest.starts_with(s))
                        {
                            // Wide results are written through an argument: any of them.
                            let args = self.named(i + 2, end - 1)?;
                            n.outputs.extend(args.vars.iter().copied());
                        }
                    } else if !TYPES.contains(&f) && !matches!(f, "static_cast" | "sizeof") {
                        n.outside = true;
                    }
                    // The arguments are named like any expression.
                    i += 1;
                }
                Tok::Id(l) if self.locals.contains(l) => {
                    n.vars.push(self.g.node(&format!("l:{}:{l}", self.fun)));
                    i += 1;
                }
                _ => i += 1,
            }
        }
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROOT: &str = include_str!("fixtures/vga_root.h");

    /// A board: the display from a counter on the system clock, a VGA column counter and pixel
    /// on a second clock; `extra` is added to the system clock's function.
    fn code(extra: &str) -> String {
        include_str!("fixtures/vga_board.cpp").replace("    // extra\n", extra)
    }

    fn observed(extra: &str) -> Vec<String> {
        let c = code(extra);
        let m = members(ROOT, &[&c]).unwrap();
        m.into_iter().filter(|m| m.observed).map(|m| m.name).collect()
    }

    #[test]
    fn a_vga_part_that_nothing_recorded_reads_is_not_observed() {
        let seen = observed("");
        for n in ["clk", "an", "digit", "en", "cpu", "__Vtrigrprev__TOP__clk"] {
            assert!(seen.iter().any(|s| s == n), "{n} not observed: {seen:?}");
        }
        for n in ["vga_r", "col", "cells", "q25", "__Vtrigrprev__TOP__q25", "frames", "__VactTriggered"] {
            assert!(!seen.iter().any(|s| s == n), "{n} observed: {seen:?}");
        }
    }

    #[test]
    fn whatever_feeds_what_is_recorded_is_observed() {
        // Through a condition: the display counts frames.
        let seen = observed("    if ((0U == (IData)(vlSelf->col))) {\n        vlSelf->frames = (0xffU & ((IData)(1U) + (IData)(vlSelf->frames)));\n    }\n    vlSelf->an = vlSelf->frames;\n");
        for n in ["frames", "col", "q25", "__Vtrigrprev__TOP__q25"] {
            assert!(seen.iter().any(|s| s == n), "{n} not observed: {seen:?}");
        }
        // Through an index, and through a model's pins.
        let seen = observed("    vlSelf->an = vlSelf->cells[(0xfU & (IData)(vlSelf->frames))];\n");
        assert!(seen.iter().any(|s| s == "cells") && seen.iter().any(|s| s == "frames"), "{seen:?}");
        let seen = observed("    Vboard___024root____Vdpiimwrap_tick_TOP(vlSelf->cpu, (IData)(vlSelf->col), __Vfunc_tick__1__Vfuncout);\n");
        assert!(seen.iter().any(|s| s == "col"), "{seen:?}");
        // Through a local.
        let seen =
            observed("    CData/*7:0*/ __Vtemp;\n    __Vtemp = (IData)(vlSelf->col);\n    vlSelf->an = __Vtemp;\n");
        assert!(seen.iter().any(|s| s == "col"), "{seen:?}");
        // A call to anything outside the model ($finish) observes what it names and its condition.
        let seen =
            observed("    if ((5U == (IData)(vlSelf->frames))) {\n        VL_FINISH_MT(\"top.v\", 9, \"\");\n    }\n");
        assert!(seen.iter().any(|s| s == "frames"), "{seen:?}");
    }

    #[test]
    fn each_observed_variable_knows_what_it_reads_and_whether_it_leaves_the_model() {
        // A free count beside the CPU model (the DPI call in the same function: its function
        // running is not the call's result).
        let c = code("    vlSelf->frames = (0xffU & ((IData)(1U) + (IData)(vlSelf->frames)));\n    vlSelf->an = vlSelf->frames;\n");
        let m = members(ROOT, &[&c]).unwrap();
        let at = |n: &str| m.iter().position(|x| x.name == n).unwrap_or_else(|| panic!("{n}"));
        let frames = &m[at("frames")];
        assert!(frames.observed && !frames.external, "{frames:?}");
        // Its clock's trigger, through the function and the trigger; not itself.
        for n in ["clk", "__Vtrigrprev__TOP__clk"] {
            assert!(frames.reads.contains(&at(n)), "{n}: {frames:?}");
        }
        assert!(!frames.reads.contains(&at("frames")), "{frames:?}");
        // The model's pins and what its result feeds leave the model, as do the records.
        for n in ["en", "digit", "an"] {
            assert!(m[at(n)].external, "{n}: {:?}", m[at(n)]);
        }
        // Not observed: no reads.
        assert!(m[at("col")].reads.is_empty() && !m[at("col")].observed);
    }

    #[test]
    fn what_the_analysis_does_not_know_ends_it() {
        let c = code("    switch (vlSelf->col) { case 1: vlSelf->an = 0U; }\n");
        let why = members(ROOT, &[&c]).unwrap_err();
        assert!(why.contains("does not know") && why.contains("switch"), "{why}");
        let c = code("    vlSelf->an = vlSelf->__VactTriggered.word(0);\n");
        assert!(members(ROOT, &[&c]).is_err());
        let c = code("    Vboard___024root____VnoInFunc_count(vlSelf, 3U);\n");
        assert!(members(ROOT, &[&c]).unwrap_err().contains("VnoInFunc_count"));
        let c = code("").replace("vlSelf->__VactIterCount = 0U;", "vlSelf->frames = 0U;");
        assert!(members(ROOT, &[&c]).unwrap_err().contains("scheduler reads `frames`"));
    }

    #[test]
    fn a_waveform_shows_what_is_observed_or_never_written() {
        // The test board's waveform: the display, the VGA pixel, the pixel clock (written by
        // the harness: public), a cell of the map (never written), one value through a local.
        let trace = include_str!("fixtures/vga_trace.cpp");
        let syms = "        __Vscope_top__clkgen.varInsert(__Vfinal,\"q\", &(TOP.q25), false, VLVT_UINT8,VLVD_NODIR|VLVF_PUB_RW,0);\n";
        let codes = |syms: &str| -> Vec<u32> {
            unshown(ROOT, &[&code("")], &[trace], syms).unwrap().iter().map(|u| u.code).collect()
        };
        // `frames` is never written by this board: a constant, like `cells`.
        assert_eq!(codes(syms), [2, 3, 5]);
        // Without the symbol table's word, the pixel clock would pass for a constant.
        assert_eq!(codes(""), [2, 5]);
        let wide = unshown(ROOT, &[&code("")], &[trace], syms).unwrap();
        assert_eq!(wide.iter().find(|u| u.code == 5).map(|u| u.width), Some(96));
        // Another way of numbering the signals is not read.
        let other = trace.replace("__Vm_baseCode)", "__Vm_baseCode + 1)");
        assert!(unshown(ROOT, &[&code("")], &[&other], syms).unwrap_err().contains("numbers its signals another way"));
        assert!(unshown(ROOT, &[&code("")], &[], syms).is_err());
    }

    #[test]
    fn the_harness_reads_only_what_the_analysis_counts_as_observed() {
        // Every output the run loop reads of the top, but for the VGA pins (read only when
        // frames are recorded) and the inputs it drives.
        // It reaches them through board_model.h's ports, `io`.
        let harness = include_str!("../board/harness.cpp");
        let mut read: Vec<&str> = harness
            .match_indices("io.")
            .filter(|(i, _)| !harness[..*i].ends_with(|c: char| c.is_alphanumeric() || c == '_'))
            .map(|(i, m)| {
                let rest = &harness[i + m.len()..];
                &rest[..rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len())]
            })
            .collect();
        assert!(read.len() > 20, "the harness's reads of the ports were not found");
        read.sort();
        read.dedup();
        for r in read {
            // (eventsPending, nextTimeSlot: the timed events of a design with delays.)
            let driven = [
                "clk",
                "reset_pressed",
                "btn",
                "sw",
                // What the host sends the peripherals.
                "uart_push",
                "ps2_push",
                "push_n",
                "push_bytes",
                "uart_div",
                "tilt_x",
                "tilt_y",
                "tilt_z",
            ]
            .contains(&r);
            let vga = ["vga_r", "vga_g", "vga_b", "hsync", "vsync"].contains(&r);
            // (An array of ports, `xbot_regs[k]`: the wrapper's `xbot_regs1`...)
            let first = format!("{r}1");
            let read = HARNESS_READS.contains(&r) || HARNESS_READS.contains(&first.as_str());
            assert!(driven || vga || read, "the harness reads `{r}`: add it to HARNESS_READS");
        }
    }
}
