//! Everything before the board runs: the arguments checked (each bad one is one line
//! before anything is built), the repository resolved into a design and a plan (each
//! decision said), the design built.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use botsim::board::build::{build, BotKind, Built, CpuModel};
use botsim::board::iss::{Host, TraceRequest};
use botsim::files::check_writable;
use botsim::firmware::{SOURCE, SOURCE_PATH};
use botsim::kcpsm6::loader;
use botsim::kcpsm6::source::SourceMap;
use botsim::{Firmware, World, PS_PER_CYCLE};
use botsim_core::board::random_stimulus::{merge, random_stimulus};
use botsim_core::board::stimulus::{parse_press, parse_tilt, parse_time, Stimulus};
use botsim_core::debug::{BreakSpec, Breaks};
use botsim_core::frontend::ip::ClockSpec;
use botsim_core::frontend::pins::{peripherals, Peripheral, Role};
use botsim_core::frontend::plan::{Plan, Request};
use botsim_core::frontend::resolve::{resolve, Design, Options};

use super::breaks::{breakpoints, parse_mark, Mark};
use super::{Args, BotArg, CpuArg, LONG_RUN_S};
use crate::cli::size::parse_size;

/// A design ready to run, with what the arguments asked for.
pub struct Prepared {
    /// The inputs over time (--stimulus, --press, --switches).
    pub stimulus: Stimulus,
    /// Where a waveform opens and closes.
    pub vcd_from: Mark,
    pub vcd_to: Option<Mark>,
    pub world: World,
    pub fw: Firmware,
    /// The design as the repository gave it (where its variables are declared).
    pub design: Design,
    pub plan: Plan,
    /// Each CPU's program source, by instance path, where it is known.
    pub maps: BTreeMap<String, SourceMap>,
    pub cpu_breaks: BTreeMap<String, Breaks>,
    pub bot_breaks: Vec<BreakSpec>,
    /// What runs the KCPSM6s and the bot of the board that is run (with --cpu lockstep, the
    /// RTL board; `bot` is then the ISS board's).
    pub cpu: CpuModel,
    pub main_bot: BotKind,
    pub bot: BotKind,
    pub lockstep: bool,
    /// --cpu-trace's folder and window.
    cpu_trace: Option<PathBuf>,
    trace_window: (u64, u64),
    pub built: Built,
    /// The lock-step's ISS board.
    pub twin: Option<Built>,
}

impl Prepared {
    /// A host of the models for a board of `cpu` and `bot` (each board needs its own).
    pub fn host(&self, cpu: CpuModel, bot: BotKind) -> Result<Option<Box<Host>>, String> {
        let plan = &self.plan;
        let mut h = match cpu {
            // The RTL board's host only writes debug text.
            CpuModel::Rtl => Host::new(Vec::new(), false),
            _ => {
                let mut h = Host::for_plan(plan, self.lockstep).map_err(|e| e.to_string())?;
                if let (Some(dir), CpuModel::Iss) = (&self.cpu_trace, cpu) {
                    h.trace(TraceRequest { dir: dir.clone(), window: self.trace_window, sources: self.maps.clone() });
                }
                if cpu == CpuModel::Iss {
                    h.break_at(self.cpu_breaks.clone());
                }
                h
            }
        };
        // The bot's firmware: the plan always has a bot_pgm (the user's, or botsim's).
        if let (BotKind::Model, Some(r)) = (bot, plan.roms.iter().find(|r| r.module == "bot_pgm")) {
            h.model_bot(r.image.clone(), self.world.clone());
        }
        Ok(Some(h))
    }

    /// The main board's host.
    pub fn main_host(&self) -> Result<Option<Box<Host>>, String> {
        self.host(self.cpu, self.main_bot)
    }
}

