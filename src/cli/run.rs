//! `botsim run`: run the BotSim RTL with a motor script or a closed-loop driver.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use botsim::backend::Backend;
use botsim::driver::{Driver, LineFollower, ScriptDriver};
use botsim::files::write_atomic;
use botsim::firmware::{Compat, Firmware, Timing};
use botsim::iss_backend::IssBot;
use botsim::kcpsm6::asm::{Options, RomSize};
use botsim::kcpsm6::image::Format;
use botsim::lockstep::Lockstep;
use botsim::render::{path_picture, PathStyle};
use botsim::script::MotorScript;
use botsim::world::World;
use botsim::{BotSim, Error, MotCtl, Snapshot};

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
    /// A closed-loop driver instead of a script: line-follow (the course's black-line follower)
    #[arg(long, value_name = "NAME", value_parser = ["line-follow"])]
    driver: Option<String>,
    /// Main-loop iterations to run [default: the script's total; with a driver, until it is
    /// done (at most 50000); else 20]
    #[arg(long, value_name = "N")]
    samples: Option<u64>,
    /// Samples per move or 45-degree turn [default: 15]
    #[arg(long, value_name = "T")]
    threshold: Option<u8>,
    /// Sample interval: hw (~50 ms at 100 MHz, as on the board) or fast (~2,000 clocks)
    #[arg(long, value_name = "hw|fast", value_parser = parse_timing)]
    timing: Option<Timing>,
    /// Behave as the 2014 BotSim 2.0 program (its facing-SW right-front cell)
    #[arg(long, value_name = "botsim20", value_parser = parse_compat)]
    compat: Option<Compat>,
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
    #[arg(long, value_name = "N|Nc", value_parser = parse_point, requires = "vcd")]
    trace_from: Option<Point>,
    /// End the waveform after this sample (or at this cycle, with a 'c' suffix)
    #[arg(long, value_name = "N|Nc", value_parser = parse_point, requires = "vcd")]
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
    #[arg(long, value_name = "rtl|iss|lockstep", default_value = "rtl", value_parser = ["rtl", "iss", "lockstep"])]
    backend: String,
}

/// What runs the bot: the RTL (which can also write a waveform), or another [`Backend`].
enum Engine {
    Rtl(BotSim),
    Other(Box<dyn Backend>),
}

impl Engine {
    fn backend(&mut self) -> &mut dyn Backend {
        match self {
            Engine::Rtl(b) => b,
            Engine::Other(b) => b.as_mut(),
        }
    }

    /// The RTL model, for the waveform window (which needs the RTL backend).
    fn rtl(&mut self) -> Result<&mut BotSim, String> {
        match self {
            Engine::Rtl(b) => Ok(b),
            Engine::Other(_) => Err("error: a waveform needs the RTL backend (--backend rtl)".into()),
        }
    }
}

/// A point of a trace window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Point {
    Sample(u64),
    Cycle(u64),
}

fn parse_point(s: &str) -> Result<Point, String> {
    let bad = || format!("expected a sample number or a cycle number with a 'c' suffix, found '{s}'");
    match s.strip_suffix('c') {
        Some(c) => c.parse().map(Point::Cycle).map_err(|_| bad()),
        None => s.parse().map(Point::Sample).map_err(|_| bad()),
    }
}

fn parse_timing(s: &str) -> Result<Timing, String> {
    Timing::parse(s).ok_or_else(|| format!("expected hw or fast, found '{s}'"))
}

fn parse_compat(s: &str) -> Result<Compat, String> {
    match s {
        "botsim20" => Ok(Compat::BotSim20),
        _ => Err(format!("the only compatibility mode is botsim20, found '{s}'")),
    }
}

/// The CSV header of `--trace-csv` (the contract's columns).
pub const CSV_HEADER: &str = "sample,cycle,loc_x,loc_y,bot_info,sensors,lm_dist,rm_dist";

