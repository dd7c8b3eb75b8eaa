//! `botsim board`: simulate a student's whole board design with the world in the loop.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::time::Instant;

use botsim::board::build::{build, BotKind, CpuModel};
use botsim::board::iss::{Host, TraceRequest};
use botsim::board::lockstep::Lockstep;
use botsim::board::model::{BoardModel, Event, FastForward, Printing, RawEvent, Stop};
use botsim::files::{check_writable, write_atomic};
use botsim::firmware::{SOURCE, SOURCE_PATH};
use botsim::kcpsm6::loader;
use botsim::kcpsm6::source::SourceMap;
use botsim::render::{path_picture, PathStyle};
use botsim::{Snapshot, World};
use botsim_core::board::display::Display;
use botsim_core::board::gtkw::View;
use botsim_core::board::ip::ClockSpec;
use botsim_core::board::plan::{Plan, Request, Rom};
use botsim_core::board::resolve::{resolve, Options};
use botsim_core::board::stimulus::{parse_press, parse_time, Stimulus};
use botsim_core::board::vga::Capture;
use botsim_core::board::wrapper;
use botsim_core::debug::{cpu_signals, describe_pc, register_filters, sample_state, Break, BreakSpec, Breaks};

use crate::cli::args::FirmwareArgs;
use crate::cli::run::{csv_row, json_row, CSV_HEADER};

/// Simulate your Nexys4 design: your top, your PicoBlaze and firmware, your display and LEDs,
/// with botsim's bot, world and Xilinx models in place of the course's netlists.
///
/// SOURCE is a file or a folder (searched recursively for .v/.sv; .vh folders are include
/// paths). botsim's kcpsm6, bot, world_if, map and world_map replace yours; every program ROM
/// (a module with address/instruction/enable/clk) becomes a behavioural ROM holding the
/// program in its INIT strings, or the one you name with --program. The run prints what it
/// replaced. The design is built once (Verilator, C++) and reused while the sources are
/// unchanged.
#[derive(clap::Args, Clone)]
#[command(after_help = "Examples:
  botsim board my_project/ --map world_map_lr.coe --seconds 5 --display display.txt
  botsim board src/ --program src/proj2demo.psm --param SIMULATE=1 --samples 200 --trace-csv trace.csv
  botsim board src/ --press btnC@100+50 --switches 00FF --json")]
pub struct Args {
    /// Your repository's folder, a project file (.xpr, .xise), or Verilog files and folders
    #[arg(required = true, value_name = "SOURCE")]
    sources: Vec<PathBuf>,
    /// The top module [default: the project's, or the one module with a board clock pin that
    /// reaches the bot]
    #[arg(long, value_name = "NAME")]
    top: Option<String>,
    /// Take the definitions in this file over other copies of the same modules
    #[arg(long = "file", value_name = "FILE")]
    prefer: Vec<PathBuf>,
    /// Leave this file or folder out of the repository
    #[arg(long, value_name = "PATH")]
    exclude: Vec<PathBuf>,
    /// The frequency of an output of a clock module the repository has no configuration
    /// for: MODULE.PORT=FREQUENCY (e.g. clk_wiz_0.clk_out1=25MHz), once per output
    #[arg(long, value_name = "MODULE.PORT=FREQ")]
    clock: Vec<String>,
    /// A program (.psm, .hex, .mem, .v) for the ROM module of the same name
    #[arg(long, value_name = "FILE")]
    program: Vec<PathBuf>,
    /// The world (.txt, .coe, .mem, .png) [default: the built-in course]
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    #[command(flatten)]
    firmware: FirmwareArgs,
    /// Stop after the bot's N-th upd_sysregs pulse after reset (sample 0 is the dump after
    /// reset, as in botsim run: the trace has samples 0 to N)
    #[arg(long, value_name = "N")]
    samples: Option<u64>,
    /// Stop after S seconds of simulated time [default: 1, or unlimited with --samples]; more
    /// than 600 s (ten minutes of the board) needs --long
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    seconds: Option<f64>,
    /// Allow a run of more than 600 s of board time (it takes about as long, or longer)
    #[arg(long)]
    long: bool,
    /// Press a button: NAME@TIME[+DURATION] (btnC, btnU, btnD, btnL, btnR, btnCpuReset; times
    /// in ms, or with a unit: 250us, 2s, 5000000c for cycles of 100 MHz; 100 ms by default)
    #[arg(long, value_name = "BTN@MS[+MS]")]
    press: Vec<String>,
    /// The switches from power-up, in hexadecimal
    #[arg(long, value_name = "HEX")]
    switches: Option<String>,
    /// A stimulus file: one `TIME press NAME [DURATION]` or `TIME switches HEX` per line
    #[arg(long, value_name = "FILE")]
    stimulus: Option<PathBuf>,
    /// A parameter of the top: NAME=VALUE (e.g. SIMULATE=1)
    #[arg(long, value_name = "NAME=VALUE")]
    param: Vec<String>,
    /// An include folder
    #[arg(long, value_name = "DIR")]
    include: Vec<PathBuf>,
    /// Tie off a module botsim has no model of
    #[arg(long, value_name = "MODULE")]
    stub: Vec<String>,
    /// The bot's registers at every upd_sysregs (the columns of `botsim run`)
    #[arg(long, value_name = "FILE")]
    trace_csv: Option<PathBuf>,
    /// The same as JSON lines
    #[arg(long, value_name = "FILE")]
    trace_json: Option<PathBuf>,
    /// The bot's path on the world as a PNG
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,
    /// Save the frames of the design's VGA output (PNG, 640 x 480 or 1024 x 768) in this folder
    #[arg(long, value_name = "DIR")]
    frames: Option<PathBuf>,
    /// With --frames: every N-th frame
    #[arg(long, value_name = "N", default_value_t = 1, requires = "frames")]
    frame_every: u64,
    /// Every change of the seven-segment display (and LEDs), one line each
    #[arg(long, value_name = "FILE")]
    display: Option<PathBuf>,
    /// Every change of the display's and the LEDs' pins, one CSV row each (time_ps, an, seg,
    /// dp, led in hex): the board's outputs edge for edge, as a waveform shows them
    #[arg(long, value_name = "FILE")]
    pins: Option<PathBuf>,
    /// A waveform of the whole design (a window of a VGA design's opened later shows its VGA
    /// part as x: see --vcd-all-signals)
    #[arg(long, value_name = "FILE")]
    vcd: Option<PathBuf>,
    /// With --vcd: the largest waveform to write, e.g. 500M or 8G [default: 2G]; a run whose
    /// waveform grows past it stops and says so (a window, --trace-from/--trace-to, keeps it
    /// small)
    #[arg(long, value_name = "SIZE", requires = "vcd")]
    vcd_max: Option<String>,
    /// With --vcd: start the waveform at bot sample N (its iteration in full), at cycle Nc of
    /// the 100 MHz clock, or at a time (2ms, 250us, 1s)
    #[arg(long, value_name = "N|Nc|TIME", requires = "vcd")]
    trace_from: Option<String>,
    /// With --vcd: end the waveform after sample N (its pulse included), at cycle Nc, or at a time
    #[arg(long, value_name = "N|Nc|TIME", requires = "vcd")]
    trace_to: Option<String>,
    /// With --vcd --trace-from on a board whose other clocks drive only what a run does not
    /// record (a VGA design): simulate every edge up to the waveform so that it shows those
    /// parts too (without it, the run skips ahead as it does without a waveform and they read x)
    #[arg(long, requires = "trace_from")]
    vcd_all_signals: bool,
    /// What runs every KCPSM6 of the design (the team's and the bot's): iss (the cycle-exact
    /// instruction-set simulator behind the same ports: only the rest of the design is
    /// evaluated by Verilator, and the board skips what repeats; the same results as rtl, pin
    /// for pin), rtl (botsim's RTL core under Verilator), or lockstep (both, compared every
    /// cycle) [default: iss]
    #[arg(long, value_enum)]
    cpu: Option<CpuArg>,
    /// What stands for the bot: rtl (botsim's bot.v: its KCPSM6 as --cpu says, world_if and
    /// the map under Verilator) or model (the same firmware on the instruction-set simulator
    /// with Rust models of world_if and the map, behind the same ports: same results). With
    /// --cpu lockstep, the ISS board's bot [default: model with --cpu iss and lockstep, but
    /// rtl where the run looks inside the bot's CPU (--cpu-trace, --break) or with --cpu rtl]
    #[arg(long, value_enum)]
    bot: Option<BotArg>,
    /// With --cpu iss --bot model the board skips the periods in which all the run records
    /// repeats itself (the same results, edge for edge); this simulates every edge
    #[arg(long)]
    no_fast_forward: bool,
    /// Evaluate the design at both edges of the clock even where the build found that nothing
    /// happens at the falling ones (the same results, at twice the evaluations; a waveform
    /// always gets both)
    #[arg(long)]
    every_edge: bool,
    /// Measure instead of run: the board harness against a minimal C++ harness of the same
    /// built design (100 MHz oscillator only, nothing recorded), or with --cpu iss the ISS
    /// board against the all-RTL board; in Mcycles/s of the 100 MHz clock, over --seconds of
    /// simulated time [default: 0.05], seven alternating rounds
    #[arg(long)]
    bench: bool,
    /// Write a source-level trace of every KCPSM6 (yours and the bot's) into this folder:
    /// `<instance>.trace.txt`, one line per instruction (cycle, time, PC, label+offset, your
    /// .psm file:line, the instruction, registers written, port accesses, flags), and
    /// `<instance>.profile.txt`, the cycles spent under each label. Runs the CPUs on the ISS
    #[arg(long, value_name = "DIR")]
    cpu_trace: Option<PathBuf>,
    /// With --cpu-trace: trace from this time on (2ms, 250us, 5000000c) [default: 0]
    #[arg(long, value_name = "TIME", requires = "cpu_trace")]
    cpu_trace_from: Option<String>,
    /// With --cpu-trace: trace until this time [default: the end of the run]
    #[arg(long, value_name = "TIME", requires = "cpu_trace")]
    cpu_trace_to: Option<String>,
    /// Stop the run at a breakpoint and say where: pc=03A, label=NAME or line=FILE.psm:N (in
    /// the CPU whose program has it), port=0A or port=0A:18 (an OUTPUT of your CPU to the port,
    /// of the value), bot=blocked, bot=off-line or bot=sensors:XX (at the first sample that
    /// shows it). With --vcd or --cpu-trace, the run is repeated to the stop to write them over
    /// the --break-window before it. Runs the CPUs on the ISS
    #[arg(long = "break", value_name = "WHAT")]
    breaks: Vec<String>,
    /// With --break: how much before the stop the waveform and the trace cover [default: 1ms]
    #[arg(long, value_name = "TIME", requires = "breaks")]
    break_window: Option<String>,
    /// Where a first run stopped, for the second run that writes the waveform and the traces
    /// to it (not an option).
    #[arg(skip)]
    stopped_at: Option<BreakStop>,
    /// This run only finds where a breakpoint stops: it says nothing (not an option).
    #[arg(skip)]
    finding: bool,
    /// Stop at the first sample that finds the bot at the end of a line (stopped on the line
    /// with a wall straight ahead)
    #[arg(long)]
    stop_at_line_end: bool,
    /// Stop at the first sample that shows a move the world refused (the bot drove into an
    /// obstruction; the JSON's first_blocked_sample)
    #[arg(long)]
    stop_when_blocked: bool,
    /// Build the design (or find it built) and stop: for CI caches and suites
    #[arg(long)]
    build_only: bool,
    /// Keep every line the design prints ($display, $write) in this file (standard error
    /// shows the first 200)
    #[arg(long, value_name = "FILE")]
    design_log: Option<PathBuf>,
    /// Print the summary as JSON
    #[arg(long)]
    json: bool,
    /// Print nothing but errors
    #[arg(short, long)]
    quiet: bool,
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

/// `--cpu`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum CpuArg {
    Rtl,
    Iss,
    Lockstep,
}

