//! What the board harness (harness.cpp) may rely on in a design, checked on Verilator's
//! generated C++ when the design is built; each verdict is kept beside the library.
//!
//! **The fast-forward** takes the bytes of Verilator's root object (with the KCPSM6 and bot
//! models, which the host compares) for the whole state of the board: two equal copies mean
//! the board repeats itself, and a copy put back is the board at that moment. That holds when
//! every flop is a plain variable of the root and an evaluation depends on nothing else. It
//! does not when the design
//! - reads the simulation time (`$time`), draws random numbers at run time (`$random`), or
//!   reads or writes files (its state, or what it does, lies outside the root);
//! - prints (`$display` in a clocked block: a skipped period would not print);
//! - calls DPI functions of its own (their state is the user's C code);
//! - has variables that are not plain data (strings, queues, class objects, a `--timing`
//!   scheduler: the bytes of a `std::string` are a pointer);
//! - has modules Verilator did not inline (their state lives in other objects).
//!
//! [`Verdicts::fast_forward`] names the first such thing found, so the fast-forward stays off
//! for that design and the run says why.
//!
//! **One evaluation per clock edge that matters**: on a board whose logic all runs on rising
//! clock edges, a moment at which clocks only fall changes nothing but their levels. The
//! harness then evaluates at rising edges only and, at the other moments, lets Verilator
//! note the levels (its trigger function) without evaluating the design.
//! [`Verdicts::falling_edges`] says why a design needs its falling edges evaluated: a trigger
//! that is neither a rising edge nor any change of a variable the logic assigns (`negedge`, a
//! level or `@*` on a clock or an input), logic that computes from a generated clock's level
//! what a trigger or a record reads (an inverted or gated clock: `board::observed`'s
//! dependency graph), or logic that reads the
//! board clock's level.
//!
//! ```
//! let header = "class Vboard___024root final : public VerilatedModule {\n  public:\n    CData/*0:0*/ x;\n    std::string name;\n};\n";
//! let why = botsim::fastforward::checks::root_blocker(header);
//! assert!(why.unwrap().contains("std::string name"));
//! ```

use std::path::Path;

use super::counters::Counter;
use super::cpp::{function, functions, squeeze, strip_comments};
use super::observed::{Analysis, Member, Unshown};

/// What a build may assume, kept in its folder: for each, why not (`None`: it may).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Verdicts {
    pub fast_forward: Option<String>,
    pub falling_edges: Option<String>,
    /// Why the variables a run observes are not known (super::observed): the fast-forward
    /// then compares the whole state, which a board with a second clock never repeats.
    pub observed: Option<String>,
}

/// The files of a build folder that keep the verdicts (empty: none against).
const FAST_FORWARD_FILE: &str = "fast-forward.txt";
const FALLING_EDGES_FILE: &str = "falling-edges.txt";
const OBSERVED_FILE: &str = "observed.txt";
/// The waveform's signals a run that keeps only what it records cannot show: a line
/// `code width` each, or a line `? why` when that is not known.
const UNSHOWN_FILE: &str = "unshown.txt";

/// Keep the waveform's unshown signals in the build folder `dir`.
pub fn save_unshown(dir: &Path, unshown: &Result<Vec<Unshown>, String>) -> std::io::Result<()> {
    let text = match unshown {
        Ok(list) => list.iter().map(|u| format!("{} {}\n", u.code, u.width)).collect(),
        Err(why) => format!("? {}\n", why.replace('\n', " ")),
    };
    std::fs::write(dir.join(UNSHOWN_FILE), text)
}

/// The waveform's unshown signals kept in the build folder `dir`, or why they are not known.
pub fn load_unshown(dir: &Path) -> Result<Vec<Unshown>, String> {
    let text = std::fs::read_to_string(dir.join(UNSHOWN_FILE))
        .map_err(|_| format!("{UNSHOWN_FILE} is missing from the build folder {}", dir.display()))?;
    if let Some(why) = text.strip_prefix("? ") {
        return Err(why.trim().to_string());
    }
    text.lines()
        .map(|l| {
            let mut f = l.split(' ').map(str::parse::<u32>);
            match (f.next(), f.next()) {
                (Some(Ok(code)), Some(Ok(width))) => Ok(Unshown { code, width }),
                _ => Err(format!("{UNSHOWN_FILE} in {} has a line `{l}`", dir.display())),
            }
        })
        .collect()
}

