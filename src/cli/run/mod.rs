//! `botsim run`: run BotSim 2.0 with a motor script or a closed-loop driver. In layers: the
//! arguments (here), the resolved [`plan`], the [`sample_loop`], the [`outputs`].

mod outputs;
pub(crate) use outputs::{csv_row, json_row, CSV_HEADER};
mod plan;
mod sample_loop;

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

use botsim::files::write_atomic;
use botsim::sim::lockstep::Lockstep;
use botsim::sim::rtl::{Point, VcdWindow};
use botsim::{IssBot, RtlBot, World};

use crate::cli::args::{BackendKind, DriverKind, FirmwareArgs};
use outputs::Taken;
use plan::Plan;
use sample_loop::Engine;

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
}

pub fn run(args: Args) -> Result<(), String> {
    run_with_frame(args, None)
}

/// `botsim frame`: a run, then the course display at its end.
pub fn run_with_frame(args: Args, end_frame: Option<PathBuf>) -> Result<(), String> {
    let mut plan = Plan::resolve(&args, end_frame)?;
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
    let mut engine = engine(&plan)?;
    let mut window = plan.waveform.as_ref().map(|w| VcdWindow::new(w.path.clone(), w.from, w.to));

    let progress = (!args.quiet && !args.json && std::io::stderr().is_terminal() && plan.samples > 50).then(|| {
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
    let stopped = sample_loop::run(&mut engine, window.as_mut(), samples, |k, s| {
        let m = driver.next(s);
        taken.json.push_str(&outputs::json_row(s, m));
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
        Ok((m, driver.finished()))
    })?;
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

    let end_frame = video
        .as_ref()
        .filter(|_| plan.end_frame.is_some())
        .map(|v| botsim::render::display::frame(v, taken.snapshots.last()));
    let mut written = outputs::write(&plan, &taken, end_frame.as_deref())?;
    match (waveform_written, &window) {
        (Some(true), Some(w)) => written.push(w.path().to_path_buf()),
        (Some(false), Some(w)) => {
            eprintln!("{}: warning: the trace window was never reached; no waveform written", w.path().display())
        }
        _ => {}
    }
    if let Some(i) = stopped {
        eprintln!(
            "interrupted: stopped in sample {} at cycle {}; the outputs hold samples 0-{}",
            i.sample,
            i.cycle,
            i.sample.saturating_sub(1)
        );
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
    Ok(())
}

/// The backend the plan asks for, with the program, world, initial motors and the firmware
/// timing's update budget.
fn engine(plan: &Plan) -> Result<Engine, String> {
    let budget = plan.firmware.timing.update_budget();
    let mut engine = match plan.backend {
        BackendKind::Rtl => Engine::Rtl(
            RtlBot::builder()
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
    let bot = engine.backend();
    bot.set_update_budget(budget);
    bot.set_motors(plan.initial);
    Ok(engine)
}