/// `--bot`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum BotArg {
    Rtl,
    Model,
}

/// The board being run: one model, or the RTL and ISS boards in lock-step.
enum Sim {
    One(Box<BoardModel>),
    Pair(Box<Lockstep>),
}

impl Sim {
    fn main(&mut self) -> &mut BoardModel {
        match self {
            Sim::One(m) => m,
            Sim::Pair(p) => &mut p.rtl,
        }
    }
    fn run(&mut self, until: u64, samples: u64, buf: &mut [RawEvent]) -> Result<(Stop, usize), String> {
        match self {
            Sim::One(m) => Ok(m.run(until, samples, buf)),
            Sim::Pair(p) => p.run(until, samples, buf).map_err(|d| d.to_string()),
        }
    }
    fn set_inputs(&mut self, r: bool, b: u8, sw: u16) {
        match self {
            Sim::One(m) => m.set_inputs(r, b, sw),
            Sim::Pair(p) => p.set_inputs(r, b, sw),
        }
    }
    fn record_vga(&mut self, on: bool) {
        match self {
            Sim::One(m) => m.record_vga(on),
            // Both boards' VGA pins are compared.
            Sim::Pair(p) => {
                p.rtl.record_vga(true);
                p.iss.record_vga(true);
            }
        }
    }
    /// Close the --cpu-trace files (the ISS board's).
    fn finish_traces(&mut self) -> Result<Vec<PathBuf>, String> {
        let m = match self {
            Sim::One(m) => m,
            Sim::Pair(p) => &mut p.iss,
        };
        m.host_mut().map_or(Ok(Vec::new()), Host::finish)
    }
    /// The breakpoint that stopped a CPU.
    fn hit(&self) -> Option<&botsim::board::iss::Hit> {
        match self {
            Sim::One(m) => m.host().and_then(Host::hit),
            Sim::Pair(p) => p.iss.host().and_then(Host::hit),
        }
    }
    /// A model error of a --cpu iss or lockstep run.
    fn check(&self) -> Result<(), String> {
        match self {
            Sim::One(m) => m.host().map_or(Ok(()), Host::check),
            Sim::Pair(p) => p.check().map_err(|e| e.to_string()),
        }
    }
}

pub fn run(a: Args) -> Result<(), String> {
    // Ctrl-C stops a build (its compilers and its temporary folder go) or a run (its outputs
    // written up to there), never the process in the middle of either.
    botsim::interrupt::catch();
    if a.cpu.is_none() {
        // The default is the ISS; a design whose KCPSM6 it cannot stand for (a ROM botsim
        // cannot read) runs on the RTL core instead, said.
        let mut first = a.clone();
        first.cpu = Some(CpuArg::Iss);
        return match run_with_breaks(first) {
            Err(e) if e.starts_with(ISS_CANNOT) => {
                if !a.quiet && !a.json {
                    eprintln!("note: {e}; running it on the RTL core (--cpu rtl)");
                }
                run_with_breaks(Args { cpu: Some(CpuArg::Rtl), ..a })
            }
            r => r,
        };
    }
    run_with_breaks(a)
}

