//! `botsim run`: run BotSim 2.0 with a motor script or a closed-loop driver. In layers: the
//! arguments (here), the resolved [`plan`], the [`sample_loop`], the [`outputs`].

mod live;
mod outputs;

mod plan;
mod sample_loop;
mod watch;

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

use botsim::files::write_atomic;
use botsim::firmware::{SOURCE, SOURCE_PATH};
use botsim::kcpsm6::image::Format;
use botsim::kcpsm6::source::SourceMap;
use botsim::sim::lockstep::Lockstep;
use botsim::sim::rtl::{Point, VcdWindow};
use botsim::{IssBot, RtlBot, World, PS_PER_CYCLE};
use botsim_core::board::gtkw::{Format as Radix, SaveFile, View};
use botsim_core::debug::{cpu_signals, register_filters, sample_state, BreakSpec, Breaks};

use crate::cli::args::{BackendKind, DriverKind, FirmwareArgs};
use outputs::Taken;
use plan::Plan;
use sample_loop::Engine;
use watch::Watched;

/// Run BotSim 2.0 (the RTL under Verilator, or the ISS with --backend) on a world, driven by a
/// motor script or a driver.
///
/// With --motors, MotCtl_in follows the script: the first segment's value from reset, each
/// later value applied right after an upd_sysregs pulse, so main-loop iteration k sees the
/// segment that covers k. With --driver, the driver reads each snapshot and sets MotCtl for the
/// next iteration. Sample 0 is the register dump after reset.
#[derive(clap::Args)]
#[command(after_help = "Examples:
  botsim run --timing fast --driver line-follow --frames frames --frame-every 30
  botsim run --timing fast --driver line-follow --png path.png --trace-csv trace.csv
  botsim run --timing fast --motors drive.txt --vcd bot.vcd --trace-from 10 --trace-to 12
  botsim run --map world_map_lr.txt --program bot_pgm.hex --samples 50 --json
  botsim run --backend iss --motors drive.txt --samples 1000 --trace-csv trace.csv
  botsim run --timing fast --samples 3 --cpu-trace t.txt
  botsim run --timing fast --driver line-follow --break bot=blocked --vcd stop.vcd
  botsim run --live   (drive the bot from the page: open the address it prints)