/// Everything the build learns from Verilator's output: the verdicts, the root's variables
/// with whether a run observes each, and the waveform's signals a run that keeps only what it
/// records cannot show (or why either is not known).
pub struct Checked {
    pub verdicts: Verdicts,
    pub members: Result<Vec<Member>, String>,
    pub unshown: Result<Vec<Unshown>, String>,
    /// The counters the fast-forward moves on by arithmetic (super::counters).
    pub counters: Vec<Counter>,
    /// The KCPSM6 models whose out_port the design reads only under a write strobe
    /// (super::strobes).
    pub out_port_free: Vec<String>,
    /// The KCPSM6 models that may run apart from the board, and their followers
    /// (super::apart).
    pub apart: Vec<super::apart::Apart>,
    /// The generated function that computes the active triggers alone (its name differs
    /// between Verilator versions), for the harness's rising-edges-only evaluation.
    pub triggers_fn: Option<String>,
}

impl Checked {
    /// The checks on Verilator's output folder `obj`.
    pub fn of(obj: &Path) -> Checked {
        match Generated::read(obj) {
            Some(g) => {
                let code: Vec<&str> = g.eval.iter().chain(&g.slow).map(String::as_str).collect();
                let analysis = Analysis::of(&g.root, &code);
                let members = analysis.as_ref().map(Analysis::members).map_err(String::clone);
                // Logic that computes from a clock's level what a trigger or a record reads (an
                // inverted or gated clock): not known when the analysis is not.
                let level = match &analysis {
                    Ok(a) => a.clock_level_feeds(&g.syms).map(|v| {
                        format!("the design computes `{v}` from a clock's level (an inverted or gated clock?)")
                    }),
                    Err(why) => Some(format!("what the design computes from its clocks' levels is not known: {why}")),
                };
                let falling_edges = falling_edge_blocker(&g).or(level);
                let trace: Vec<&str> = g.trace.iter().map(String::as_str).collect();
                let counters = analysis.as_ref().map_or(Vec::new(), |a| a.counters(&g.root, &code, &g.syms));
                let unshown = analysis.and_then(|a| a.unshown(&g.root, &trace, &g.syms));
                let verdicts = Verdicts {
                    fast_forward: fast_forward_blocker(&g),
                    falling_edges,
                    observed: members.as_ref().err().cloned(),
                };
                let triggers_fn = g.triggers_fn.clone();
                let eval: Vec<&str> = g.eval.iter().map(String::as_str).collect();
                let out_port_free = super::strobes::out_port_free(&g.root, &eval);
                let apart = super::apart::cores_apart(&g.root, &eval);
                Checked { verdicts, members, unshown, counters, out_port_free, apart, triggers_fn }
            }
            None => {
                let why = "Verilator's output could not be read".to_string();
                let verdicts = Verdicts {
                    fast_forward: Some(why.clone()),
                    falling_edges: Some(why.clone()),
                    observed: Some(why.clone()),
                };
                Checked {
                    verdicts,
                    members: Err(why.clone()),
                    unshown: Err(why),
                    counters: Vec::new(),
                    out_port_free: Vec::new(),
                    apart: Vec::new(),
                    triggers_fn: None,
                }
            }
        }
    }
}

impl Verdicts {
    /// Keep them in the build folder `dir`.
    pub fn save(&self, dir: &Path) -> std::io::Result<()> {
        std::fs::write(dir.join(FAST_FORWARD_FILE), self.fast_forward.as_deref().unwrap_or(""))?;
        std::fs::write(dir.join(FALLING_EDGES_FILE), self.falling_edges.as_deref().unwrap_or(""))?;
        std::fs::write(dir.join(OBSERVED_FILE), self.observed.as_deref().unwrap_or(""))
    }

    /// The verdicts kept in the build folder `dir` (a missing file says no).
    pub fn load(dir: &Path) -> Verdicts {
        let read = |name: &str| match std::fs::read_to_string(dir.join(name)) {
            Ok(t) if t.trim().is_empty() => None,
            Ok(t) => Some(t.trim().to_string()),
            Err(_) => Some(format!("{name} is missing from the build folder {}", dir.display())),
        };
        Verdicts {
            fast_forward: read(FAST_FORWARD_FILE),
            falling_edges: read(FALLING_EDGES_FILE),
            observed: read(OBSERVED_FILE),
        }
    }
}