/// How an error starts when the ISS cannot stand for a design's KCPSM6.
const ISS_CANNOT: &str = botsim::board::iss::ISS_CANNOT;

fn run_with_breaks(a: Args) -> Result<(), String> {
    if a.breaks.is_empty() || (a.vcd.is_none() && a.cpu_trace.is_none()) {
        return run_once(a).map(|_| ());
    }
    // First find the stop; then the same run, which is deterministic, to the stop with the
    // waveform and the trace over the window before it.
    let window = match &a.break_window {
        Some(w) => parse_time(w).map_err(|e| format!("--break-window: {e}"))?,
        None => 1_000_000_000,
    };
    let mut find = a.clone();
    (find.vcd, find.cpu_trace, find.trace_from, find.trace_to) = (None, None, None, None);
    find.finding = true;
    let Some(found) = run_once(find)? else {
        return run_once(a).map(|_| ());
    };
    let stop = found.time_ps;
    // On past the stop: through the edge that stopped a CPU and two instructions more, so the
    // waveform shows the stop inside it; after a bot condition, long enough for the firmware's
    // answer to that sample (its interrupt, its decision, its motor command). The outputs
    // other than the waveform and the CPU traces still end at the stop.
    let after = if found.bot { BOT_BREAK_AFTER_PS } else { CPU_BREAK_AFTER_PS };
    let mut again = a;
    again.breaks.clear();
    again.stopped_at = Some(found);
    let end_cycle = (stop + after) / 10_000 + 1;
    again.seconds = Some(end_cycle as f64 * 1e-8);
    again.samples = None;
    let from = format!("{}c", (stop.saturating_sub(window)) / 10_000);
    if again.trace_from.is_none() && again.vcd.is_some() {
        again.trace_from = Some(from.clone());
    }
    if again.cpu_trace_from.is_none() && again.cpu_trace.is_some() {
        again.cpu_trace_from = Some(from);
    }
    run_once(again).map(|_| ())
}

/// Where a `--break` stopped a run.
#[derive(Clone, Debug)]
struct BreakStop {
    time_ps: u64,
    /// What it says ("stopped by --break ...").
    message: String,
    /// A bot condition (at a sample), not a CPU's breakpoint.
    bot: bool,
}

/// What a `--break` stopped.
type Stopped = Option<BreakStop>;

/// The progress line of a long run on a terminal: board time (or samples) against the end,
/// the rate against real time and the expected end; shown once a run has taken 2 s.
struct Progress {
    on: bool,
    end_ps: u64,
    samples: u64,
    start: Instant,
    bar: Option<indicatif::ProgressBar>,
}

impl Progress {
    fn new(wanted: bool, end_ps: u64, samples: u64) -> Progress {
        use std::io::IsTerminal;
        let on = wanted && std::io::stderr().is_terminal();
        Progress { on, end_ps, samples, start: Instant::now(), bar: None }
    }

    fn show(&mut self, now_ps: u64, samples: u64) {
        if !self.on || self.start.elapsed() < std::time::Duration::from_secs(2) {
            return;
        }
        let by_time = self.end_ps != u64::MAX;
        let bar = self.bar.get_or_insert_with(|| {
            let len = if by_time { self.end_ps / 1_000_000_000 } else { self.samples };
            let b = indicatif::ProgressBar::new(len);
            let unit = if by_time { "ms of board time" } else { "samples" };
            b.set_style(
                indicatif::ProgressStyle::with_template(&format!(
                    "{{bar:30}} {{pos}}/{{len}} {unit}, {{msg}}, ends in {{eta}}"
                ))
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            b
        });
        bar.set_position(if by_time { now_ps / 1_000_000_000 } else { samples });
        let real = now_ps as f64 / 1e12 / self.start.elapsed().as_secs_f64();
        bar.set_message(format!("{real:.2} x real time"));
    }

    fn done(&mut self) {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
    }
}

/// The one line that says why a design stopped at `at` from its runtime's message `f` (the
/// user's paths already in it).
fn design_stopped(f: &str, built: &botsim::board::build::Built, at: &str) -> String {
    if f.contains("did not converge") {
        // Verilator names the loop when it builds the design (UNOPTFLAT).
        let looped = built.warnings.iter().find(|(code, _, _)| code == "UNOPTFLAT").map(|(_, _, first)| {
            let place = first.split(": ").next().unwrap_or("");
            let signal = first.rsplit('\'').nth(1).unwrap_or("").trim_start_matches("botsim_board.user.");
            format!("{place}: `{signal}` depends on itself (a combinational loop)")
        });
        return match looped {
            Some(l) => format!("{l}: the design never settles, stopped at {at}"),
            None => format!(
                "the design never settles (a combinational loop, or an always block with no event), stopped at {at}"
            ),
        };
    }
    if let Some(file) = f.strip_suffix(":0: $readmem file not found") {
        return format!("{file}: the design's $readmem cannot read this file (stopped at {at})");
    }
    format!("{f} (stopped at {at})")
}

/// The longest run `--seconds` allows without `--long`, in seconds of board time.
const LONG_RUN_S: f64 = 600.0;

/// The most board time one call into the model covers: between two calls the run checks
/// Ctrl-C, the waveform's size and its progress line.
const CHUNK_PS: u64 = 50_000_000_000;

/// The largest waveform written without `--vcd-max`.
pub const VCD_MAX: u64 = 2 << 30;

/// A size in bytes from `500M`, `2G`, `4096` (K, M, G: powers of 1024).
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let (num, unit) = match t.char_indices().find(|(_, c)| c.is_ascii_alphabetic()) {
        Some((i, _)) => (&t[..i], t[i..].trim_end_matches(['B', 'b'])),
        None => (t, ""),
    };
    let scale: u64 = match unit.to_ascii_uppercase().as_str() {
        "" => 1,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        _ => return Err("expected a size such as 500M or 4G".into()),
    };
    num.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .map(|v| (v * scale as f64) as u64)
        .ok_or_else(|| "expected a size such as 500M or 4G".into())
}

/// How many lines of the design's own printing standard error shows.
const DESIGN_LINES: u64 = 200;

/// How far a waveform and CPU trace written for a breakpoint go on past the stop.
const CPU_BREAK_AFTER_PS: u64 = 40_000;
const BOT_BREAK_AFTER_PS: u64 = 100_000_000;

