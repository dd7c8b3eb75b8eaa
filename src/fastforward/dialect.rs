//! The build-time analyses ([`super::checks`], [`super::observed`], [`super::counters`])
//! read the C++ that Verilator 5.006 generates. Later versions write the same model in
//! another dialect; this module rewrites it into 5.006's, for the analyses only (the
//! harness compiles against the real output). What changed, and what becomes of it:
//!
//! | later Verilator (5.02x-5.04x) | 5.006, as the analyses read it |
//! |---|---|
//! | `auto& vlSelfRef = std::ref(*vlSelf).get();`, `vlSelfRef.x` | `vlSelf->x` |
//! | `VlUnpacked<QData/*63:0*/, W> __VactTriggered;` | `VlTriggerVec<N> __VactTriggered;` |
//! | one word for all triggers: `__VactTriggered[0U] = (QData)((IData)((t1 << 1U) \| t0));` | one statement per trigger: `__VactTriggered.at(1U) = t1;` |
//! | a trigger read as a mask: `(2ULL & vlSelfRef.__VnbaTriggered[0U])` | `vlSelf->__VnbaTriggered.at(1U)` |
//! | `___eval` loops over `___eval_phase__{ico,act,nba}` | `___eval` calls the regions: `___eval_triggers__ico`, `___eval_ico`, ... `___eval_nba` |
//! | `___eval_triggers_vec__act` | `___eval_triggers__act` |
//! | the NBA functions inlined, their delayed copies `__Vinline__f___Vdly__x` | `__Vdly__x` |
//! | the waveform's values in `__trace_full_0_sub_0` and its constants in `__trace_const_0_sub_0` | both `__trace_full_sub_*` |
//! | `class alignas(VL_CACHE_LINE_BYTES) Vboard___024root final {` | `class Vboard___024root final : public VerilatedModule {` |
//!
//! A shape this module does not know is left as it is: the analyses then say what they
//! could not read, and the board runs every edge (exact, slower).
//!
//! ```
//! use botsim::fastforward::dialect;
//! let code = "void Vboard___024root___eval_triggers_vec__act(Vboard___024root* vlSelf) {\n    auto& vlSelfRef = std::ref(*vlSelf).get();\n    vlSelfRef.__VactTriggered[0U] = (QData)((IData)(((((IData)(vlSelfRef.q) & (~ (IData)(vlSelfRef.__Vtrigprevexpr___TOP__q__0))) << 1U) | ((IData)(vlSelfRef.clk) & (~ (IData)(vlSelfRef.__Vtrigprevexpr___TOP__clk__0))))));\n}\n";
//! let (_, code) = dialect::to_5006("", &[code.to_string()]);
//! assert!(code[0].contains("void Vboard___024root___eval_triggers__act(Vboard___024root* vlSelf) {"));
//! let flat = botsim::fastforward::cpp::squeeze(&code[0]);
//! assert!(flat.contains("vlSelf->__VactTriggered.at(0U)=((IData)(vlSelf->clk)&(~(IData)(vlSelf->__Vtrigprevexpr___TOP__clk__0)));"));
//! assert!(flat.contains("vlSelf->__VactTriggered.at(1U)=((IData)(vlSelf->q)&(~(IData)(vlSelf->__Vtrigprevexpr___TOP__q__0)));"));
//! ```

use super::cpp::{closing, functions, tokens, Tok};

/// The trigger vectors of the scheduler's regions.
const VECTORS: [&str; 4] = ["stl", "ico", "act", "nba"];

/// The root's header and the code files, in 5.006's dialect (unchanged when they are in it).
pub fn to_5006(root: &str, code: &[String]) -> (String, Vec<String>) {
    // A later version: `vlSelfRef`, or the triggers declared as words.
    let word_triggers =
        root.lines().any(|l| l.contains("VlUnpacked<QData/*63:0*/") && l.contains("> __VactTriggered;"));
    let newer = word_triggers || code.iter().any(|c| c.contains("vlSelfRef"));
    if !newer {
        return (root.to_string(), code.to_vec());
    }
    let mut code: Vec<String> = code.iter().map(|c| plain_self(c)).collect();
    let mut counts = [0usize; 4];
    for c in code.iter_mut() {
        *c = c.replace("___eval_triggers_vec__", "___eval_triggers__");
        *c = trace_names(c);
        *c = split_trigger_words(c, &mut counts);
        *c = trigger_masks(c);
        *c = inlined_delays(c);
    }
    // The NBA region's triggers are the active region's.
    counts[3] = counts[3].max(counts[2]);
    scheduler(&mut code);
    (header(root, &counts), code)
}