/// What the checks read of Verilator's output folder (`--Mdir`), read once.
struct Generated {
    /// Every file name, sorted.
    names: Vec<String>,
    root: String,
    dpi: String,
    /// The evaluation's source files but the `__Slow` ones, in name order.
    eval: Vec<String>,
    /// The `__Slow` ones (the initial blocks, the settling, the constructor).
    slow: Vec<String>,
    /// The waveform's functions (`Vboard__Trace__*`).
    trace: Vec<String>,
    /// The symbol table's source (the public variables).
    syms: String,
    /// The function that computes the active triggers alone, by its real name.
    triggers_fn: Option<String>,
}

impl Generated {
    fn read(obj: &Path) -> Option<Generated> {
        let mut names: Vec<String> =
            std::fs::read_dir(obj).ok()?.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect();
        names.sort();
        let read = |n: &str| std::fs::read_to_string(obj.join(n)).unwrap_or_default();
        // The root's code: `Vboard___024root__DepSet_<hash>__0.cpp` (5.006), or
        // `Vboard___024root__0.cpp` (later), each with its `__Slow` part.
        let root_code = |n: &&String| {
            n.strip_prefix("Vboard___024root__")
                .is_some_and(|r| r.starts_with("DepSet_") || r.starts_with(|c: char| c.is_ascii_digit()))
                && n.ends_with(".cpp")
        };
        let eval: Vec<String> =
            names.iter().filter(root_code).filter(|n| !n.ends_with("__Slow.cpp")).map(|n| read(n)).collect();
        let slow: Vec<String> =
            names.iter().filter(root_code).filter(|n| n.ends_with("__Slow.cpp")).map(|n| read(n)).collect();
        let trace: Vec<String> = names.iter().filter(|n| n.starts_with("Vboard__Trace__")).map(|n| read(n)).collect();
        let triggers_fn = ["Vboard___024root___eval_triggers__act", "Vboard___024root___eval_triggers_vec__act"]
            .into_iter()
            .find(|f| eval.iter().any(|c| function(c, f).is_some()))
            .map(str::to_string);
        // In the dialect the analyses read (a later Verilator's output rewritten).
        let (eval_n, slow_n) = (eval.len(), slow.len());
        let all: Vec<String> = eval.into_iter().chain(slow).chain(trace).collect();
        let (root, mut all) = super::dialect::to_5006(&read("Vboard___024root.h"), &all);
        let trace = all.split_off(eval_n + slow_n);
        let slow = all.split_off(eval_n);
        let syms = ["Vboard__Syms.cpp", "Vboard__Syms__Slow.cpp"].map(read).concat();
        Some(Generated { root, dpi: read("Vboard__Dpi.h"), syms, eval: all, slow, trace, names, triggers_fn })
    }
}

/// Why the fast-forward cannot take the root object for the design's whole state, or `None`
/// when it can.
fn fast_forward_blocker(g: &Generated) -> Option<String> {
    if let Some(n) =
        g.names.iter().find(|n| n.ends_with(".h") && n.starts_with("Vboard_") && !KNOWN_HEADERS.contains(&n.as_str()))
    {
        return Some(format!(
            "Verilator kept a module apart (`{}`) instead of inlining it",
            n.trim_start_matches("Vboard_").trim_end_matches(".h").trim_start_matches('_')
        ));
    }
    root_blocker(&g.root).or_else(|| dpi_blocker(&g.dpi)).or_else(|| g.eval.iter().find_map(|code| eval_blocker(code)))
}

/// Why the harness must evaluate the design's falling clock edges, or `None` when the rising
/// ones are enough.
fn falling_edge_blocker(g: &Generated) -> Option<String> {
    edge_blocker(&g.root, &g.eval.iter().map(String::as_str).collect::<Vec<_>>())
}