/// One run of the board; the time of the stop when a breakpoint stopped it.
fn run_once(a: Args) -> Result<Stopped, String> {
    // Arguments first: every bad one is one line before anything is built.
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
        let img = loader::load(p, &botsim::kcpsm6::asm::Options::default()).map_err(|d| d.to_string())?;
        programs.push((p.clone(), img));
    }
    for p in [&a.trace_csv, &a.trace_json, &a.png, &a.display, &a.pins, &a.vcd, &a.design_log].into_iter().flatten() {
        check_writable(p)?;
    }
    if let Some(d) = &a.frames {
        std::fs::create_dir_all(d).map_err(|e| format!("{}: error: cannot create the folder: {e}", d.display()))?;
        check_writable(&d.join("frame.png"))?;
    }

    // Find the design, plan and build.
    let clocks = a.clock.iter().map(|c| ClockSpec::parse(c)).collect::<Result<Vec<_>, _>>()?;
    let options = Options {
        top: a.top.clone(),
        prefer: a.prefer.clone(),
        exclude: a.exclude.clone(),
        clocks,
        stubs: a.stub.clone(),
        include_dirs: a.include.clone(),
    };
    let design = resolve(&a.sources, &options).map_err(|e| e.to_string())?;
    let req = Request { programs, bot_firmware, force_own_firmware: a.firmware.any() };
    let mut plan = Plan::new(&design, &req).map_err(|e| e.to_string())?;
    // Every --param names a parameter of the top.
    if let Some((src, top)) = design.sources.iter().find_map(|s| s.module(&design.top).map(|m| (s, m))) {
        if let Some((name, _)) = params.iter().find(|(n, _)| !top.params.contains(n)) {
            let has = if top.params.is_empty() { "none".to_string() } else { top.params.join(", ") };
            return Err(format!(
                "--param {name}: the top `{}` ({}:{}) has no parameter {name} (its parameters: {has})",
                top.name,
                src.path.display(),
                top.line
            ));
        }
    }
    plan.replaced.extend(design.generated.iter().cloned());
    let say = |s: String| {
        if !a.quiet && !a.json {
            eprintln!("{s}");
        }
    };
    if let Some(p) = &design.project {
        say(format!("botsim board: the project {}", p.display()));
    }
    for n in &design.notes {
        say(format!("note: {n}"));
    }
    say(format!("botsim board: top `{}`, bot at `{}.{}`", plan.top, plan.top, plan.bot_path));
    for r in &plan.replaced {
        let from = if r.from.is_empty() { String::new() } else { format!(" ({})", r.from) };
        say(format!("  replaced {}{from} with {}", r.module, r.with));
    }
    for w in &plan.warnings {
        say(format!("warning: {w}"));
    }
    if !plan.unknown_pins.is_empty() {
        say(format!("  ports with no board pin (inputs held low, outputs open): {}", plan.unknown_pins.join(", ")));
    }
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
            say("note: --cpu-trace and --break run the KCPSM6s on the ISS (--cpu iss: the same results, cycle for cycle)".into());
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
    let maps = sources(&plan);
    let (cpu_breaks, bot_breaks) = breakpoints(&a.breaks, &plan, &maps)?;
    // The models' programs are known before anything is built.
    let looks_inside = a.cpu_trace.is_some() || !a.breaks.is_empty();
    let bot = match (a.bot, cpu_arg) {
        (Some(BotArg::Model), _) => BotKind::Model,
        (None, CpuArg::Iss | CpuArg::Lockstep) if !looks_inside => BotKind::Model,
        _ => BotKind::Rtl,
    };
    // The lock-step's RTL board is all RTL; --bot applies to its ISS board.
    let main_bot = if lockstep { BotKind::Rtl } else { bot };
    let host = |plan: &Plan, cpu: CpuModel, bot: BotKind| -> Result<Option<Box<Host>>, String> {
        let mut h = match cpu {
            // The RTL board's host only writes debug text.
            CpuModel::Rtl => Host::new(Vec::new(), false),
            _ => {
                let mut h = Host::for_plan(plan, lockstep).map_err(|e| e.to_string())?;
                if let (Some(dir), CpuModel::Iss) = (&a.cpu_trace, cpu) {
                    h.trace(TraceRequest { dir: dir.clone(), window: trace_window, sources: maps.clone() });
                }
                if cpu == CpuModel::Iss {
                    h.break_at(cpu_breaks.clone());
                }
                h
            }
        };
        // The bot's firmware: the plan always has a bot_pgm (the user's, or botsim's).
        if let (BotKind::Model, Some(r)) = (bot, plan.roms.iter().find(|r| r.module == "bot_pgm")) {
            h.model_bot(r.image.clone(), world.clone());
        }
        Ok(Some(h))
    };
    host(&plan, cpu, main_bot)?;
    let debug = a.vcd.is_some();
    let built = build(&plan, &params, cpu, main_bot, debug, a.quiet || a.json).map_err(|e| e.to_string())?;
    match built.seconds {
        Some(s) => say(format!("  built in {s:.1} s with Verilator {} ({})", built.verilator, built.library.display())),
        None => say(format!("  reused the build in {}", built.library.parent().unwrap_or(&built.library).display())),
    }
    if let Some(at) = &built.delays {
        say(format!(
            "note: {at}: the design has delays (#): botsim simulates them as written (Vivado's synthesis ignores them), evaluating every clock edge"
        ));
    }
    for (code, n, first) in &built.warnings {
        match leniency(code) {
            Some(what) => {
                let at = first.split(": ").next().unwrap_or(first);
                let more = if *n > 1 { format!(" (and {} more)", n - 1) } else { String::new() };
                say(format!("note: {at}: {what}{more}"));
            }
            None => say(format!("  verilator warning {code} ({n}x), first: {first}")),
        }
    }

    let twin = if lockstep {
        let b = build(&plan, &params, CpuModel::Iss, bot, false, a.quiet || a.json).map_err(|e| e.to_string())?;
        match b.seconds {
            Some(s) => say(format!("  built the ISS board in {s:.1} s")),
            None => say("  reused the ISS board's build".into()),
        }
        Some(b)
    } else {
        None
    };

    if a.build_only {
        return Ok(None);
    }
    if a.bench && cpu == CpuModel::Iss {
        let rtl =
            build(&plan, &params, CpuModel::Rtl, BotKind::Rtl, false, a.quiet || a.json).map_err(|e| e.to_string())?;
        let iss = &built.library;
        let ff = main_bot == BotKind::Model && !a.no_fast_forward;
        return bench_iss([&rtl.library, iss], &world, &plan.roms, a.seconds.unwrap_or(0.05), a.json, ff, &|| {
            host(&plan, cpu, main_bot)
        })
        .map(|_| None);
    }
    if a.bench {
        return bench(&built.library, &world, &plan.roms, a.seconds.unwrap_or(0.05), a.json, &|| {
            host(&plan, cpu, main_bot)
        })
        .map(|_| None);
    }

    // Run.
    let printing = Printing { log: a.design_log.clone(), lines: if a.quiet { 0 } else { DESIGN_LINES } };
    let mut first = load(&built.library, &world, &plan.roms, host(&plan, cpu, main_bot)?, &printing)?;
    if a.every_edge {
        first.every_edge();
    }
    let mut model = match &twin {
        Some(b) => {
            let mut iss = load(&b.library, &world, &plan.roms, host(&plan, CpuModel::Iss, bot)?, &Printing::SILENT)?;
            if a.every_edge {
                iss.every_edge();
            }
            Sim::Pair(Box::new(Lockstep::new(first, iss)))
        }
        None => Sim::One(Box::new(first)),
    };
    // The waveform: open from the start, or at its --trace-from mark.
    let (mut vcd_open, mut vcd_done, mut vcd_close_at) = (false, a.vcd.is_none(), None);
    if let (Some(v), Mark::Time(0) | Mark::Sample(0)) = (&a.vcd, vcd_from) {
        model.main().open_vcd(v).map_err(|e| e.to_string())?;
        vcd_open = true;
    }
    model.record_vga(a.frames.is_some());
    // The fast-forward: every KCPSM6 and the bot are models, and nothing needs every edge
    // (a waveform turns it off while it is written).
    let fast_forward = !a.no_fast_forward
        && cpu == CpuModel::Iss
        && main_bot == BotKind::Model
        && a.frames.is_none()
        && a.cpu_trace.is_none()
        && cpu_breaks.is_empty();
    // Why a run that could fast-forward does not (the design, not the options).
    let mut fast_forward_off: Option<String> = None;
    if let Sim::One(m) = &mut model {
        if fast_forward {
            // A waveform window later shows every variable: compare them all until then. A
            // board with another clock cannot; unless asked to, it skips as without a
            // waveform, which then shows what the run did not simulate as x.
            let mut mode = if a.vcd.is_some() { FastForward::Whole } else { FastForward::Recorded };
            fast_forward_off = m.fast_forward_blocker().map(str::to_string);
            let mut on = fast_forward_off.is_none() && m.fast_forward(mode);
            if !on
                && fast_forward_off.is_none()
                && mode == FastForward::Whole
                && !vcd_open
                && !a.vcd_all_signals
                && m.unshown_unknown().is_none()
            {
                mode = FastForward::Recorded;
                on = m.fast_forward(mode);
                if on {
                    say("note: the waveform shows x for the parts of the design the run does not record (another clock drives them, and they are not simulated before it); --vcd-all-signals simulates every edge to show them".into());
                }
            }
            if fast_forward_off.is_none() && !on {
                let why = match (mode, m.observed_unknown()) {
                    (FastForward::Whole, _) => "a waveform later shows every variable".to_string(),
                    (_, Some(unknown)) => format!("what a run observes of it is not known: {unknown}"),
                    _ => "one besides the oscillator drives what the run records".to_string(),
                };
                fast_forward_off = Some(format!(
                    "the board has {} clocks, and {why} (the fast-forward needs one clock, or others that drive only what the run does not record)",
                    m.clocks().len()
                ));
            }
            if let Some(why) = &fast_forward_off {
                say(format!("note: no fast-forward: {why}; every clock edge is simulated"));
            }
        } else {
            m.fast_forward(FastForward::Off);
        }
    }
    let mut vga = Capture::default();
    let mut frames_seen = 0u64;
    let mut frames_written = 0u64;
    let end_ps = match (a.seconds, a.samples) {
        (Some(s), _) => (s * 1e12) as u64,
        (None, Some(_)) => u64::MAX,
        (None, None) => 1_000_000_000_000,
    };
    // As botsim run: sample 0 is the dump after reset, --samples N stops after sample N.
    let sample_limit = a.samples.map_or(u64::MAX, |n| n.saturating_add(1));
    // Times at which the run stops to change something: the inputs, the waveform window.
    let mut stops: BTreeSet<u64> = stimulus.change_times().into_iter().collect();
    if a.vcd.is_some() {
        for m in [Some(vcd_from), vcd_to].into_iter().flatten() {
            if let Mark::Time(t) = m {
                stops.insert(t);
            }
        }
    }
    let (r, b, sw) = stimulus.inputs_at(0);
    model.set_inputs(r, b, sw);

    let t0 = Instant::now();
    let vcd_max = a.vcd_max.as_deref().map_or(Ok(VCD_MAX), parse_size)?;
    let mut progress = Progress::new(!a.quiet && !a.json && !a.finding, end_ps, sample_limit);
    let mut display = Display::default();
    let mut display_log = String::new();
    let mut pins_csv = String::from("time_ps,an,seg,dp,led\n");
    let mut pins_now = (0xFFu8, 0x7Fu8, 1u8, 0u16);
    let mut snapshots: Vec<Snapshot> = Vec::new();
    let mut json = String::new();
    let mut buf = vec![RawEvent::default(); 4096];
    let mut last_led = 0u16;
    let mut at_end = false;
    let mut blocked_now = false;
    let mut bot_stop: Option<BreakStop> = None;
    let mut last_sample_ps = 0u64;
    let counted_in_samples = a.seconds.is_none();
    // A run repeated to a stop writes its other outputs up to the stop only.
    let past_stop = |t: u64| a.stopped_at.as_ref().is_some_and(|s| t > s.time_ps);
    let finished = loop {
        if crate::cli::interrupted() {
            break None;
        }
        let now = model.main().time_ps();
        let mut until = stops.range(now + 1..).next().copied().unwrap_or(end_ps).min(end_ps);
        // A waveform grows fast: its size is looked at more often.
        until = until.min(now.saturating_add(if vcd_open { CHUNK_PS / 10 } else { CHUNK_PS }));
        progress.show(now, snapshots.len() as u64);
        if let (Some(v), true) = (&a.vcd, vcd_open) {
            let size = std::fs::metadata(v).map_or(0, |m| m.len());
            if size > vcd_max {
                drop(model);
                let _ = std::fs::remove_file(v);
                return Err(format!(
                    "{}: the waveform passed {} MB at {:.3} ms of board time and was removed: ask for a window (--trace-from/--trace-to) or allow more (--vcd-max)",
                    v.display(),
                    vcd_max >> 20,
                    now as f64 / 1e9
                ));
            }
        }
        // A run counted in samples waits for the next one a bounded time.
        if counted_in_samples {
            until = until.min(last_sample_ps.saturating_add(NO_SAMPLE_PS));
        }
        // A window given in samples: stop after sample s - 1 to open, after sample s to close.
        let window_limit = match (vcd_done, vcd_open, vcd_from, vcd_to) {
            (false, false, Mark::Sample(s), _) => Some(s),
            (false, true, _, Some(Mark::Sample(s))) if vcd_close_at.is_none() => Some(s + 1),
            _ => None,
        };
        let mut limit = window_limit.map_or(sample_limit, |w| w.min(sample_limit));
        if a.stop_at_line_end || a.stop_when_blocked || !bot_breaks.is_empty() {
            limit = limit.min(snapshots.len() as u64 + 1);
        }
        let (stop, n) = model.run(until, limit, &mut buf)?;
        for e in buf[..n].iter().filter(|r| !past_stop(r.time_ps())).filter_map(Event::of) {
            match e {
                Event::Display { time_ps, an, seg, dp } => {
                    pins_now = (an, seg, dp as u8, pins_now.3);
                    pins_csv.push_str(&pins_row(time_ps, pins_now));
                    let before = display.lines().len();
                    display.pins(time_ps, an, seg, dp);
                    for l in &display.lines()[before..] {
                        display_log.push_str(&format!("{:>12.3} ms  display {}\n", l.time_ps as f64 / 1e9, l.text));
                    }
                }
                Event::Leds { time_ps, leds } => {
                    pins_now.3 = leds;
                    pins_csv.push_str(&pins_row(time_ps, pins_now));
                    last_led = leds;
                    display_log.push_str(&format!("{:>12.3} ms  leds    {leds:016b}\n", time_ps as f64 / 1e9));
                }
                Event::Sample { time_ps, snapshot, motctl } => {
                    last_sample_ps = time_ps;
                    json.push_str(&json_row(&snapshot, motctl));
                    at_end = at_end || (a.stop_at_line_end && at_line_end(&snapshot));
                    blocked_now = blocked_now
                        || (a.stop_when_blocked
                            && snapshots.last().is_some_and(|b| b.move_refused(&snapshot, fw.threshold)));
                    if bot_stop.is_none() {
                        let before = snapshots.last();
                        if let Some(b) = bot_breaks.iter().find(|b| b.hit(before, &snapshot, fw.threshold)) {
                            let at = sample_state(&snapshot).replacen(
                                ',',
                                &format!(" at {:.6} ms,", time_ps as f64 / 1e9),
                                1,
                            );
                            bot_stop = Some(BreakStop {
                                time_ps,
                                bot: true,
                                message: format!("stopped by --break {}: {at}", b.text),
                            });
                        }
                    }
                    snapshots.push(snapshot);
                }
                Event::Vga { time_ps, pins } => vga.pins(time_ps, pins),
                // Recorded for the lock-step's comparison only.
                Event::Bot { .. } => {}
            }
        }
        if let Some(dir) = &a.frames {
            for f in vga.take() {
                if frames_seen % a.frame_every.max(1) == 0 {
                    write_atomic(&dir.join(format!("frame_{frames_seen:05}.png")), &f.png())?;
                    frames_written += 1;
                }
                frames_seen += 1;
            }
        }
        if at_end {
            break Some("line-end");
        }
        if blocked_now {
            break Some("blocked");
        }
        if bot_stop.is_some() {
            break Some("break");
        }
        match stop {
            Stop::BufferFull => continue,
            Stop::Samples if snapshots.len() as u64 >= sample_limit => break Some("samples"),
            // A stop after one more sample, to look for the end of the line.
            Stop::Samples if !window_limit.is_some_and(|w| snapshots.len() as u64 >= w) => continue,
            Stop::Samples => {
                // A window mark in samples.
                if let (false, Some(v)) = (vcd_open, &a.vcd) {
                    model.main().open_vcd(v).map_err(|e| e.to_string())?;
                    vcd_open = true;
                } else {
                    // Close with the whole 2-clock pulse in the window (3 clocks of 100 MHz).
                    let t = model.main().time_ps() + 30_000;
                    stops.insert(t);
                    vcd_close_at = Some(t);
                }
            }
            Stop::Finished => break Some("finish"),
            Stop::Until => {
                // A CPU the ISS cannot stand for stops the run here, not at its end.
                model.check()?;
                let t = model.main().time_ps();
                if t >= end_ps {
                    break Some("time");
                }
                if counted_in_samples && t >= last_sample_ps.saturating_add(NO_SAMPLE_PS) {
                    let after = match snapshots.last() {
                        None => "from the start".to_string(),
                        Some(s) => format!("after sample {} at {:.3} ms", s.sample, last_sample_ps as f64 / 1e9),
                    };
                    return Err(format!(
                        "no bot sample in {} s of board time {after} (upd_sysregs never pulsed: is the bot held in reset, or its clock stopped?)",
                        NO_SAMPLE_PS / 1_000_000_000_000
                    ));
                }
                if stops.contains(&t) {
                    let (r, b, sw) = stimulus.inputs_at(t);
                    model.set_inputs(r, b, sw);
                    if let Some(v) = &a.vcd {
                        if !vcd_open && !vcd_done && vcd_from == Mark::Time(t) {
                            model.main().open_vcd(v).map_err(|e| e.to_string())?;
                            vcd_open = true;
                        } else if vcd_open && (vcd_to == Some(Mark::Time(t)) || vcd_close_at == Some(t)) {
                            model.main().close_vcd().map_err(|e| e.to_string())?;
                            (vcd_open, vcd_done) = (false, true);
                        }
                    }
                }
            }
        }
    };
    let wall = t0.elapsed().as_secs_f64();
    let (skips, skipped_ps) = model.main().fast_forwarded();
    let sim_ps = model.main().time_ps();
    display.settle(sim_ps);
    model.check()?;
    let traces = model.finish_traces()?;
    // A breakpoint in a CPU stops the model like $finish.
    let cpu_stop = model.hit().map(|h| {
        let (path, at) = (h.cpu.clone(), describe_pc(maps.get(&h.cpu), h.pc));
        BreakStop {
            time_ps: h.time_ps,
            bot: false,
            message: format!(
                "stopped by --break {}: {path} at {at} in its cycle {}, at {:.6} ms",
                h.what,
                h.cycle,
                h.time_ps as f64 / 1e9
            ),
        }
    });
    progress.done();
    let stopped = cpu_stop.or(bot_stop).or(a.stopped_at.clone());
    // The design's own printing ends here: botsim's lines start on lines of their own.
    let (design_lines, mid_line) = model.main().printed();
    if mid_line {
        eprintln!();
    }
    if let Some(s) = &stopped {
        if !a.json && !a.finding {
            eprintln!("{}", s.message);
        }
    } else if let Some(f) = model.main().fatal() {
        let at = format!("{:.6} ms", model.main().time_ps() as f64 / 1e9);
        if let (Some(v), Some(why)) = (&a.vcd, f.strip_prefix(":0: VerilatedVcd::bufferFlush: ")) {
            drop(model);
            let _ = std::fs::remove_file(v);
            return Err(format!(
                "{}: the waveform could not be written ({why}) at {at}; the part written was removed",
                v.display()
            ));
        }
        return Err(design_stopped(&built.user_paths(&f), &built, &at));
    }
    if let (Some(f), false) = (model.main().finish(), a.json || a.quiet || a.finding) {
        eprintln!(
            "botsim board: the design called $finish at {} ({:.6} ms)",
            built.user_paths(&f),
            model.main().time_ps() as f64 / 1e9
        );
    }
    let finished = if stopped.is_some() { Some("break") } else { finished };
    model.main().close_vcd().map_err(|e| e.to_string())?;
    if let (Some(v), Some((start, end))) = (&a.vcd, model.main().vcd_span()) {
        let view = save_file_view(start, end, stopped.as_ref());
        write_save_file(v, &plan, &maps, cpu == CpuModel::RtlProbed, main_bot == BotKind::Model, view)?;
    }

    // Outputs.
    if let Some(p) = &a.trace_csv {
        let mut csv = format!("{CSV_HEADER}\n");
        for s in &snapshots {
            csv.push_str(&csv_row(s));
        }
        write_atomic(p, csv.as_bytes())?;
    }
    if let Some(p) = &a.trace_json {
        write_atomic(p, json.as_bytes())?;
    }
    if let Some(p) = &a.pins {
        write_atomic(p, pins_csv.as_bytes())?;
    }
    if let Some(p) = &a.display {
        write_atomic(p, display_log.as_bytes())?;
    }
    if let Some(p) = &a.png {
        let picture = path_picture(&world, &snapshots, fw.threshold, &PathStyle::default());
        write_atomic(p, &picture)?;
    }
    let last_display = display.lines().last().map(|l| l.text.clone()).unwrap_or_default();
    let end = snapshots.last().map(|s| (s.regs.loc_x, s.regs.loc_y));
    let evals = model.main().evals();
    // Moves the world refused (the destination was an obstruction): the samples with the event.
    let blocked: Vec<u64> =
        snapshots.windows(2).filter(|w| w[0].move_refused(&w[1], fw.threshold)).map(|w| w[0].sample).collect();
    if a.finding {
        // The run that writes the waveform and the traces says it all.
    } else if a.json {
        let v = serde_json::json!({
            "top": plan.top,
            "simulated_seconds": sim_ps as f64 / 1e12,
            "stopped_by": finished.unwrap_or("interrupt"),
            "samples": snapshots.len(),
            "end": snapshots.last().map(|s| serde_json::json!({
                "loc_x": s.regs.loc_x, "loc_y": s.regs.loc_y, "sensors": s.regs.sensors,
                "orientation": s.orientation().name(), "movement": s.movement().name(),
                // Stopped on the line with a wall straight ahead: the end of a course.
                "at_line_end": at_line_end(s),
            })),
            "blocked_moves": blocked.len(),
            "first_blocked_sample": blocked.first(),
            "display": last_display,
            "leds": last_led,
            "vga_frames": frames_seen,
            "vga_frames_written": frames_written,
            "vga_unknown_frames": vga.unknown,
            "vcd_x_signals": model.main().vcd_unshown(),
            "evaluations": evals,
            "wall_seconds": wall,
            "build_seconds": built.seconds,
            "verilator": built.verilator,
            "cpu_traces": traces,
            "design_lines": design_lines,
            "fast_forward": {"skips": skips, "skipped_seconds": skipped_ps as f64 / 1e12, "off_because": fast_forward_off},
            "break": stopped.as_ref().map(|s| serde_json::json!({"time_ps": s.time_ps, "what": s.message})),
        });
        println!("{v}");
    } else if !a.quiet {
        let end = end.map_or("no sample yet".to_string(), |(x, y)| format!("({x}, {y})"));
        println!(
            "simulated {:.3} s in {wall:.1} s: {} samples, the bot ended at {end}, the display showed \"{last_display}\", LEDs {last_led:016b}",
            sim_ps as f64 / 1e12,
            snapshots.len()
        );
        if skips > 0 {
            println!("  fast-forwarded {:.3} s of it in {skips} skips", skipped_ps as f64 / 1e12);
        }
        for t in &traces {
            println!("  wrote {}", t.display());
        }
    }
    Ok(stopped)
}