fn csv_row(s: &Snapshot) -> String {
    let r = &s.regs;
    format!(
        "{},{},{},{},{},{},{},{}\n",
        s.sample, s.cycle, r.loc_x, r.loc_y, r.bot_info, r.sensors, r.lm_dist, r.rm_dist
    )
}

fn json_row(s: &Snapshot, motctl: MotCtl) -> String {
    let r = &s.regs;
    let v = serde_json::json!({
        "sample": s.sample, "cycle": s.cycle,
        "loc_x": r.loc_x, "loc_y": r.loc_y, "bot_info": r.bot_info, "sensors": r.sensors,
        "lm_dist": r.lm_dist, "rm_dist": r.rm_dist,
        "orientation": s.orientation().name(), "heading_degrees": s.orientation().degrees(),
        "movement": s.movement().name(),
        "prox_left": s.sensors().prox_left(), "prox_right": s.sensors().prox_right(),
        "on_line": s.sensors().on_line(),
        "next_motctl": motctl.0,
    });
    format!("{v}\n")
}

/// Fail early on an output path that cannot be written (before a long run).
fn check_writable(path: &Path) -> Result<(), String> {
    write_atomic(path, b"")
        .and_then(|()| std::fs::remove_file(path).map_err(|e| format!("{}: error: {e}", path.display())))
}

/// The temporary name a file is written under until it is complete.
fn part_name(p: &Path) -> PathBuf {
    p.with_file_name(format!(".{}.part", p.file_name().unwrap_or_default().to_string_lossy()))
}

pub fn run(args: Args) -> Result<(), String> {
    run_with_frame(args, None)
}