/// The falling-edge check on the root's header and the evaluation's files.
fn edge_blocker(root: &str, code: &[&str]) -> Option<String> {
    // Every trigger a rising edge of a variable (the board clock, a generated clock, a
    // clock made by the design's logic, which cannot change while nothing is evaluated).
    let Some(n) = trigger_count(root) else {
        return Some("Verilator's triggers were not found".into());
    };
    let triggers =
        squeeze(code.iter().find_map(|c| function(c, "Vboard___024root___eval_triggers__act")).unwrap_or(""));
    for i in 0..n {
        if logic_change_trigger(&triggers, i, code) {
            continue;
        }
        let at = format!("vlSelf->__VactTriggered.at({i}U)=((IData)(vlSelf->");
        let Some(start) = triggers.find(&at) else {
            return Some(format!("the design's trigger {i} is not a rising clock edge"));
        };
        let rest = &triggers[start + at.len()..];
        let var = rest.split(')').next().unwrap_or("");
        // (The previous level's name: `__Vtrigrprev__TOP__clk` in 5.006, later
        // `__Vtrigprevexpr___TOP__clk__0`.)
        let rising = |prev: String| rest.starts_with(&format!("{var})&(~(IData)(vlSelf->{prev})));"));
        if var.is_empty()
            || !(rising(format!("__Vtrigrprev__TOP__{var}")) || rising(format!("__Vtrigprevexpr___TOP__{var}__0")))
        {
            return Some(format!("the design's trigger {i} is not a rising clock edge"));
        }
    }
    // Nothing else reads the board clock's level (the debug build's assertion on it aside).
    for c in code {
        for (name, body) in functions(c) {
            if name.ends_with("___eval_triggers__act") || name.ends_with("___eval_debug_assertions") {
                continue;
            }
            if reads_clk(body) {
                return Some("the design reads the board clock's level in its logic".into());
            }
        }
    }
    None
}

/// Trigger `i` (in the squeezed trigger function `triggers`) fires on any change of a variable
/// the design's logic assigns (`always @(instruction)`, the debug build's instruction text):
/// such a variable changes only while the design is evaluated, never at a moment when clocks
/// only fall. (The harness writes the inputs and the generated clocks' levels, which the
/// logic never assigns.)
fn logic_change_trigger(triggers: &str, i: usize, code: &[&str]) -> bool {
    let at = format!("vlSelf->__VactTriggered.at({i}U)=(vlSelf->");
    let Some(start) = triggers.find(&at) else { return false };
    let rest = &triggers[start + at.len()..];
    let var = rest.split("!=").next().unwrap_or("");
    let valid = !var.is_empty() && var.chars().all(|c| c.is_alphanumeric() || c == '_');
    let assigned = format!("vlSelf->{var}=");
    valid
        && (rest.starts_with(&format!("{var}!=vlSelf->__Vtrigrprev__TOP__{var});"))
            || rest.starts_with(&format!("{var}!=vlSelf->__Vtrigprevexpr___TOP__{var}__0);")))
        && code.iter().any(|c| {
            let c = squeeze(c);
            c.match_indices(&assigned).any(|(k, m)| !c[k + m.len()..].starts_with('='))
        })
}

/// How many triggers the root has (`VlTriggerVec<N> __VactTriggered;`).
fn trigger_count(root: &str) -> Option<usize> {
    let at = root.find("> __VactTriggered;")?;
    let open = root[..at].rfind('<')?;
    root[open + 1..at].trim().parse().ok()
}

/// The body names the top's `clk` (not merely a name that begins so).
fn reads_clk(body: &str) -> bool {
    body.match_indices("vlSelf->clk")
        .any(|(i, m)| body[i + m.len()..].chars().next().map_or(true, |c| !(c.is_alphanumeric() || c == '_')))
}

/// Headers every build has: the model, its symbol table, its DPI imports, the root.
const KNOWN_HEADERS: &[&str] = &["Vboard__Syms.h", "Vboard__Dpi.h", "Vboard___024root.h", "Vboard__pch.h"];

/// Plain member types of the root: Verilator's integer and wide types, unpacked arrays of
/// them, trigger vectors, the ports, and the symbol table's pointer.
const PLAIN: &[&str] = &[
    "CData",
    "SData",
    "IData",
    "QData",
    "EData",
    "VlWide<",
    "VlUnpacked<",
    "VlTriggerVec<",
    "VL_IN",
    "VL_OUT",
    "Vboard__Syms* const vlSymsp;",
    // Later Verilators: the same pointer, and the instance's name (a constant).
    "Vboard__Syms* vlSymsp;",
    "const char* vlNamep;",
];