/// Stopped on the line with a wall straight ahead: the end of a course.
fn at_line_end(s: &Snapshot) -> bool {
    s.sensors().on_line()
        && s.sensors().prox_left()
        && s.sensors().prox_right()
        && s.movement() == botsim::Movement::Stopped
}

/// What the save file opens on: the whole waveform, or after a breakpoint about twelve
/// instructions of a 100 MHz KCPSM6 (wide enough for their text) with the marker on the
/// stop: those before a CPU's stop, those after a bot condition's sample (the firmware's
/// answer to it begins there).
fn save_file_view(start_ps: u64, end_ps: u64, stop: Option<&BreakStop>) -> View {
    const SPAN_PS: u64 = 240_000;
    const MARGIN_PS: u64 = 40_000;
    match stop {
        Some(s) if (start_ps..=end_ps).contains(&s.time_ps) => {
            let t = s.time_ps;
            let from = if s.bot { t.saturating_sub(MARGIN_PS) } else { (t + MARGIN_PS).saturating_sub(SPAN_PS) };
            let from = from.max(start_ps);
            View { start_ps: from, end_ps: (from + SPAN_PS).min(end_ps), marker_ps: Some(t) }
        }
        _ => View { start_ps, end_ps: end_ps.max(start_ps + 1), marker_ps: None },
    }
}