/// `botsim frame`: a run, then the course display at its end.
pub fn run_with_frame(args: Args, frame_out: Option<PathBuf>) -> Result<(), String> {
    let firmware = Firmware {
        threshold: args.threshold.unwrap_or(15),
        timing: args.timing.unwrap_or_default(),
        compat: args.compat.unwrap_or_default(),
    };
    let image = match &args.program {
        None => firmware.assemble().map_err(|d| d.to_string())?,
        Some(p) => {
            // bot_pgm is a 1K ROM: a .psm that runs past it fails at the line that does.
            let opts = Options { defines: firmware.defines(), rom_size: Some(RomSize::K1), ..Options::default() };
            if Format::of(p) != Some(Format::Psm)
                && (args.threshold.is_some() || args.timing.is_some() || args.compat.is_some())
                && !args.quiet
            {
                eprintln!("{}: warning: --threshold, --timing and --compat only apply to .psm programs", p.display());
            }
            let image = kcpsm6::loader::load(p, &opts).map_err(|d| d.to_string())?;
            if let Some(last) = image.words.iter().rposition(|&w| w != 0).filter(|&a| a >= 1024) {
                return Err(format!("{}: error: {}", p.display(), Error::ProgramTooLarge(last)));
            }
            image
        }
    };
    let world = match &args.map {
        Some(p) => World::load(p).map_err(|d| d.to_string())?,
        None => World::builtin(),
    };
    // MotCtl_in from reset is the script's first value (a driver starts stopped).
    let (mut driver, samples, initial): (Box<dyn Driver>, u64, MotCtl) = match (&args.motors, &args.driver) {
        (Some(p), _) => {
            let script = MotorScript::load(p).map_err(|d| d.to_string())?;
            let (n, first) = (args.samples.unwrap_or(script.total()), script.initial());
            (Box::new(ScriptDriver::new(script)), n, first)
        }
        (None, Some(_)) => {
            (Box::new(LineFollower::new(firmware.threshold)), args.samples.unwrap_or(50_000), MotCtl::STOP)
        }
        (None, None) => (Box::new(ScriptDriver::new(MotorScript::default())), args.samples.unwrap_or(20), MotCtl::STOP),
    };
    if args.backend != "rtl" && args.vcd.is_some() {
        return Err(format!("error: --vcd needs the RTL backend; --backend {} has no waveform", args.backend));
    }
    let outputs = [&args.trace_csv, &args.trace_json, &args.vcd, &args.png, &frame_out];
    for p in outputs.into_iter().flatten() {
        check_writable(p)?;
    }
    // Frames show the world as read through the RTL video port, scanned once in a model of
    // its own (so no sample of the run is skipped, whatever the backend).
    let video = match args.frames.is_some() || frame_out.is_some() {
        false => None,
        true => {
            let mut scan =
                BotSim::builder().program(image.clone()).world(world.clone()).build().map_err(|e| e.to_string())?;
            Some(World::from_cells(&scan.scan_video().map_err(|e| e.to_string())?))
        }
    };
    let frames = match (&args.frames, &video) {
        (Some(dir), Some(video)) => {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: error: cannot create folder: {e}", dir.display()))?;
            Some((dir.clone(), video.clone()))
        }
        _ => None,
    };
    let mut frames_written = 0;

    let mut bot = match args.backend.as_str() {
        "rtl" => Engine::Rtl(
            BotSim::builder()
                .firmware(firmware)
                .program(image)
                .world(world.clone())
                .motors(initial)
                .build()
                .map_err(|e| e.to_string())?,
        ),
        "iss" => {
            let mut iss = IssBot::new(&image, world.clone());
            iss.set_motors(initial);
            Engine::Other(Box::new(iss))
        }
        _ => {
            let mut both = Lockstep::new(&image, world.clone()).map_err(|e| e.to_string())?;
            both.set_motors(initial);
            Engine::Other(Box::new(both))
        }
    };

    let progress = (!args.quiet && !args.json && std::io::stderr().is_terminal() && samples > 50).then(|| {
        let bar = indicatif::ProgressBar::new(samples + 1);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} samples {elapsed_precise} ({per_sec}) {msg}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    });

    let mut window = args.vcd.clone().map(|path| Window {
        part: part_name(&path),
        path,
        from: args.trace_from,
        to: args.trace_to,
        state: State::Before,
    });
    let _unfinished = Unfinished(window.as_ref().map(|w| w.part.clone()));
    // Ctrl-C stops the run between two checks (at most ~1 M cycles apart); the outputs are
    // then written for the samples taken, as at a normal end.
    let _ = ctrlc::set_handler(|| super::INTERRUPTED.store(true, std::sync::atomic::Ordering::Relaxed));
    let mut stopped_at = None;
    let start = Instant::now();
    let mut snaps: Vec<Snapshot> = vec![];
    let mut json = String::new();
    for k in 0..=samples {
        if let Some(w) = window.as_mut() {
            w.before_sample(bot.rtl()?, k)?;
        }
        let s = match next_sample(&mut bot, window.as_mut()) {
            Ok(s) => s,
            Err(Wait::Interrupted) => {
                stopped_at = Some((k, bot.backend().cycle()));
                break;
            }
            Err(Wait::Sim(Error::Waveform(why))) => {
                let p = args.vcd.as_deref().unwrap_or(Path::new("waveform"));
                return Err(format!("{}: error: cannot write file: {why} (in sample {k})", p.display()));
            }
            Err(Wait::Sim(e)) => return Err(format!("error: sample {k}: {e}")),
            Err(Wait::Other(msg)) => return Err(msg),
        };
        let m = driver.next(&s);
        json.push_str(&json_row(&s, m));
        snaps.push(s);
        if let Some((dir, video)) = &frames {
            if k % args.frame_every.max(1) == 0 || k == samples || driver.finished() {
                let p = dir.join(format!("frame_{k:06}.png"));
                write_atomic(&p, &botsim::render::display::frame(video, Some(&s)))?;
                frames_written += 1;
            }
        }
        if let Some(w) = window.as_mut() {
            w.after_sample(bot.rtl()?, k)?;
        }
        if let Some(b) = &progress {
            b.set_position(k + 1);
        }
        if driver.finished() {
            break;
        }
        bot.backend().set_motors(m);
    }
    if let Some(w) = window.as_mut() {
        w.close(bot.rtl()?)?;
    }
    let cycles = bot.backend().cycle();
    let wall = start.elapsed().as_secs_f64();
    let end_frame =
        video.as_ref().filter(|_| frame_out.is_some()).map(|v| botsim::render::display::frame(v, snaps.last()));
    drop(bot);
    if let Some(b) = progress {
        b.finish_and_clear();
    }

    let mut written = vec![];
    if let Some(p) = &args.trace_csv {
        let mut csv = String::from(CSV_HEADER);
        csv.push('\n');
        for s in &snaps {
            csv.push_str(&csv_row(s));
        }
        write_atomic(p, csv.as_bytes())?;
        written.push(p.clone());
    }
    if let Some(p) = &args.trace_json {
        write_atomic(p, json.as_bytes())?;
        written.push(p.clone());
    }
    if let (Some(p), Some(png)) = (&frame_out, &end_frame) {
        write_atomic(p, png)?;
        written.push(p.clone());
    }
    if let Some((dir, _)) = &frames {
        written.push(dir.join(format!("({frames_written} frames)")));
    }
    if let Some(p) = &args.png {
        write_atomic(p, &path_picture(&world, &snaps, firmware.threshold, &PathStyle::default()))?;
        written.push(p.clone());
    }
    if let Some(Window { path, part, .. }) = &window {
        if part.exists() {
            std::fs::rename(part, path).map_err(|e| format!("{}: error: cannot write file: {e}", path.display()))?;
            written.push(path.clone());
        } else {
            eprintln!("{}: warning: the trace window was never reached; no waveform written", path.display());
        }
    }
    if let Some((k, cycle)) = stopped_at {
        eprintln!(
            "interrupted: stopped in sample {k} at cycle {cycle}; the outputs hold samples 0-{}",
            k.saturating_sub(1)
        );
    }
    let Some(last) = snaps.last().copied() else { return Ok(()) };
    if args.json {
        let v = serde_json::json!({
            "samples": snaps.len(), "cycles": cycles, "simulated_seconds": cycles as f64 / 1e8,
            "wall_seconds": wall, "mcycles_per_second": cycles as f64 / wall.max(1e-9) / 1e6,
            "final": {
                "loc_x": last.regs.loc_x, "loc_y": last.regs.loc_y, "orientation": last.orientation().name(),
                "movement": last.movement().name(), "sensors": last.regs.sensors,
            },
            "driver": driver.status(),
            "files": written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
            "frames": frames_written,
        });
        println!("{v}");
    } else if !args.quiet {
        let mut out = String::new();
        let _ = writeln!(out, "samples      {} (the reset dump and {} iterations)", snaps.len(), snaps.len() - 1);
        let _ = writeln!(out, "cycles       {cycles} ({:.3} s at 100 MHz)", cycles as f64 / 1e8);
        let _ = writeln!(out, "wall time    {wall:.2} s ({:.1} Mcycles/s)", cycles as f64 / wall.max(1e-9) / 1e6);
        let _ = writeln!(
            out,
            "final        ({}, {}) facing {} {}, sensors {:02X}",
            last.regs.loc_x,
            last.regs.loc_y,
            last.orientation().name(),
            last.movement().name(),
            last.regs.sensors
        );
        if !driver.status().is_empty() {
            let _ = writeln!(out, "driver       {}", driver.status());
        }
        for w in written {
            let _ = writeln!(out, "wrote        {}", w.display());
        }
        print!("{out}");
    }
    Ok(())
}