Motor script lines: '<MOTCTL> <COUNT>', e.g. '33 15' or 'forward 15'; '#' starts a comment.
Trace windows: a number of samples (e.g. 10), or of cycles with a 'c' suffix (e.g. 2500000c).")]
pub struct Args {
    /// Program: .psm (assembled with the constants below), .hex, .mem or a ROM .v
    /// [default: the built-in BotSim firmware]
    #[arg(long, value_name = "FILE")]
    program: Option<PathBuf>,
    /// World: .txt, .coe, .mem or .png [default: the built-in course]
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    /// Motor script
    #[arg(long, value_name = "FILE", conflicts_with = "driver")]
    motors: Option<PathBuf>,
    /// A closed-loop driver instead of a script
    #[arg(long, value_enum, value_name = "NAME")]
    driver: Option<DriverKind>,
    /// Main-loop iterations to run [default: the script's total; with a driver, until it is
    /// done (at most 50000); else 20]
    #[arg(long, value_name = "N")]
    samples: Option<u64>,
    #[command(flatten)]
    firmware: FirmwareArgs,
    /// Write one CSV row per upd_sysregs pulse
    #[arg(long, value_name = "FILE")]
    trace_csv: Option<PathBuf>,
    /// Write one JSON object per upd_sysregs pulse (with decoded fields)
    #[arg(long, value_name = "FILE")]
    trace_json: Option<PathBuf>,
    /// Write a VCD waveform (of the whole run, or of the --trace-from/--trace-to window)
    #[arg(long, value_name = "FILE")]
    vcd: Option<PathBuf>,
    /// Start the waveform at this sample (or cycle, with a 'c' suffix)
    #[arg(long, value_name = "N|Nc", requires = "vcd")]
    trace_from: Option<Point>,
    /// End the waveform after this sample (or at this cycle, with a 'c' suffix)
    #[arg(long, value_name = "N|Nc", requires = "vcd")]
    trace_to: Option<Point>,
    /// Draw the world and the bot's path into a PNG
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,
    /// Save course-display frames (640 x 480 PNG) into this folder
    #[arg(long, value_name = "DIR")]
    frames: Option<PathBuf>,
    /// With --frames: one frame every N samples (and the last)
    #[arg(long, value_name = "N", default_value_t = 15, requires = "frames")]
    frame_every: u64,
    /// Print the summary as JSON
    #[arg(long)]
    json: bool,
    /// Print only errors (no summary, no progress bar)
    #[arg(short, long)]
    quiet: bool,
    /// What simulates the bot: rtl (Verilator), iss (the instruction-set simulator with
    /// cycle-timed models, ~80 x faster, no waveform), or lockstep (both, every snapshot and
    /// port access compared)
    #[arg(long, value_enum, value_name = "rtl|iss|lockstep", default_value = "rtl")]
    backend: BackendKind,
    /// Write a source-level trace of the bot's CPU: one line per instruction (cycle, time, PC,
    /// label+offset, the .psm file:line, the instruction, registers written, port accesses,
    /// flags), and beside it FILE's `.profile.txt`, the cycles spent under each label. Runs
    /// the bot on the ISS (the same results, cycle for cycle)
    #[arg(long, value_name = "FILE")]
    cpu_trace: Option<PathBuf>,
    /// With --cpu-trace: trace from this sample's iteration (or cycle, with a 'c' suffix)
    #[arg(long, value_name = "N|Nc", requires = "cpu_trace")]
    cpu_trace_from: Option<Point>,
    /// With --cpu-trace: trace to the end of this sample's iteration (or to this cycle)
    #[arg(long, value_name = "N|Nc", requires = "cpu_trace")]
    cpu_trace_to: Option<Point>,
    /// Stop the run at a breakpoint and say where: pc=03A, label=NAME or line=FILE.psm:N (in
    /// the bot's program), port=0A or port=0A:18 (an OUTPUT of the firmware to the port, of
    /// the value), bot=blocked, bot=off-line or bot=sensors:XX (at the first sample that
    /// shows it). With --vcd or --cpu-trace, the run is repeated to the stop to write them
    /// over the --break-window before it. Runs the bot on the ISS
    #[arg(long = "break", value_name = "WHAT")]
    breaks: Vec<String>,
    /// With --break: how much before the stop the waveform and the trace cover, in cycles
    /// [default: 100000, 1 ms]
    #[arg(long, value_name = "CYCLES", requires = "breaks")]
    break_window: Option<u64>,
    /// With --vcd: the largest waveform to write, e.g. 500M or 8G [default: 2G]; a run whose
    /// waveform grows past it stops, removes it and says so
    #[arg(long, value_name = "SIZE", requires = "vcd")]
    vcd_max: Option<String>,
    #[command(flatten)]
    live: crate::cli::live::LiveArgs,
}

impl Args {
    /// Whether `--live` was given.
    pub(crate) fn is_live(&self) -> bool {
        self.live.live
    }
}

pub fn run(args: Args) -> Result<(), String> {
    if args.live.live {
        return live::run(&args);
    }
    run_with_frame(args, None)
}

/// How far a waveform and a CPU trace written for a breakpoint go on past the stop (cycles):
/// the stopping instruction and two more; after a bot condition, the firmware's answer to
/// that sample.
const CPU_BREAK_AFTER: u64 = 4;
const BOT_BREAK_AFTER: u64 = 10_000;

/// Where a breakpoint stopped the first pass.
struct Stop {
    cycle: u64,
    /// The sample of the iteration it stopped in (a CPU breakpoint), or that showed it (a bot
    /// condition): the outputs end with the sample before it, or with it.
    sample: u64,
    bot: bool,
    message: String,
}

/// What one pass over the run does besides the plan's outputs.
#[derive(Default)]
struct Pass {
    /// Run the bot on the watched ISS with these breakpoints (and the --cpu-trace window).
    watch: Option<(Breaks, Vec<BreakSpec>)>,
    trace: Option<(Option<Point>, Option<Point>)>,
    /// Find the stop only: no outputs, nothing said.
    finding: bool,
    /// Write the plan's outputs (and the waveform) of this pass.
    outputs: bool,
    /// The waveform's window instead of --trace-from/--trace-to.
    window: Option<(Point, Point)>,
    /// The outputs keep the samples before this one.
    keep_below: Option<u64>,
}