/// The GTKWave save file beside a waveform (`w.vcd` -> `w.gtkw`), with its translate filters:
/// the board pins, the bot's registers (BotInfo as heading and movement, MotCtl as movement)
/// and every KCPSM6 (its address as `label+offset` where the program's source is known, the
/// instruction text, the status, the registers, the port bus); with `bot_model`, the bot has
/// no KCPSM6 in the waveform.
fn write_save_file(
    vcd: &Path,
    plan: &Plan,
    sources: &BTreeMap<String, SourceMap>,
    probed: bool,
    bot_model: bool,
    view: View,
) -> Result<(), String> {
    use botsim_core::board::gtkw::{filter_text, Format, SaveFile};
    let top = "TOP.botsim_board";
    let side = |suffix: &str| {
        let name = vcd.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        vcd.with_file_name(format!("{name}.{suffix}"))
    };
    let mut s = SaveFile::new(&std::path::absolute(vcd).unwrap_or_else(|_| vcd.to_path_buf()));
    s.view(view);
    let sig = |n: &str, f: Format| (format!("{top}.{n}"), f, None);
    // The wrapper's board pins (wrapper.rs), each in the radix it reads best in.
    const PINS: [(&str, Format); 13] = [
        ("clk", Format::Binary),
        ("reset_pressed", Format::Binary),
        ("btn[4:0]", Format::Binary),
        ("sw[15:0]", Format::Hex),
        ("led[15:0]", Format::Binary),
        ("an[7:0]", Format::Binary),
        ("seg[6:0]", Format::Binary),
        ("dp", Format::Binary),
        ("vga_r[3:0]", Format::Hex),
        ("vga_g[3:0]", Format::Hex),
        ("vga_b[3:0]", Format::Hex),
        ("hsync", Format::Binary),
        ("vsync", Format::Binary),
    ];
    s.group("Board pins", PINS.iter().map(|(n, f)| sig(n, *f)).collect());
    let (info, motctl) = register_filters();
    let info_file = side("botinfo.txt");
    write_atomic(&info_file, info.as_bytes())?;
    let motctl_file = side("motctl.txt");
    write_atomic(&motctl_file, motctl.as_bytes())?;
    let (fi, fm) = (s.filter(&info_file), s.filter(&motctl_file));
    s.group(
        "Bot registers",
        vec![
            sig("bot_upd", Format::Binary),
            sig("bot_locx[7:0]", Format::Decimal),
            sig("bot_locy[7:0]", Format::Decimal),
            (format!("{top}.bot_info[7:0]"), Format::Hex, Some(fi)),
            sig("bot_sensors[7:0]", Format::Binary),
            sig("bot_lmdist[7:0]", Format::Decimal),
            sig("bot_rmdist[7:0]", Format::Decimal),
            (format!("{top}.bot_motctl[7:0]"), Format::Hex, Some(fm)),
        ],
    );
    let in_bot = |path: &str| path.strip_prefix(plan.bot_path.as_str()).is_some_and(|r| r.starts_with('.'));
    for site in plan.cpus.iter().filter(|c| !(bot_model && in_bot(&c.path))) {
        let at = format!("{top}.user.{}", site.path);
        let debug = if probed { format!("{at}.core") } else { at.clone() };
        let labels = match sources.get(&site.path) {
            Some(map) => {
                let file = side(&format!("{}.labels.txt", site.path));
                write_atomic(&file, filter_text((0..4096u32).map(|a| (a, map.describe(a as u16))), 3).as_bytes())?;
                Some(s.filter(&file))
            }
            None => None,
        };
        let v = cpu_signals(&at, &debug, labels);
        s.group(&site.path, v);
    }
    write_atomic(&vcd.with_extension("gtkw"), s.text().as_bytes())
}