/// Every option and stimulus about a peripheral the design does not reach is one line.
fn peripheral_options(a: &Args, s: &Stimulus, plan: &Plan) -> Result<(), String> {
    let has = |r: Role| plan.pins.iter().any(|(_, x)| *x == r);
    let acl = plan.pins.iter().any(|(_, r)| r.peripheral() == Some(Peripheral::Accelerometer));
    let lacks = |what: &str, pins: &str| format!("{what}, and the design has no {pins}");
    if a.uart.is_some() && !has(Role::UartTx) {
        return Err(lacks("--uart writes what the design sends on the USB-UART", "RsTx (UART_RXD_OUT) pin"));
    }
    if a.audio.is_some() && !has(Role::AudioPwm) {
        return Err(lacks("--audio writes the board's sound", "ampPWM (AUD_PWM) pin"));
    }
    if !s.uart.is_empty() && !has(Role::UartRx) {
        return Err(lacks("the stimulus sends text to the USB-UART", "RsRx (UART_TXD_IN) pin"));
    }
    let keyboard = has(Role::Ps2Clock) && has(Role::Ps2Data);
    if !s.keys.is_empty() && !keyboard {
        return Err(lacks("the stimulus types on the keyboard", "PS2_CLK and PS2_DATA pins"));
    }
    if (!s.tilts.is_empty() || a.tilt.is_some()) && !acl {
        return Err(lacks("the board's tilt is measured by its accelerometer", "aclSCK/aclMOSI/aclMISO/aclSS pins"));
    }
    Ok(())
}

/// `--random-stimulus SEED`: its events for the design's pins, within the run's time, added
/// to the stimulus and listed.
fn add_random_stimulus(a: &Args, seed: u64, plan: &Plan, inputs: &mut Inputs) {
    let roles: Vec<Role> = plan.pins.iter().map(|(_, r)| *r).collect();
    let span_ps = match (a.seconds, a.samples) {
        (Some(s), _) => (s * 1e12) as u64,
        // Half the budget of a wait for a sample is about one sample's interval.
        (None, Some(n)) => n.saturating_mul(inputs.fw.timing.update_budget() / 2).saturating_mul(PS_PER_CYCLE),
        (None, None) => 1_000_000_000_000,
    };
    let r = random_stimulus(seed, &roles, span_ps);
    let text = r.text(span_ps, "");
    let events: Vec<&str> = text.lines().skip(1).collect();
    a.say(format!("  random stimulus {seed}: {} events on the design's inputs:", events.len()));
    for l in events {
        a.say(format!("    {l}"));
    }
    merge(&mut inputs.stimulus, r);
}

/// Check the arguments, find the design, plan it and build it.
pub fn prepare(a: &Args) -> Result<Prepared, String> {
    let mut inputs = checked_arguments(a)?;
    let (design, plan) = find_design(a, &inputs)?;
    say_design(a, &design, &plan, &inputs.stimulus)?;
    if let Some(seed) = a.random_stimulus {
        add_random_stimulus(a, seed, &plan, &mut inputs);
    }
    let models = choose_models(a, &plan, &inputs.fw)?;
    let (built, twin) = build_boards(a, &plan, &inputs.params, &models)?;
    let Inputs { stimulus, vcd_from, vcd_to, world, fw, .. } = inputs;
    let Models { cpu, main_bot, bot, lockstep, maps, cpu_breaks, bot_breaks, trace_window } = models;
    Ok(Prepared {
        stimulus,
        vcd_from,
        vcd_to,
        world,
        fw,
        design,
        plan,
        maps,
        cpu_breaks,
        bot_breaks,
        cpu,
        main_bot,
        bot,
        lockstep,
        cpu_trace: a.cpu_trace.clone(),
        trace_window,
        built,
        twin,
    })
}

/// What the arguments give before any design is read.
struct Inputs {
    stimulus: Stimulus,
    vcd_from: Mark,
    vcd_to: Option<Mark>,
    params: Vec<(String, String)>,
    world: World,
    fw: Firmware,
    bot_firmware: botsim::kcpsm6::image::Image,
    programs: Vec<(PathBuf, botsim::kcpsm6::image::Image)>,
}