/// `botsim frame`: a run, then the course display at its end.
pub fn run_with_frame(args: Args, end_frame: Option<PathBuf>) -> Result<(), String> {
    // The bot's program as source: its breakpoints and trace lines name its lines.
    let map = source_map(&args)?;
    let mut cpu_breaks = Breaks::default();
    let mut bot_breaks = Vec::new();
    for text in &args.breaks {
        let spec = BreakSpec::parse(text)?;
        if spec.bot().is_some() {
            bot_breaks.push(spec);
        } else if !cpu_breaks.add(&spec, map.as_ref())? {
            return Err(format!("--break {text}: the bot's program has no such label or line"));
        }
    }
    let debugging = args.cpu_trace.is_some() || !args.breaks.is_empty();
    if debugging && args.backend != BackendKind::Rtl && args.backend != BackendKind::Iss {
        return Err("--cpu-trace and --break run the bot on the ISS: --backend lockstep cannot".into());
    }
    if debugging && args.backend == BackendKind::Rtl && args.vcd.is_none() && !args.quiet && !args.json {
        eprintln!(
            "note: --cpu-trace and --break run the bot on the ISS (the same results as the RTL, cycle for cycle)"
        );
    }
    let trace = args.cpu_trace.as_ref().map(|_| (args.cpu_trace_from, args.cpu_trace_to));
    let watch = (!cpu_breaks.is_empty() || !bot_breaks.is_empty()).then_some((cpu_breaks, bot_breaks));
    match (watch, args.vcd.is_some() || args.cpu_trace.is_some()) {
        (None, _) if args.cpu_trace.is_none() => {
            pass(&args, end_frame, Pass { outputs: true, ..Pass::default() }).map(|_| ())
        }
        (None, _) => {
            // The trace from the watched ISS; the outputs from it too, or from the RTL when a
            // waveform is asked for (the two are equal, cycle for cycle).
            let with_vcd = args.vcd.is_some();
            let p = Pass { watch: Some(Default::default()), trace, outputs: !with_vcd, ..Pass::default() };
            pass(&args, end_frame.clone(), p)?;
            if with_vcd {
                pass(&args, end_frame, Pass { outputs: true, ..Pass::default() })?;
            }
            Ok(())
        }
        (Some(w), false) => {
            pass(&args, end_frame, Pass { watch: Some(w), outputs: true, ..Pass::default() }).map(|_| ())
        }
        (Some(w), true) => {
            // Find the stop; then the same run, which is deterministic, to the stop with the
            // waveform and the trace over the window before it.
            let found = pass(&args, None, Pass { watch: Some(w), finding: true, ..Pass::default() })?;
            let Some(stop) = found else {
                if !args.quiet && !args.json {
                    eprintln!("note: no breakpoint was hit");
                }
                return pass(
                    &args,
                    end_frame,
                    Pass { trace, outputs: true, watch: trace.map(|_| Default::default()), ..Pass::default() },
                )
                .map(|_| ());
            };
            let from = Point::Cycle(stop.cycle.saturating_sub(args.break_window.unwrap_or(100_000)));
            let to = Point::Cycle(stop.cycle + if stop.bot { BOT_BREAK_AFTER } else { CPU_BREAK_AFTER });
            // A CPU breakpoint stops in the iteration of a sample, a bot condition at one.
            let keep_below = Some(if stop.bot { stop.sample + 1 } else { stop.sample });
            let (window, run_to) = (Some((from, to)), Some(stop.sample));
            if args.cpu_trace.is_some() {
                let outputs = args.vcd.is_none();
                let p = Pass {
                    watch: Some(Default::default()),
                    trace: Some((Some(from), Some(to))),
                    outputs,
                    keep_below,
                    window,
                    ..Pass::default()
                };
                pass_to(&args, end_frame.clone(), p, run_to)?;
            }
            if args.vcd.is_some() {
                pass_to(&args, end_frame, Pass { outputs: true, window, keep_below, ..Pass::default() }, run_to)?;
            }
            if !args.json {
                eprintln!("{}", stop.message);
            }
            Ok(())
        }
    }
}