/// The `--break` specs: each CPU's breakpoints by instance path (addresses and port writes
/// apply to the team's CPUs; labels and lines to the CPU whose program has them), and the
/// conditions on the bot's samples.
fn breakpoints(
    specs: &[String],
    plan: &Plan,
    sources: &BTreeMap<String, SourceMap>,
) -> Result<(BTreeMap<String, Breaks>, Vec<BreakSpec>), String> {
    let bot_cpu = format!("{}.{}", plan.bot_path, botsim_core::board::plan::BOT_CPU_INSTANCE);
    let team: Vec<&str> = plan.cpus.iter().map(|c| c.path.as_str()).filter(|p| *p != bot_cpu).collect();
    let mut cpu: BTreeMap<String, Breaks> = BTreeMap::new();
    let mut bot = Vec::new();
    for text in specs {
        let spec = BreakSpec::parse(text)?;
        match &spec.kind {
            Break::Bot(_) => bot.push(spec),
            Break::Pc(_) | Break::Port(..) => {
                for p in &team {
                    cpu.entry(p.to_string()).or_default().add(&spec, sources.get(*p))?;
                }
            }
            Break::Label(_) | Break::Line(..) => {
                let mut found = false;
                for (path, map) in sources {
                    found |= cpu.entry(path.clone()).or_default().add(&spec, Some(map))?;
                }
                if !found {
                    return Err(format!(
                        "--break {text}: no CPU's program has it (the source is known for programs given with --program and for the bot's firmware)"
                    ));
                }
            }
        }
    }
    cpu.retain(|_, b| !b.is_empty());
    Ok((cpu, bot))
}

/// Where a waveform window opens or closes: after a bot sample, or at a time (cycles of the
/// 100 MHz clock are a time).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mark {
    Sample(u64),
    Time(u64),
}