/// The waveform's functions named as 5.006 names those that write every value
/// (`Vboard___024root__trace_full_sub_0`): `trace_full_0_sub_0` and `trace_const_0_sub_0`.
fn trace_names(code: &str) -> String {
    let mut out = code.to_string();
    for (kind, tag) in [("full", ""), ("const", "const")] {
        let prefix = format!("Vboard___024root__trace_{kind}_");
        let mut rest = out.as_str();
        let mut next = String::new();
        while let Some(at) = rest.find(&prefix) {
            let tail = &rest[at + prefix.len()..];
            let digits = |s: &str| s.chars().take_while(char::is_ascii_digit).count();
            let n = digits(tail);
            let renamed = (n > 0 && tail[n..].starts_with("_sub_") && digits(&tail[n + 5..]) > 0).then(|| {
                let m = digits(&tail[n + 5..]);
                (format!("Vboard___024root__trace_full_sub_{tag}{}_{}", &tail[..n], &tail[n + 5..n + 5 + m]), n + 5 + m)
            });
            next.push_str(&rest[..at]);
            match renamed {
                Some((name, len)) => {
                    next.push_str(&name);
                    rest = &tail[len..];
                }
                None => {
                    next.push_str(&prefix);
                    rest = tail;
                }
            }
        }
        next.push_str(rest);
        out = next;
    }
    out
}

/// `vlSelfRef.x` as `vlSelf->x`, its declaration gone.
fn plain_self(code: &str) -> String {
    code.lines()
        .filter(|l| l.trim() != "auto& vlSelfRef = std::ref(*vlSelf).get();")
        .map(|l| l.replace("vlSelfRef.", "vlSelf->") + "\n")
        .collect()
}

/// The header: the root class as 5.006 declares it, each trigger vector with its count.
fn header(root: &str, counts: &[usize; 4]) -> String {
    let mut out = root.replace(
        "class alignas(VL_CACHE_LINE_BYTES) Vboard___024root final {",
        "class Vboard___024root final : public VerilatedModule {",
    );
    for (v, n) in VECTORS.iter().zip(counts) {
        for words in 1..=4 {
            let newer = format!("VlUnpacked<QData/*63:0*/, {words}> __V{v}Triggered;");
            let n = if *n == 0 { 64 * words } else { *n };
            out = out.replace(&newer, &format!("VlTriggerVec<{n}> __V{v}Triggered;"));
        }
    }
    out
}

/// The text of tokens, spaced (the analyses read it without white space, or as tokens).
fn text(toks: &[Tok<'_>]) -> String {
    let mut out = String::new();
    for t in toks {
        if !out.is_empty() {
            out.push(' ');
        }
        match t {
            Tok::Id(s) | Tok::Num(s) | Tok::P(s) => out.push_str(s),
            Tok::Str => out.push_str("\"\""),
        }
    }
    out
}

/// The expression without its outer parentheses and casts (`(QData)((IData)(e))` is `e`).
fn strip<'a, 'b>(mut toks: &'b [Tok<'a>]) -> &'b [Tok<'a>] {
    loop {
        match toks {
            // A cast of the whole rest: `(IData)(e)`.
            [Tok::P("("), Tok::Id(t), Tok::P(")"), rest @ ..]
                if ["QData", "IData", "CData", "SData"].contains(t)
                    && rest.first() == Some(&Tok::P("("))
                    && closing(rest, 0) == Some(rest.len() - 1) =>
            {
                toks = rest;
            }
            [Tok::P("("), .., Tok::P(")")] if closing(toks, 0) == Some(toks.len() - 1) => {
                toks = &toks[1..toks.len() - 1]
            }
            _ => return toks,
        }
    }
}

