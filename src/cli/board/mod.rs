//! `botsim board`: simulate a student's whole board design with the world in the loop.

mod bench;
mod breaks;
mod check;
mod devices;
mod live;
mod prepare;
mod progress;
mod report;
mod session;

use std::path::PathBuf;

use botsim_core::board::stimulus::parse_time;
use botsim_core::PS_PER_CYCLE;
use breaks::{BreakStop, Stopped};

use crate::cli::args::FirmwareArgs;

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
    /// A stimulus file: one `TIME press NAME [DURATION]`, `TIME switches HEX`, `TIME key NAME
    /// [DURATION]`, `TIME uart "TEXT"` or `TIME tilt X Y Z` per line
    #[arg(long, value_name = "FILE")]
    stimulus: Option<PathBuf>,
    /// Add a random stimulus of the inputs the design has pins for: presses of its buttons,
    /// one CPU reset in the middle of the run, switch changes, and text to its UART, keys
    /// and tilts where it has those; the same SEED gives the same events (the run's first
    /// lines list them)
    #[arg(long, value_name = "SEED")]
    random_stimulus: Option<u64>,
    /// The board's tilt from power-up, in g, as its accelerometer measures it [default: 0,0,1,
    /// lying flat]
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    tilt: Option<String>,
    /// The USB-UART's rate in baud [default: measured from what the design sends, 115200
    /// before it has sent anything]
    #[arg(long, value_name = "BAUD")]
    uart_baud: Option<u32>,
    /// What the design sent on the USB-UART (RsTx), byte for byte
    #[arg(long, value_name = "FILE")]
    uart: Option<PathBuf>,
    /// The board's sound (ampPWM averaged, silent while ampSD is 0) as a 48 kHz WAV file
    #[arg(long, value_name = "FILE")]
    audio: Option<PathBuf>,
    /// A parameter of the top: NAME=VALUE (e.g. SIMULATE=1)
    #[arg(long, value_name = "NAME=VALUE")]
    param: Vec<String>,
    /// An include folder
    #[arg(long, value_name = "DIR")]
    include: Vec<PathBuf>,
    /// Tie off a module botsim has no model of
    #[arg(long, value_name = "MODULE")]
    stub: Vec<String>,
    /// A memory core committed without its configuration: the .coe that holds its contents
    /// (its depth and width follow), when the file is not named after the module and is not
    /// the one that fits and whose name is the closest
    #[arg(long, value_name = "MODULE=FILE")]
    memory: Vec<String>,
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
    /// Every change of the lines between the FPGA and the board's peripherals, one CSV row
    /// each (time_ps, then RsTx, ampPWM, ampSD, RsRx, PS2_CLK, PS2_DATA, aclSCK, aclMOSI,
    /// aclMISO, aclSS as 0 or 1, as on the board: idle where the design has no such pin)
    #[arg(long, value_name = "FILE")]
    lines: Option<PathBuf>,
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
    /// Of a design's several bots (a game's hero and monster), the one the options about the
    /// bot mean (--trace-csv's own file, --break on the bot, --stop-at-line-end, the summary's
    /// samples): its instance path as the run's first line lists them (`nexys4fpga.SYS.hero`
    /// or `SYS.hero`) [default: the first listed]. The others' traces go beside its own.
    #[arg(long, value_name = "PATH")]
    bot_at: Option<String>,
    /// With --cpu iss --bot model the board skips the periods in which all the run records
    /// repeats itself (the same results, edge for edge); this simulates every edge
    #[arg(long)]
    no_fast_forward: bool,
    /// Evaluate the design at both edges of the clock even where the build found that nothing
    /// happens at the falling ones (the same results, at twice the evaluations; a waveform
    /// always gets both)
    #[arg(long)]
    every_edge: bool,
    /// Measure the run instead of saving it: the run as the other options make it (its stop,
    /// stimulus, records and fast-forward; 1 s of board time by default), three times, each
    /// beside the same run on the all-RTL board (--cpu rtl --bot rtl); it prints both in
    /// Mcycles/s of the 100 MHz clock, the ratio, how much was skipped and what kept it from
    /// skipping more. With --cpu rtl: the board harness against a minimal C++ harness of the
    /// same built design over --seconds [default: 0.05]
    #[arg(long)]
    bench: bool,
    /// Check this run against the all-RTL board (--cpu rtl --bot rtl, every edge under
    /// Verilator): after the run, the same run on both boards over the same time, every record
    /// compared byte for byte (each bot's samples, the display, its pins, the peripherals'
    /// lines, the UART, every 8th VGA frame or every --frame-every-th, what the design
    /// printed); says the first that differs (which, when, both values) and exits 1, or that
    /// all are equal
    #[arg(long, conflicts_with_all = ["live", "bench", "build_only", "breaks"])]
    check: bool,
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
    #[command(flatten)]
    live: crate::cli::live::LiveArgs,
    /// Print the summary as JSON
    #[arg(long)]
    json: bool,
    /// Print nothing but errors
    #[arg(short, long)]
    quiet: bool,
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
    let end_cycle = (stop + after) / PS_PER_CYCLE + 1;
    again.seconds = Some(end_cycle as f64 * 1e-8);
    again.samples = None;
    let from = format!("{}c", (stop.saturating_sub(window)) / PS_PER_CYCLE);
    if again.trace_from.is_none() && again.vcd.is_some() {
        again.trace_from = Some(from.clone());
    }
    if again.cpu_trace_from.is_none() && again.cpu_trace.is_some() {
        again.cpu_trace_from = Some(from);
    }
    run_once(again).map(|_| ())
}

/// The longest run `--seconds` allows without `--long`, in seconds of board time.
const LONG_RUN_S: f64 = 600.0;

/// How far a waveform and CPU trace written for a breakpoint go on past the stop.
const CPU_BREAK_AFTER_PS: u64 = 40_000;
const BOT_BREAK_AFTER_PS: u64 = 100_000_000;

/// One run of the board; the time of the stop when a breakpoint stopped it.
fn run_once(a: Args) -> Result<Stopped, String> {
    let p = prepare::prepare(&a)?;
    if a.build_only {
        return Ok(None);
    }
    if a.bench {
        return bench::run(&a, &p).map(|_| None);
    }
    if a.live.live {
        return live::run(&a, &p).map(|_| None);
    }
    let outcome = session::simulate(&a, &p)?;
    let stopped = report::report(&a, &p, outcome)?;
    if a.check {
        check::run(&a, &p)?;
    }
    Ok(stopped)
}

impl Args {
    /// Say a line of the run's account on standard error (not with --quiet or --json).
    fn say(&self, s: String) {
        if !self.quiet && !self.json {
            eprintln!("{s}");
        }
    }

    /// Say a warning about the design on standard error: also with --json (whose summary
    /// goes to standard output), not with --quiet.
    fn warn(&self, w: &str) {
        if !self.quiet {
            eprintln!("warning: {w}");
        }
    }
}