/// `N` (sample N, as `botsim run` takes it), `Nc` (cycle N of 100 MHz) or a time with a unit.
fn parse_mark(s: &str, name: &str) -> Result<Mark, String> {
    if !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) {
        return s.parse().map(Mark::Sample).map_err(|_| format!("--{name} {s}: too large"));
    }
    parse_time(s).map(Mark::Time).map_err(|e| format!("--{name}: {e} or a sample number"))
}

/// Create the model of a built design on `world` with the programs of `roms` (the files are
/// read when the model is created, then removed).
fn load(
    library: &Path,
    world: &World,
    roms: &[Rom],
    host: Option<Box<Host>>,
    printing: &Printing,
) -> Result<BoardModel, String> {
    let dir = std::env::temp_dir();
    let stem = format!("botsim-{}-{}", std::process::id(), LOADS.fetch_add(1, std::sync::atomic::Ordering::Relaxed));
    let mut files = vec![(dir.join(format!("{stem}-world.mem")), world.to_mem(), "botsim_world".to_string())];
    for r in roms {
        files.push((dir.join(format!("{stem}-{}.mem", r.module)), r.image.to_mem(), wrapper::rom_plusarg(&r.module)));
    }
    let mut args = Vec::new();
    for (path, text, arg) in &files {
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        args.push(format!("+{arg}={}", path.display()));
    }
    let model = BoardModel::load(library, &args, host, printing);
    for (path, _, _) in &files {
        let _ = std::fs::remove_file(path);
    }
    model.map_err(|e| e.to_string())
}

/// How long a run counted in samples (--samples without --seconds) waits for the bot's next
/// sample: 1 s of board time, about 19 samples at hw timing.
const NO_SAMPLE_PS: u64 = 1_000_000_000_000;

/// A row of --pins: the time and the display's and the LEDs' pins after a change.
fn pins_row(time_ps: u64, (an, seg, dp, led): (u8, u8, u8, u16)) -> String {
    format!("{time_ps},{an:02X},{seg:02X},{dp},{led:04X}\n")
}

/// Models created by this process (their temporary files' names).
static LOADS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// Rounds of `--bench`.
const ROUNDS: usize = 7;

/// The board harness on a fresh model of `library`, the reset released from the start, for
/// `cycles` of 100 MHz; its events decoded as a run decodes them. Mcycles/s.
fn board_rate(
    library: &Path,
    world: &World,
    roms: &[Rom],
    host: Option<Box<Host>>,
    cycles: u64,
    fast_forward: bool,
) -> Result<f64, String> {
    let mut m = load(library, world, roms, host, &Printing::SILENT)?;
    m.set_inputs(false, 0, 0);
    m.fast_forward(if fast_forward { FastForward::Recorded } else { FastForward::Off });
    let mut buf = vec![RawEvent::default(); 4096];
    let mut display = Display::default();
    let t = Instant::now();
    loop {
        let (stop, n) = m.run(cycles * 10_000, u64::MAX, &mut buf);
        for e in buf[..n].iter().filter_map(Event::of) {
            if let Event::Display { time_ps, an, seg, dp } = e {
                display.pins(time_ps, an, seg, dp);
            }
        }
        if stop != Stop::BufferFull {
            break;
        }
    }
    Ok(cycles as f64 / t.elapsed().as_secs_f64() / 1e6)
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// `--bench --cpu iss`: the ISS board against the all-RTL board of the same design (and,
/// with `fast_forward`, the ISS board fast-forwarding), alternating rounds; each speed-up is
/// the median of the rounds' ratios.
fn bench_iss(
    [rtl, iss]: [&Path; 2],
    world: &World,
    roms: &[Rom],
    seconds: f64,
    json: bool,
    fast_forward: bool,
    host: &dyn Fn() -> Result<Option<Box<Host>>, String>,
) -> Result<(), String> {
    let cycles = (seconds * 1e8) as u64;
    let (mut r, mut i, mut f, mut ratios, mut ff_ratios) = (vec![], vec![], vec![], vec![], vec![]);
    for _ in 0..ROUNDS {
        let a = board_rate(rtl, world, roms, Some(Host::new(Vec::new(), false)), cycles, false)?;
        let b = board_rate(iss, world, roms, host()?, cycles, false)?;
        r.push(a);
        i.push(b);
        ratios.push(b / a);
        if fast_forward {
            let c = board_rate(iss, world, roms, host()?, cycles, true)?;
            f.push(c);
            ff_ratios.push(c / a);
        }
    }
    let (r, i, x) = (median(&mut r), median(&mut i), median(&mut ratios));
    let (f, fx) = (fast_forward.then(|| median(&mut f)), fast_forward.then(|| median(&mut ff_ratios)));
    if json {
        println!(
            "{}",
            serde_json::json!({"iss_board_mcycles_per_s": i, "rtl_board_mcycles_per_s": r, "speedup": x,
                "fast_forward_mcycles_per_s": f, "fast_forward_speedup": fx, "cycles": cycles, "rounds": ROUNDS})
        );
    } else {
        println!(
            "ISS board {i:.2} Mcycles/s, all-RTL board {r:.2} Mcycles/s (medians): {x:.2} x (median of {ROUNDS} side-by-side rounds of {cycles} cycles of 100 MHz; {:.3} x the board's real time)",
            i / 100.0
        );
        if let (Some(f), Some(fx)) = (f, fx) {
            println!(
                "with the fast-forward {f:.2} Mcycles/s of board time: {fx:.2} x the all-RTL board ({:.3} x the board's real time)",
                f / 100.0
            );
        }
    }
    Ok(())
}

/// `--bench`: both harnesses on fresh models of the same library, the reset released from
/// the start, alternating. The cost is the median of the rounds' ratios (each round
/// measures both side by side).
fn bench(
    library: &Path,
    world: &World,
    roms: &[Rom],
    seconds: f64,
    json: bool,
    host: &dyn Fn() -> Result<Option<Box<Host>>, String>,
) -> Result<(), String> {
    let cycles = (seconds * 1e8) as u64;
    let (mut board_rates, mut minimal_rates) = (Vec::new(), Vec::new());
    for _ in 0..ROUNDS {
        board_rates.push(board_rate(library, world, roms, host()?, cycles, false)?);
        let mut m = load(library, world, roms, host()?, &Printing::SILENT)?;
        m.set_inputs(false, 0, 0);
        let t = Instant::now();
        m.bench_minimal(cycles);
        minimal_rates.push(cycles as f64 / t.elapsed().as_secs_f64() / 1e6);
    }
    let mut costs: Vec<f64> = minimal_rates.iter().zip(&board_rates).map(|(m, b)| m / b - 1.0).collect();
    let cost = median(&mut costs);
    let best = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    // Noise on a shared machine only slows a run down: the best rates are the least disturbed.
    let best_cost = best(&minimal_rates) / best(&board_rates) - 1.0;
    let (b, m) = (median(&mut board_rates), median(&mut minimal_rates));
    if json {
        println!(
            "{}",
            serde_json::json!({"board_mcycles_per_s": b, "minimal_mcycles_per_s": m, "board_cost": cost, "board_cost_best": best_cost, "cycles": cycles, "rounds": ROUNDS})
        );
    } else {
        println!(
            "board harness {b:.2} Mcycles/s, minimal harness {m:.2} Mcycles/s (medians): the board harness costs {:+.1} % (median of {ROUNDS} side-by-side rounds of {cycles} cycles of 100 MHz; best against best {:+.1} %)",
            cost * 100.0,
            best_cost * 100.0
        );
    }
    Ok(())
}