/// The root's header: a member that is not plain data, or `None`.
pub fn root_blocker(header: &str) -> Option<String> {
    let Some(start) = header.find("class Vboard___024root") else {
        return Some("Verilator's root class was not found".into());
    };
    for line in header[start..].lines().skip(1) {
        let code = strip_comments(line);
        let code = code.trim();
        if code.starts_with("} VL_ATTR_ALIGNED") || code == "};" && line.starts_with('}') {
            break;
        }
        // Members end with `;`; skip access labels, nested struct braces and functions.
        let function = code.contains('(') && !code.starts_with("VL_IN") && !code.starts_with("VL_OUT");
        if !code.ends_with(';') || code == "};" || function {
            continue;
        }
        let plain = PLAIN.iter().any(|p| code.starts_with(p)) && !code.contains("std::") && only_plain_vl_types(code);
        if !plain {
            return Some(format!("the design has a variable that is not plain data (`{code}`)"));
        }
    }
    None
}

/// Every `Vl...` type named on the line is one of the plain ones.
fn only_plain_vl_types(code: &str) -> bool {
    code.match_indices("Vl").all(|(i, _)| {
        let rest = &code[i..];
        let before = code[..i].chars().next_back();
        before.is_some_and(|c| c.is_alphanumeric() || c == '_')
            || ["VlWide<", "VlUnpacked<", "VlTriggerVec<"].iter().any(|p| rest.starts_with(p))
    })
}

/// DPI imports and exports: only botsim's own (the KCPSM6 and bot models, the disassembler).
fn dpi_blocker(header: &str) -> Option<String> {
    let mut at = "";
    for line in header.lines().map(str::trim) {
        if let Some(place) = line.strip_prefix("// DPI import at ").or_else(|| line.strip_prefix("// DPI export at ")) {
            at = place;
        }
        let Some(decl) = line.strip_prefix("extern ").filter(|d| !d.starts_with('"')) else { continue };
        let name = decl.split('(').next().unwrap_or("").split_whitespace().last().unwrap_or("");
        let name = name.trim_start_matches('*');
        if !name.starts_with("botsim_") {
            let place = if at.is_empty() { String::new() } else { format!(", {at}") };
            return Some(format!("the design calls a DPI function of its own (`{name}`{place})"));
        }
    }
    None
}

/// What the evaluation may not do, by the name of Verilator's runtime call, and what it is in
/// the user's terms.
const EVAL_CALLS: &[(&str, &str)] = &[
    ("VL_TIME", "reads the simulation time ($time, $realtime)"),
    ("->time()", "reads the simulation time ($time, $realtime)"),
    ("VL_RANDOM", "draws random numbers while it runs ($random)"),
    ("VL_URANDOM", "draws random numbers while it runs ($urandom)"),
    ("VL_RAND_RESET", "draws random numbers while it runs"),
    ("VL_WRITEF", "prints while it runs ($display, $write, $strobe, $monitor)"),
    ("VL_FWRITEF", "writes a file while it runs ($fdisplay, $fwrite)"),
    ("VL_FOPEN", "opens files while it runs ($fopen)"),
    ("VL_FCLOSE", "closes files while it runs ($fclose)"),
    ("VL_FREAD", "reads files while it runs ($fread)"),
    ("VL_FGET", "reads files while it runs ($fgetc, $fgets)"),
    ("VL_FSCANF", "reads files while it runs ($fscanf)"),
    ("VL_FFLUSH", "writes a file while it runs ($fflush)"),
    ("VL_READMEM", "loads memories while it runs ($readmemh)"),
    ("VL_WRITEMEM", "writes memories to files while it runs ($writememh)"),
    ("VL_SYSTEM", "runs commands while it runs ($system)"),
];