/// The arguments checked, each bad one one line before anything is built.
fn checked_arguments(a: &Args) -> Result<Inputs, String> {
    let mut stimulus = match &a.stimulus {
        Some(f) => {
            let text = std::fs::read_to_string(f).map_err(|e| format!("{}: error: cannot read: {e}", f.display()))?;
            Stimulus::parse(f, &text).map_err(|e| e.to_string())?
        }
        None => Stimulus::default(),
    };
    for p in &a.press {
        stimulus.presses.push(parse_press(p)?);
    }
    if let Some(h) = &a.switches {
        stimulus.initial_switches = u16::from_str_radix(h.trim_start_matches("0x"), 16)
            .map_err(|_| format!("--switches {h}: expected up to four hexadecimal digits"))?;
    }
    if let Some(t) = &a.tilt {
        stimulus.tilts.insert(0, (0, parse_tilt(t).map_err(|e| format!("--tilt {e}"))?));
    }
    if a.uart_baud.is_some_and(|b| !(50..=4_000_000).contains(&b)) {
        return Err("--uart-baud: expected a rate from 50 to 4000000 baud".into());
    }
    let vcd_from = a.trace_from.as_deref().map(|m| parse_mark(m, "trace-from")).transpose()?.unwrap_or(Mark::Time(0));
    let vcd_to = a.trace_to.as_deref().map(|m| parse_mark(m, "trace-to")).transpose()?;
    match (vcd_from, vcd_to) {
        (Mark::Sample(f), Some(Mark::Sample(t))) if t < f => return Err("--trace-to: before --trace-from".into()),
        (Mark::Time(f), Some(Mark::Time(t))) if t <= f => return Err("--trace-to: before --trace-from".into()),
        _ => {}
    }
    let params = a
        .param
        .iter()
        .map(|p| {
            p.split_once('=')
                .filter(|(n, v)| !n.is_empty() && !v.is_empty())
                .map(|(n, v)| (n.to_string(), v.to_string()))
                .ok_or_else(|| format!("--param {p}: expected NAME=VALUE"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(s) = a.seconds {
        if !s.is_finite() || s <= 0.0 {
            return Err(format!("--seconds {s}: expected a positive number of seconds of board time"));
        }
        if s > LONG_RUN_S && !a.long {
            return Err(format!(
                "--seconds {s}: more than {LONG_RUN_S} s of board time takes about as long to simulate, or longer; add --long to run it"
            ));
        }
    }
    if a.bench && (a.vcd.is_some() || a.cpu_trace.is_some() || !a.breaks.is_empty()) {
        return Err("--bench times a run as it is made: without --vcd, --cpu-trace or --break".into());
    }
    if let Some(max) = &a.vcd_max {
        parse_size(max).map_err(|e| format!("--vcd-max {max}: {e}"))?;
    }
    let world = match &a.map {
        Some(p) => World::load(p).map_err(|d| d.to_string())?,
        None => World::builtin(),
    };
    let fw = a.firmware.firmware();
    let bot_firmware = fw.assemble().map_err(|d| d.to_string())?;
    let mut programs = Vec::new();
    for p in &a.program {
        let img = loader::load(p, &botsim::kcpsm6::asm::Options::default()).map_err(|d| d.errors_text())?;
        programs.push((p.clone(), img));
    }
    for p in
        [&a.trace_csv, &a.trace_json, &a.png, &a.display, &a.pins, &a.vcd, &a.design_log, &a.uart, &a.audio, &a.lines]
            .into_iter()
            .flatten()
    {
        check_writable(p)?;
    }
    if let Some(d) = &a.frames {
        std::fs::create_dir_all(d).map_err(|e| format!("{}: error: cannot create the folder: {e}", d.display()))?;
        check_writable(&d.join("frame.png"))?;
    }
    Ok(Inputs { stimulus, vcd_from, vcd_to, params, world, fw, bot_firmware, programs })
}

/// The repository resolved into a design and planned; every `--param` names a parameter of
/// the top.
fn find_design(a: &Args, inputs: &Inputs) -> Result<(Design, Plan), String> {
    let params = &inputs.params;
    let clocks = a.clock.iter().map(|c| ClockSpec::parse(c)).collect::<Result<Vec<_>, _>>()?;
    let options = Options {
        top: a.top.clone(),
        prefer: a.prefer.clone(),
        exclude: a.exclude.clone(),
        clocks,
        stubs: a.stub.clone(),
        include_dirs: a.include.clone(),
        memories: a
            .memory
            .iter()
            .map(|m| {
                m.split_once('=')
                    .filter(|(n, f)| !n.is_empty() && !f.is_empty())
                    .map(|(n, f)| (n.to_string(), PathBuf::from(f)))
                    .ok_or_else(|| format!("--memory {m}: expected MODULE=FILE (for example --memory knitg=frt.coe)"))
            })
            .collect::<Result<Vec<_>, _>>()?,
    };
    let design = resolve(&a.sources, &options).map_err(|e| e.to_string())?;
    let req = Request {
        programs: inputs.programs.clone(),
        bot_firmware: inputs.bot_firmware.clone(),
        force_own_firmware: a.firmware.any(),
        first_bot: a.bot_at.clone(),
    };
    let mut plan = Plan::new(&design, &req).map_err(|e| e.to_string())?;
    plan.replaced.extend(design.generated.iter().cloned());
    // Every --param names a parameter of the top.
    if let Some((src, top)) = design.sources.iter().find_map(|s| s.module(&design.top).map(|m| (s, m))) {
        // A parameter declaration the scanner could not read (`parameter SIMULATE <= 0;`) is
        // the design's mistake, at its line: the build says it (Verilator's syntax error in
        // the user's terms), not this.
        let tokens: Vec<String> = botsim_core::frontend::scan::normalized(&src.text, top.span.clone())
            .split_whitespace()
            .map(str::to_string)
            .collect();
        let declared_unread = |name: &str| {
            tokens.split(|t| t == ";").any(|stmt| {
                stmt.iter().any(|t| t == "parameter" || t == "localparam") && stmt.iter().any(|t| t == name)
            })
        };
        if let Some((name, _)) = params.iter().find(|(n, _)| !top.params.contains(n) && !declared_unread(n)) {
            let has = if top.params.is_empty() { "none".to_string() } else { top.params.join(", ") };
            return Err(format!(
                "--param {name}: the top `{}` ({}:{}) has no parameter {name} (its parameters: {has})",
                top.name,
                src.path.display(),
                top.line
            ));
        }
    }
    Ok((design, plan))
}

/// Every decision about the design in a line of its own (the project, the bots, what botsim
/// replaced, the pins), and the options that cannot apply to it.
fn say_design(a: &Args, design: &Design, plan: &Plan, stimulus: &Stimulus) -> Result<(), String> {
    if let Some(p) = &design.project {
        a.say(format!("botsim board: the project {}", p.display()));
    }
    for n in &design.notes {
        a.say(format!("note: {n}"));
    }
    let bots = plan.bots();
    match bots.as_slice() {
        [] => {
            bot_options_without_bot(a)?;
            a.say(format!("botsim board: top `{}`, no bot (the board alone)", plan.top));
        }
        [one] => a.say(format!("botsim board: top `{}`, bot at `{}.{}`", plan.top, plan.top, one.path)),
        [first, rest @ ..] => {
            let rest: Vec<String> = rest.iter().map(|b| format!("`{}.{}`", plan.top, b.path)).collect();
            a.say(format!(
                "botsim board: top `{}`, {} bots: `{}.{}` (the one options about the bot mean; --bot-at names another), {}",
                plan.top,
                bots.len(),
                plan.top,
                first.path,
                rest.join(", ")
            ));
        }
    }
    let mut said = std::collections::BTreeSet::new();
    for (k, b) in bots.iter().enumerate() {
        let Some(t) = b.team.as_ref().filter(|t| said.insert(t.module.clone())) else { continue };
        let which = match &t.config {
            Some(port) => format!("a later BotSim than 2.0 (port `{port}`; BotSim 3.1)"),
            None => "the bot's ports around a KCPSM6".to_string(),
        };
        a.say(format!(
            "  the team's bot `{}` ({}) is {which}: simulated from its own RTL, with botsim's kcpsm6 and the world from the map",
            t.module, t.at
        ));
        if k == 0 && a.bot == Some(BotArg::Model) && !plan.has_own_bot() {
            return Err(format!(
                "--bot model: the design's bot is the team's `{}` ({}), simulated from its RTL; botsim's model is BotSim 2.0's",
                t.module, t.at
            ));
        }
    }
    for r in &plan.replaced {
        let from = if r.from.is_empty() { String::new() } else { format!(" ({})", r.from) };
        a.say(format!("  replaced {}{from} with {}", r.module, r.with));
    }
    for w in &plan.warnings {
        a.warn(w);
    }
    let reached = peripherals(&plan.pins);
    for (device, names) in &reached {
        a.say(format!("  the board's {}: {}", device.name(), names.join(", ")));
    }
    peripheral_options(a, stimulus, plan)?;
    if !plan.unknown_pins.is_empty() {
        a.say(format!("  ports with no board pin (inputs held low, outputs open): {}", plan.unknown_pins.join(", ")));
    }
    Ok(())
}

/// What runs the KCPSM6s and the bot, and what the run looks at inside them.
struct Models {
    cpu: CpuModel,
    main_bot: BotKind,
    bot: BotKind,
    lockstep: bool,
    maps: BTreeMap<String, SourceMap>,
    cpu_breaks: BTreeMap<String, Breaks>,
    bot_breaks: Vec<BreakSpec>,
    trace_window: (u64, u64),
}

fn choose_models(a: &Args, plan: &Plan, fw: &Firmware) -> Result<Models, String> {
    let trace_window = (
        a.cpu_trace_from
            .as_deref()
            .map(parse_time)
            .transpose()
            .map_err(|e| format!("--cpu-trace-from: {e}"))?
            .unwrap_or(0),
        a.cpu_trace_to
            .as_deref()
            .map(parse_time)
            .transpose()
            .map_err(|e| format!("--cpu-trace-to: {e}"))?
            .unwrap_or(u64::MAX),
    );
    if let Some(d) = &a.cpu_trace {
        std::fs::create_dir_all(d).map_err(|e| format!("{}: error: cannot create the folder: {e}", d.display()))?;
        check_writable(&d.join("cpu.trace.txt"))?;
    }
    let cpu_arg = a.cpu.unwrap_or(CpuArg::Iss);
    let cpu = match cpu_arg {
        // The trace comes from the ISS, which equals the RTL core at every port.
        CpuArg::Rtl if a.cpu_trace.is_some() || !a.breaks.is_empty() => {
            a.say("note: --cpu-trace and --break run the KCPSM6s on the ISS (--cpu iss: the same results, cycle for cycle)".into());
            CpuModel::Iss
        }
        CpuArg::Rtl => CpuModel::Rtl,
        CpuArg::Iss => CpuModel::Iss,
        CpuArg::Lockstep => CpuModel::RtlProbed,
    };
    // The source of each CPU's program: the .psm given with --program or found beside its
    // ROM (the plan knows), botsim's firmware; otherwise none (the trace shows disassembly).
    let sources = |plan: &Plan| -> BTreeMap<String, SourceMap> {
        let mut out = BTreeMap::new();
        for site in &plan.cpus {
            let Ok(rom) = &site.rom else { continue };
            let Some(r) = plan.roms.iter().find(|r| &r.module == rom) else { continue };
            let map = if let Some(p) = &r.source {
                match botsim::kcpsm6::asm::assemble_file(p, &Default::default()) {
                    Ok(prog) => SourceMap::of(&prog),
                    Err(_) => continue,
                }
            } else if rom == "bot_pgm" && r.origin.starts_with("botsim's firmware") {
                match fw.program(0) {
                    Ok(prog) => SourceMap::of_source(&prog, Path::new(SOURCE_PATH), SOURCE),
                    Err(_) => continue,
                }
            } else {
                continue;
            };
            out.insert(site.path.clone(), map);
        }
        out
    };
    let lockstep = cpu_arg == CpuArg::Lockstep;
    if lockstep && a.bench {
        return Err("--bench measures one board: --cpu rtl or iss".into());
    }
    // Assembled once: the breakpoints, the traces, the stop message and the save file use it.
    let maps = sources(plan);
    let (cpu_breaks, bot_breaks) = breakpoints(&a.breaks, plan, &maps)?;
    // The models' programs are known before anything is built.
    let looks_inside = a.cpu_trace.is_some() || !a.breaks.is_empty();
    let bot = match (a.bot, cpu_arg) {
        // Without a bot, nothing is built for one: the board's runs are as with a model.
        _ if !plan.has_own_bot() => BotKind::Model,
        (Some(BotArg::Model), _) => BotKind::Model,
        (None, CpuArg::Iss | CpuArg::Lockstep) if !looks_inside => BotKind::Model,
        _ => BotKind::Rtl,
    };
    // The lock-step's RTL board is all RTL; --bot applies to its ISS board.
    let main_bot = if lockstep { BotKind::Rtl } else { bot };
    // The models' hosts can be made (every KCPSM6 has its program) before anything is built.
    if cpu != CpuModel::Rtl {
        Host::for_plan(plan, lockstep).map_err(|e| e.to_string())?;
    }
    Ok(Models { cpu, main_bot, bot, lockstep, maps, cpu_breaks, bot_breaks, trace_window })
}

/// The board built (or found in the cache), and the lock-step's ISS board; what the build
/// found said.
fn build_boards(
    a: &Args,
    plan: &Plan,
    params: &[(String, String)],
    m: &Models,
) -> Result<(Built, Option<Built>), String> {
    let (cpu, main_bot, bot, lockstep) = (m.cpu, m.main_bot, m.bot, m.lockstep);
    let debug = a.vcd.is_some();
    let built = build(plan, params, cpu, main_bot, debug, a.quiet || a.json).map_err(|e| e.to_string())?;
    match built.seconds {
        Some(s) => {
            a.say(format!("  built in {s:.1} s with Verilator {} ({})", built.verilator, built.library.display()))
        }
        None => a.say(format!("  reused the build in {}", built.library.parent().unwrap_or(&built.library).display())),
    }
    if let Some(at) = &built.delays {
        a.say(format!(
            "note: {at}: the design has delays (#): botsim simulates them as written (Vivado's synthesis ignores them), evaluating every clock edge"
        ));
    }
    for w in &built.widths {
        a.warn(w);
    }
    for (code, n, first) in &built.warnings {
        match leniency(code) {
            Some(what) => {
                let at = first.split(": ").next().unwrap_or(first);
                let more = if *n > 1 { format!(" (and {} more)", n - 1) } else { String::new() };
                a.say(format!("note: {at}: {what}{more}"));
            }
            None => {
                // Another finding of Verilator's that does not stop the build: where, what
                // it says, and that the run goes on.
                let (at, what) = first.split_once(": ").unwrap_or(("", first));
                let more = if *n > 1 { format!("; {} places like it", n) } else { String::new() };
                let at = if at.is_empty() { String::new() } else { format!("{at}: ") };
                a.say(format!("note: {at}{what} (Verilator's {code} warning{more}; the run goes on)"));
            }
        }
    }

    let twin = if lockstep {
        let b = build(plan, params, CpuModel::Iss, bot, false, a.quiet || a.json).map_err(|e| e.to_string())?;
        match b.seconds {
            Some(s) => a.say(format!("  built the ISS board in {s:.1} s")),
            None => a.say("  reused the ISS board's build".into()),
        }
        Some(b)
    } else {
        None
    };
    Ok((built, twin))
}

/// The options that need a bot, on a design without one: the first is an error.
fn bot_options_without_bot(a: &Args) -> Result<(), String> {
    let in_samples =
        |m: &Option<String>| m.as_deref().is_some_and(|m| matches!(parse_mark(m, ""), Ok(Mark::Sample(_))));
    const BY_TIME: &str = ": use a time (2ms) or cycles (5000000c)";
    let given = [
        (a.samples.is_some(), "--samples counts the bot's samples", ": use --seconds"),
        (a.trace_csv.is_some(), "--trace-csv records the bot's samples", ""),
        (a.trace_json.is_some(), "--trace-json records the bot's samples", ""),
        (a.png.is_some(), "--png draws the bot's path", " (--frames saves the design's VGA output)"),
        (a.map.is_some(), "--map is the bot's world", ""),
        (a.bot.is_some(), "--bot says what stands for the bot", ""),
        (a.firmware.any(), "--timing, --threshold and --compat set the bot's firmware", ""),
        (a.stop_at_line_end, "--stop-at-line-end looks at the bot's samples", ""),
        (a.stop_when_blocked, "--stop-when-blocked looks at the bot's samples", ""),
        (in_samples(&a.trace_from), "--trace-from N counts the bot's samples", BY_TIME),
        (in_samples(&a.trace_to), "--trace-to N counts the bot's samples", BY_TIME),
    ];
    match given.iter().find(|(on, _, _)| *on) {
        Some((_, what, hint)) => Err(format!("{what}, and the design has no bot{hint}")),
        None => Ok(()),
    }
}

/// What a Verilator finding that Vivado accepts means for the simulation, for the codes the
/// build waives (`VERILATOR_FLAGS` in src/board/build.rs).
fn leniency(code: &str) -> Option<&'static str> {
    match code {
        "BLKANDNBLK" => Some(
            "a variable is given both blocking and non-blocking assignments; Vivado builds it, and botsim simulates each assignment as written",
        ),
        "MULTIDRIVEN" => Some(
            "a signal has more than one driver (Vivado reports it too); botsim simulates the drivers as written, so what the signal shows depends on which ran last",
        ),
        _ => None,
    }
}