/// Removes a waveform still under its temporary name when the run ends in an error.
struct Unfinished(Option<PathBuf>);

impl Drop for Unfinished {
    fn drop(&mut self) {
        if let Some(p) = &self.0 {
            let _ = std::fs::remove_file(p);
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    Before,
    Open,
    Done,
}

/// The waveform window: opens at `from` (a sample's start or a cycle), closes after `to`.
struct Window {
    path: PathBuf,
    part: PathBuf,
    from: Option<Point>,
    to: Option<Point>,
    state: State,
}

impl Window {
    fn open(&mut self, bot: &mut BotSim) -> Result<(), String> {
        bot.open_vcd(&self.part).map_err(|e| e.to_string())?;
        self.state = State::Open;
        Ok(())
    }

    fn close(&mut self, bot: &mut BotSim) -> Result<(), String> {
        let open = self.state == State::Open;
        self.state = State::Done;
        if open {
            bot.close_vcd().map_err(|e| match e {
                Error::Waveform(why) => format!("{}: error: cannot write file: {why}", self.path.display()),
                e => e.to_string(),
            })?;
        }
        Ok(())
    }

    /// Before waiting for sample `k`: open a whole-run or sample window.
    fn before_sample(&mut self, bot: &mut BotSim, k: u64) -> Result<(), String> {
        match (self.state, self.from) {
            (State::Before, None) => self.open(bot),
            (State::Before, Some(Point::Sample(s))) if k >= s => {
                if k > 0 {
                    // The run stands at the first cycle of sample k-1's pulse: start after it.
                    bot.run(2).map_err(|e| e.to_string())?;
                }
                self.open(bot)
            }
            _ => Ok(()),
        }
    }

    /// After sample `k`'s pulse began: close a sample window, including the whole pulse.
    fn after_sample(&mut self, bot: &mut BotSim, k: u64) -> Result<(), String> {
        if let (State::Open, Some(Point::Sample(s))) = (self.state, self.to) {
            if k >= s {
                bot.run(3).map_err(|e| e.to_string())?;
                self.close(bot)?;
            }
        }
        Ok(())
    }

    /// The next cycle at which the window opens or closes, if it is given in cycles.
    fn boundary(&self) -> Option<u64> {
        match (self.state, self.from, self.to) {
            (State::Before, Some(Point::Cycle(c)), _) => Some(c),
            (State::Open, _, Some(Point::Cycle(c))) => Some(c),
            _ => None,
        }
    }

    fn cross_boundary(&mut self, bot: &mut BotSim) -> Result<(), String> {
        match self.state {
            State::Before => self.open(bot),
            _ => self.close(bot),
        }
    }
}

/// Why a wait for the next sample ended without one.
enum Wait {
    Interrupted,
    Sim(Error),
    Other(String),
}

impl From<String> for Wait {
    fn from(e: String) -> Wait {
        Wait::Other(e)
    }
}

/// Cycles between two looks at the Ctrl-C flag (~0.07 s of RTL time here).
const CHECK_EVERY: u64 = 1 << 20;

/// Wait for the next pulse within the bot's update budget, opening or closing a cycle window
/// on the way and stopping early on Ctrl-C.
fn next_sample(engine: &mut Engine, mut window: Option<&mut Window>) -> Result<Snapshot, Wait> {
    let deadline = engine.backend().cycle() + engine.backend().update_budget();
    loop {
        if super::interrupted() {
            return Err(Wait::Interrupted);
        }
        let bot = engine.backend();
        let now = bot.cycle();
        if now >= deadline {
            let budget = bot.update_budget();
            return Err(Wait::Sim(Error::Timeout {
                waited_for: "upd_sysregs pulse",
                budget,
                cycle: now,
                cpu: bot.cpu_at(),
            }));
        }
        let boundary = window.as_ref().and_then(|w| w.boundary());
        let stop = boundary.filter(|&c| c > now).unwrap_or(deadline).min(deadline).min(now + CHECK_EVERY);
        if boundary.map_or(true, |c| c > now) {
            match bot.wait_update_within(stop - now) {
                Ok(s) => return Ok(s),
                Err(Error::Timeout { .. }) => {}
                Err(e) => return Err(Wait::Sim(e)),
            }
        }
        if let (Some(w), Some(c)) = (window.as_mut(), boundary) {
            if engine.backend().cycle() >= c {
                w.cross_boundary(engine.rtl()?)?;
            }
        }
    }
}