/// The bot's program as source, when it has one: the built-in firmware, or a `--program`
/// .psm (assembled as the run assembles it).
fn source_map(args: &Args) -> Result<Option<SourceMap>, String> {
    let fw = args.firmware.firmware();
    match &args.program {
        None => {
            let prog = fw.program(0).map_err(|d| d.to_string())?;
            Ok(Some(SourceMap::of_source(&prog, std::path::Path::new(SOURCE_PATH), SOURCE)))
        }
        Some(p) if Format::of(p) == Some(Format::Psm) => {
            let opts = botsim::kcpsm6::asm::Options { defines: fw.defines(), ..Default::default() };
            let prog = botsim::kcpsm6::asm::assemble_file(p, &opts).map_err(|d| d.errors_text())?;
            Ok(Some(SourceMap::of(&prog)))
        }
        Some(_) => Ok(None),
    }
}

fn pass(args: &Args, end_frame: Option<PathBuf>, p: Pass) -> Result<Option<Stop>, String> {
    pass_to(args, end_frame, p, None)
}

/// One pass over the run; `run_to`: the last sample to run (a stop's).
fn pass_to(args: &Args, end_frame: Option<PathBuf>, p: Pass, run_to: Option<u64>) -> Result<Option<Stop>, String> {
    let mut plan = Plan::resolve(args, if p.outputs { end_frame } else { None })?;
    if let Some(n) = run_to {
        plan.samples = plan.samples.min(n);
    }
    if let (Some(w), Some((from, to))) = (plan.waveform.as_mut(), p.window) {
        (w.from, w.to) = (Some(from), Some(to));
    }
    if !p.outputs {
        plan.waveform = None;
        plan.frames = None;
    }
    let quiet = args.quiet || p.finding || !p.outputs;
    // Frames show the world as read through the RTL video port, scanned once in a model of
    // its own (so no sample of the run is skipped, whatever the backend).
    let video = match plan.frames.is_some() || plan.end_frame.is_some() {
        false => None,
        true => {
            let mut scan = RtlBot::builder()
                .program(plan.image.clone())
                .world(plan.world.clone())
                .build()
                .map_err(|e| e.to_string())?;
            Some(World::from_cells(&scan.scan_video().map_err(|e| e.to_string())?))
        }
    };
    if let Some(f) = &plan.frames {
        std::fs::create_dir_all(&f.dir)
            .map_err(|e| format!("{}: error: cannot create folder: {e}", f.dir.display()))?;
    }
    let bot_breaks = p.watch.as_ref().map(|(_, b)| b.clone()).unwrap_or_default();
    let mut engine = match p.watch {
        Some((breaks, _)) => {
            let bot = IssBot::new(&plan.image, plan.world.clone()).map_err(|e| e.to_string())?;
            let mut w = Watched::new(bot, breaks, source_map(args)?);
            if let (Some(file), Some((from, to))) = (&args.cpu_trace, p.trace) {
                w.trace(file, from, to)?;
            }
            prepare(Engine::Watched(Box::new(w)), &plan)
        }
        None => engine(&plan)?,
    };
    let mut window = plan.waveform.as_ref().map(|w| VcdWindow::new(w.path.clone(), w.from, w.to));

    let progress = (!quiet && !args.json && std::io::stderr().is_terminal() && plan.samples > 50).then(|| {
        let bar = indicatif::ProgressBar::new(plan.samples + 1);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} samples {elapsed_precise} ({per_sec}) {msg}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    });
    // Ctrl-C stops the run between two checks (at most ~1 M cycles apart); the outputs are
    // then written for the samples taken, as at a normal end.
    botsim::interrupt::catch();
    let start = Instant::now();
    let mut taken = Taken::default();
    let (samples, frames) = (plan.samples, plan.frames.as_ref().zip(video.as_ref()));
    let driver = &mut plan.driver;
    let threshold = plan.firmware.threshold;
    let mut bot_stop: Option<Stop> = None;
    let vcd_max = args.vcd_max.as_deref().map_or(Ok(crate::cli::size::VCD_MAX), crate::cli::size::parse_size)?;
    let vcd_path = window.as_ref().map(|w| w.path().to_path_buf());
    let vcd_part = window.as_ref().map(|w| w.part().to_path_buf());
    let looped = sample_loop::run(&mut engine, window.as_mut(), samples, |k, s| {
        if let (Some(v), Some(part)) = (&vcd_path, &vcd_part) {
            let size = std::fs::metadata(part).map_or(0, |m| m.len());
            if size > vcd_max {
                return Err(format!(
                    "{}: the waveform passed {} MB in sample {k} and was removed: ask for a window (--trace-from/--trace-to) or allow more (--vcd-max)",
                    v.display(),
                    vcd_max >> 20
                ));
            }
        }
        let m = driver.next(s);
        if let Some(b) = bot_breaks.iter().find(|b| b.hit(taken.snapshots.last(), s, threshold)) {
            let message = format!("stopped by --break {}: {}", b.text, sample_state(s));
            bot_stop = Some(Stop { cycle: s.cycle, sample: s.sample, bot: true, message });
        }
        taken.json.push_str(&crate::cli::rows::json_row(s, m));
        taken.snapshots.push(*s);
        if let Some((f, video)) = frames {
            if k % f.every == 0 || k == samples || driver.finished() {
                write_atomic(
                    &f.dir.join(format!("frame_{k:06}.png")),
                    &botsim::render::display::frame(video, Some(s)),
                )?;
                taken.frames_written += 1;
            }
        }
        if let Some(b) = &progress {
            b.set_position(k + 1);
        }
        Ok((m, driver.finished() || bot_stop.is_some()))
    });
    // A run that failed leaves no part of a waveform behind (the window removes its own).
    let stopped = looped?;
    // A breakpoint of the firmware: where, and what the run writes up to it.
    let cpu_stop = match (&stopped, engine.watched()) {
        (Some(i), Some(w)) if i.by_break => w.stop_message().zip(w.hit.clone()).map(|(message, h)| Stop {
            cycle: h.cycle,
            sample: h.sample,
            bot: false,
            message,
        }),
        _ => None,
    };
    let stop = cpu_stop.or(bot_stop);
    if p.finding {
        return Ok(stop);
    }
    let mut written = match engine.watched() {
        Some(w) => w.finish()?,
        None => Vec::new(),
    };
    let waveform_written = match (&mut window, &mut engine) {
        (Some(w), Engine::Rtl(bot)) => Some(w.finish(bot).map_err(|e| match e {
            botsim::Error::Waveform(why) => format!("{}: error: cannot write file: {why}", w.path().display()),
            e => e.to_string(),
        })?),
        _ => None,
    };
    let totals = outputs::Totals { cycles: engine.backend().cycle(), wall_seconds: start.elapsed().as_secs_f64() };
    drop(engine);
    if let Some(b) = progress {
        b.finish_and_clear();
    }
    if !p.outputs {
        return Ok(stop);
    }
    if let Some(end) = p.keep_below {
        taken.snapshots.retain(|s| s.sample < end);
    }
    let end_frame = video
        .as_ref()
        .filter(|_| plan.end_frame.is_some())
        .map(|v| botsim::render::display::frame(v, taken.snapshots.last()));
    written.extend(outputs::write(&plan, &taken, end_frame.as_deref())?);
    match (waveform_written, &window) {
        (Some(true), Some(w)) => {
            written.push(w.path().to_path_buf());
            let view = p.window.map(|(from, to)| view_of(from, to));
            written.push(save_file(w.path(), args, view)?);
        }
        (Some(false), Some(w)) => {
            eprintln!("{}: warning: the trace window was never reached; no waveform written", w.path().display())
        }
        _ => {}
    }
    match (&stopped, &stop) {
        (_, Some(s)) if p.window.is_none() && !args.json => eprintln!("{}", s.message),
        (Some(i), None) => eprintln!(
            "interrupted: stopped in sample {} at cycle {}; the outputs hold samples 0-{}",
            i.sample,
            i.cycle,
            i.sample.saturating_sub(1)
        ),
        _ => {}
    }
    let status = plan.driver.status();
    if args.json {
        if let Some(s) = outputs::summary_json(&taken, &totals, &status, &written) {
            println!("{s}");
        }
    } else if !args.quiet {
        if let Some(s) = outputs::summary_text(&taken, &totals, &status, &written) {
            print!("{s}");
        }
    }
    Ok(stop)
}