/// One file of the evaluation: the first call the fast-forward cannot repeat, or `None`.
fn eval_blocker(code: &str) -> Option<String> {
    EVAL_CALLS.iter().find(|(call, _)| code.contains(call)).map(|(_, what)| format!("the design {what}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROOT: &str = include_str!("fixtures/checks_root.h");

    #[test]
    fn a_root_of_plain_variables_passes() {
        assert_eq!(root_blocker(ROOT), None);
    }

    #[test]
    fn strings_queues_and_schedulers_are_not_plain() {
        for member in [
            "std::string name;",
            "VlQueue<CData> q;",
            "VlUnpacked<std::string, 2> names;",
            "VlDelayScheduler __VdlySched;",
            "VlClassRef<Vboard_c> obj;",
        ] {
            let h = ROOT.replace("QData/*63:0*/ cpu;", member);
            let why = root_blocker(&h).unwrap_or_else(|| panic!("{member} passed"));
            assert!(why.contains(member), "{why}");
        }
    }

    #[test]
    fn only_botsims_dpi_functions_pass() {
        let ours = include_str!("fixtures/checks_dpi.h");
        assert_eq!(dpi_blocker(ours), None);
        let theirs = format!("{ours}    // DPI import at uart.v:3:5\n    extern int uart_poll(int port);\n");
        assert_eq!(
            dpi_blocker(&theirs).as_deref(),
            Some("the design calls a DPI function of its own (`uart_poll`, uart.v:3:5)")
        );
    }

    #[test]
    fn one_rising_edge_trigger_lets_falling_edges_go() {
        let root = "    VlTriggerVec<1> __VactTriggered;\n";
        let triggers = include_str!("fixtures/checks_triggers.cpp");
        let nba = "VL_INLINE_OPT void Vboard___024root___nba_sequent__TOP__0(Vboard___024root* vlSelf) {\n    vlSelf->x = (1U + vlSelf->x);\n}\n";
        let assertions = "void Vboard___024root___eval_debug_assertions(Vboard___024root* vlSelf) {\n    if (VL_UNLIKELY((vlSelf->clk & 0xfeU))) {\n        Verilated::overWidthError(\"clk\");}\n}\n";
        assert_eq!(edge_blocker(root, &[triggers, nba, assertions]), None);
        // A second clock's rising edge (a Clocking Wizard's output) too.
        let two = "    VlTriggerVec<2> __VactTriggered;\n";
        let q = "botsim_board__DOT__user__DOT__CLKGEN__DOT__q";
        let second = format!("    vlSelf->__VactTriggered.at(1U) = ((IData)(vlSelf->{q}) \n        & (~ (IData)(vlSelf->__Vtrigrprev__TOP__{q})));\n}}\n");
        let both = triggers.replacen("    vlSelf->__Vtrigrprev__TOP__clk = vlSelf->clk;\n}\n", &second, 1);
        assert_eq!(edge_blocker(two, &[&both, nba]), None);
        // A trigger missing, or a falling edge.
        assert!(edge_blocker(two, &[triggers, nba]).unwrap().contains("trigger 1 is not a rising clock edge"));
        let falling = triggers.replace("((IData)(vlSelf->clk) \n", "(~(IData)(vlSelf->clk) \n");
        assert!(edge_blocker(root, &[&falling, nba]).unwrap().contains("trigger 0 is not a rising clock edge"));
        // Any change of a variable the logic assigns (`always @(instruction)`), but not of
        // one only the harness writes (an input).
        let change = |var: &str| {
            both.replacen(
                &format!("((IData)(vlSelf->{q}) \n        & (~ (IData)(vlSelf->__Vtrigrprev__TOP__{q})))"),
                &format!("(vlSelf->{var} \n        != vlSelf->__Vtrigrprev__TOP__{var})"),
                1,
            )
        };
        assert_eq!(edge_blocker(two, &[&change("x"), nba]), None);
        assert!(edge_blocker(two, &[&change("btn"), nba]).unwrap().contains("trigger 1 is not a rising clock edge"));
        // Logic that reads the level (`assign led = {15'd0, clk}`).
        let level = "void Vboard___024root___ico_sequent__TOP__0(Vboard___024root* vlSelf) {\n    vlSelf->led = (IData)(vlSelf->clk);\n}\n";
        assert!(edge_blocker(root, &[triggers, nba, level]).unwrap().contains("level"));
    }

    #[test]
    fn time_random_prints_and_files_in_the_evaluation_block() {
        assert_eq!(eval_blocker("vlSelf->x = (1U + vlSelf->x);\n"), None);
        let why = eval_blocker("if ((0x64ULL < VL_TIME_UNITED_Q(1000))) {").unwrap();
        assert!(why.contains("$time"), "{why}");
        assert!(eval_blocker("vlSelf->led = VL_RANDOM_I();").unwrap().contains("$random"));
        assert!(eval_blocker("VL_WRITEF(\"hi %3#\\n\",8,vlSelf->x);").unwrap().contains("$display"));
    }
}