/// The terms of an `|` at the top level of `toks`.
fn or_terms<'a, 'b>(toks: &'b [Tok<'a>]) -> Vec<&'b [Tok<'a>]> {
    let mut out = Vec::new();
    let (mut depth, mut from) = (0i32, 0);
    for (i, t) in toks.iter().enumerate() {
        match t {
            Tok::P("(") => depth += 1,
            Tok::P(")") => depth -= 1,
            Tok::P("|") if depth == 0 => {
                out.push(&toks[from..i]);
                from = i + 1;
            }
            _ => {}
        }
    }
    out.push(&toks[from..]);
    out
}

/// A number of the generated code (`1U`, `0x20U`, `0x0000000000000004ULL`).
fn number(s: &str) -> Option<u64> {
    let s = s.trim_end_matches(['U', 'L', 'u', 'l']);
    match s.strip_prefix("0x") {
        Some(h) => u64::from_str_radix(h, 16).ok(),
        None => s.parse().ok(),
    }
}

/// Each trigger of a word (`__VactTriggered[W] = ...;`) as a statement of its own.
fn split_trigger_words(code: &str, counts: &mut [usize; 4]) -> String {
    let mut out = String::new();
    let mut rest = code;
    while let Some(at) = rest.find("vlSelf->__V") {
        let after = &rest[at + "vlSelf->__V".len()..];
        let Some(v) = VECTORS.iter().position(|v| after.starts_with(&format!("{v}Triggered["))) else {
            out.push_str(&rest[..at + 1]);
            rest = &rest[at + 1..];
            continue;
        };
        let Some(end) = rest[at..].find(';').map(|e| at + e) else { break };
        let statement = &rest[at..end];
        match split_statement(statement, VECTORS[v]) {
            Some(lines) => {
                let indent = &rest[rest[..at].rfind('\n').map_or(0, |i| i + 1)..at];
                out.push_str(&rest[..at]);
                for (k, line) in lines.iter().enumerate() {
                    if k > 0 {
                        out.push_str(";\n");
                        out.push_str(indent);
                    }
                    out.push_str(&line.1);
                    counts[v] = counts[v].max(line.0 + 1);
                }
                rest = &rest[end..];
            }
            None => {
                out.push_str(&rest[..=at]);
                rest = &rest[at + 1..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// `vlSelf->__VactTriggered[W] = e` as (trigger, statement) pairs, each statement without
/// its `;`; `None` when it is not an assignment of a whole word.
fn split_statement(statement: &str, v: &str) -> Option<Vec<(usize, String)>> {
    let toks = tokens(statement).ok()?;
    // vlSelf -> __VactTriggered [ W ] = e
    let (Tok::Id("vlSelf"), Tok::P("->"), Tok::Id(_), Tok::P("["), Tok::Num(w), Tok::P("]"), Tok::P("=")) =
        (*toks.first()?, *toks.get(1)?, *toks.get(2)?, *toks.get(3)?, *toks.get(4)?, *toks.get(5)?, *toks.get(6)?)
    else {
        return None;
    };
    let word = number(w)? as usize;
    let mut out = Vec::new();
    let mut pending = vec![strip(&toks[7..])];
    while let Some(e) = pending.pop() {
        let terms = or_terms(e);
        if terms.len() > 1 {
            pending.extend(terms.into_iter().map(strip));
            continue;
        }
        // A term of its own vector: the bits kept from before (another statement sets them).
        let mine = format!("__V{v}Triggered");
        if e.iter().any(|t| *t == Tok::Id(&mine)) {
            continue;
        }
        // `(t) << k`, or `t` for bit 0.
        let (term, shift) = match e {
            [body @ .., Tok::P("<<"), Tok::Num(k)] => (strip(body), number(k)? as usize),
            _ => (e, 0),
        };
        let k = 64 * word + shift;
        out.push((k, format!("vlSelf->__V{v}Triggered.at({k}U) = ({})", text(term))));
    }
    out.sort();
    (!out.is_empty()).then_some(out)
}

/// `(MASK & vlSelf->__VnbaTriggered[W])` as the triggers of the mask's bits, or-ed.
fn trigger_masks(code: &str) -> String {
    let mut out = String::new();
    let mut rest = code;
    while let Some(at) = rest.find("Triggered[") {
        // Back to the `(`: `( MASK & vlSelf->__Vxxx` with any spacing.
        let head = &rest[..at];
        let name_start = head.rfind("vlSelf->__V");
        let parsed = name_start.and_then(|n| {
            let v = &head[n + "vlSelf->__V".len()..];
            let before = head[..n].trim_end();
            let before = before.strip_suffix('&')?.trim_end();
            let mask_start = before.rfind(|c: char| !(c.is_ascii_alphanumeric()))? + 1;
            let mask = number(&before[mask_start..])?;
            let open = before[..mask_start].trim_end();
            if !open.ends_with('(') {
                return None;
            }
            let tail = &rest[at + "Triggered[".len()..];
            let close = tail.find(']')?;
            let word = number(&tail[..close])? as usize;
            let after = tail[close + 1..].trim_start();
            if !after.starts_with(')') {
                return None;
            }
            let consumed = at + "Triggered[".len() + close + 1 + (tail[close + 1..].len() - after.len()) + 1;
            let bits: Vec<String> = (0..64)
                .filter(|b| mask >> b & 1 == 1)
                .map(|b| format!("vlSelf->__V{v}Triggered.at({}U)", 64 * word + b))
                .collect();
            (!bits.is_empty()).then(|| (open.len() - 1, consumed, format!("({})", bits.join(" | "))))
        });
        match parsed {
            Some((from, to, replacement)) => {
                out.push_str(&rest[..from]);
                out.push_str(&replacement);
                rest = &rest[to..];
            }
            None => {
                out.push_str(&rest[..at + 1]);
                rest = &rest[at + 1..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// An inlined function's delayed copies (`__Vinline__f___Vdly__x`) named as 5.006 names
/// them (`__Vdly__x`), in each function where that names no two alike.
fn inlined_delays(code: &str) -> String {
    let mut out = code.to_string();
    for (_, body) in functions(code) {
        let mut names: Vec<(String, String)> = Vec::new();
        let toks = match tokens(body) {
            Ok(t) => t,
            Err(_) => continue,
        };
        for t in toks {
            if let Tok::Id(id) = t {
                if let Some(i) = id.find("___Vdly__").filter(|_| id.starts_with("__Vinline__")) {
                    let short = format!("__Vdly__{}", &id[i + "___Vdly__".len()..]);
                    if !names.iter().any(|(l, _)| l == id) {
                        names.push((id.to_string(), short));
                    }
                }
            }
        }
        let mut shorts: Vec<&String> = names.iter().map(|(_, s)| s).collect();
        shorts.sort();
        let unique = shorts.windows(2).all(|w| w[0] != w[1]) && !names.iter().any(|(_, s)| body.contains(s.as_str()));
        if names.is_empty() || !unique {
            continue;
        }
        let mut renamed = body.to_string();
        // Longest first, so that no name is a prefix of one renamed after it.
        names.sort_by_key(|(l, _)| std::cmp::Reverse(l.len()));
        for (long, short) in &names {
            renamed = renamed.replace(long.as_str(), short);
        }
        out = out.replacen(body, &renamed, 1);
    }
    out
}

/// `___eval` as 5.006 writes it (the regions called in order), when the later scheduler's
/// loop calls only its phases and each phase only its region's functions.
fn scheduler(code: &mut [String]) {
    let all: Vec<String> = code.iter().flat_map(|c| functions(c).into_iter().map(|(n, _)| n.to_string())).collect();
    let body_of = |name: &str| {
        code.iter().find_map(|c| functions(c).into_iter().find(|(n, _)| *n == name).map(|(_, b)| b.to_string()))
    };
    let Some(eval) = body_of("Vboard___024root___eval") else { return };
    let calls = |body: &str| -> Option<Vec<String>> {
        let toks = tokens(body).ok()?;
        Some(
            toks.windows(2)
                .filter_map(|w| match w {
                    [Tok::Id(f), Tok::P("(")] if f.starts_with("Vboard___024root___") => Some(f.to_string()),
                    _ => None,
                })
                .collect(),
        )
    };
    let Some(phases) = calls(&eval) else { return };
    if phases.is_empty() || !phases.iter().all(|p| p.starts_with("Vboard___024root___eval_phase__")) {
        return;
    }
    for p in &phases {
        let region = p.trim_start_matches("Vboard___024root___eval_phase__");
        let Some(helpers) = body_of(p).and_then(|b| calls(&b)) else { return };
        let allowed = |f: &str| {
            let f = f.trim_start_matches("Vboard___024root___");
            f == format!("eval_triggers__{region}")
                || f == format!("eval_{region}")
                || f.starts_with("trigger_anySet__")
                || f.starts_with("trigger_orInto__")
                || f.starts_with("trigger_clear__")
        };
        if !helpers.iter().all(|f| allowed(f)) {
            return;
        }
    }
    let mut body = String::from("    // The regions, as Verilator 5.006 calls them (src/fastforward/dialect.rs).\n");
    for region in ["ico", "act", "nba"] {
        for f in [format!("Vboard___024root___eval_triggers__{region}"), format!("Vboard___024root___eval_{region}")] {
            if all.contains(&f) {
                body.push_str(&format!("    {f}(vlSelf);\n"));
            }
        }
    }
    for c in code.iter_mut() {
        if let Some((_, old)) = functions(c).into_iter().find(|(n, _)| *n == "Vboard___024root___eval") {
            let old = old.to_string();
            *c = c.replacen(&old, body.trim_end_matches('\n'), 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::fastforward::checks::Checked;
    use std::path::Path;

    fn checked(version: &str) -> Checked {
        Checked::of(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src/fastforward/fixtures").join(version))
    }

    /// The same design from Verilator 5.006 and 5.048: the same verdicts, the same observed
    /// variables (the scheduler's own aside), the same counters, the same unshown count.
    #[test]
    fn a_later_verilators_output_reads_as_5006s() {
        let (old, new) = (checked("verilator_5006"), checked("verilator_5048"));
        let verdicts = |c: &Checked| {
            (c.verdicts.fast_forward.clone(), c.verdicts.falling_edges.clone(), c.verdicts.observed.clone())
        };
        assert_eq!(verdicts(&old), (None, None, None));
        assert_eq!(verdicts(&new), verdicts(&old));
        let observed = |c: &Checked| -> Vec<(String, bool)> {
            let mut v: Vec<(String, bool)> = c
                .members
                .as_ref()
                .unwrap()
                .iter()
                .filter(|m| !m.name.starts_with("__V"))
                .map(|m| (m.name.clone(), m.observed))
                .collect();
            v.sort();
            v
        };
        assert_eq!(observed(&new), observed(&old));
        // What a run observes, and what it does not (a counter nothing reads).
        assert!(observed(&old).contains(&("board__DOT__refresh".to_string(), true)), "{:?}", observed(&old));
        assert!(observed(&old).contains(&("board__DOT__hidden".to_string(), false)), "{:?}", observed(&old));
        let counters = |c: &Checked| -> Vec<(String, u32, u64)> {
            c.counters.iter().map(|k| (k.name.clone(), k.bits, k.step)).collect()
        };
        assert_eq!(counters(&old), vec![("board__DOT__refresh".to_string(), 18, 1)]);
        assert_eq!(counters(&new), counters(&old));
        assert_eq!(new.unshown.as_ref().map(Vec::len), old.unshown.as_ref().map(Vec::len));
        // The harness calls the version's own trigger function.
        assert_eq!(old.triggers_fn.as_deref(), Some("Vboard___024root___eval_triggers__act"));
        assert_eq!(new.triggers_fn.as_deref(), Some("Vboard___024root___eval_triggers_vec__act"));
    }
}