/// The save file's view of a window of cycles: its whole span, the marker at its end.
fn view_of(from: Point, to: Point) -> View {
    let ps = |p: Point| match p {
        Point::Cycle(c) => c * PS_PER_CYCLE,
        Point::Sample(_) => 0,
    };
    View { start_ps: ps(from), end_ps: ps(to), marker_ps: Some(ps(to).saturating_sub(CPU_BREAK_AFTER * PS_PER_CYCLE)) }
}

/// The GTKWave save file beside a `botsim run` waveform (`<vcd>.gtkw`): the bot's ports and
/// registers, its CPU with the debug signals (the instruction's text, the status, the
/// registers) and its address as label+offset; the filter files beside it.
fn save_file(vcd: &std::path::Path, args: &Args, view: Option<View>) -> Result<PathBuf, String> {
    let side = |suffix: &str| {
        let name = vcd.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        vcd.with_file_name(format!("{name}.{suffix}"))
    };
    let mut s = SaveFile::new(&std::path::absolute(vcd).unwrap_or_else(|_| vcd.to_path_buf()));
    if let Some(v) = view {
        s.view(v);
    }
    let (info, motctl) = register_filters();
    let (info_file, motctl_file) = (side("botinfo.txt"), side("motctl.txt"));
    write_atomic(&info_file, info.as_bytes())?;
    write_atomic(&motctl_file, motctl.as_bytes())?;
    let (fi, fm) = (s.filter(&info_file), s.filter(&motctl_file));
    let top = "TOP.bot";
    let sig = |n: &str, f: Radix| (format!("{top}.{n}"), f, None);
    s.group(
        "Bot",
        vec![
            sig("clk", Radix::Binary),
            sig("reset", Radix::Binary),
            (format!("{top}.MotCtl_in[7:0]"), Radix::Hex, Some(fm)),
            sig("upd_sysregs", Radix::Binary),
            sig("LocX_reg[7:0]", Radix::Decimal),
            sig("LocY_reg[7:0]", Radix::Decimal),
            (format!("{top}.BotInfo_reg[7:0]"), Radix::Hex, Some(fi)),
            sig("Sensors_reg[7:0]", Radix::Binary),
            sig("LMDist_reg[7:0]", Radix::Decimal),
            sig("RMDist_reg[7:0]", Radix::Decimal),
        ],
    );
    let cpu = format!("{top}.{}", botsim_core::frontend::plan::BOT_CPU_INSTANCE);
    let labels = match source_map(args)? {
        Some(map) => {
            let file = side("labels.txt");
            let text = botsim_core::board::gtkw::filter_text((0..4096u32).map(|a| (a, map.describe(a as u16))), 3);
            write_atomic(&file, text.as_bytes())?;
            Some(s.filter(&file))
        }
        None => None,
    };
    s.group("bot_pgm (the bot's KCPSM6)", cpu_signals(&cpu, &cpu, labels));
    let path = vcd.with_extension("gtkw");
    write_atomic(&path, s.text().as_bytes())?;
    Ok(path)
}

/// The backend the plan asks for, with the program, world, initial motors and the firmware
/// timing's update budget.
fn engine(plan: &Plan) -> Result<Engine, String> {
    let engine = match plan.backend {
        BackendKind::Rtl => Engine::Rtl(
            RtlBot::builder()
                .debug(plan.waveform.is_some())
                .firmware(plan.firmware)
                .program(plan.image.clone())
                .world(plan.world.clone())
                .build()
                .map_err(|e| e.to_string())?,
        ),
        BackendKind::Iss => {
            Engine::Other(Box::new(IssBot::new(&plan.image, plan.world.clone()).map_err(|e| e.to_string())?))
        }
        BackendKind::Lockstep => {
            Engine::Other(Box::new(Lockstep::new(&plan.image, plan.world.clone()).map_err(|e| e.to_string())?))
        }
    };
    Ok(prepare(engine, plan))
}

/// The engine with the plan's update budget and initial motors.
fn prepare(mut engine: Engine, plan: &Plan) -> Engine {
    let bot = engine.backend();
    bot.set_update_budget(plan.firmware.timing.update_budget());
    bot.set_motors(plan.initial);
    engine
}
