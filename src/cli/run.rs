//! `botsim run`: a closed run of the BotSim RTL with a motor script.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use botsim::files::write_atomic;
use botsim::firmware::{Compat, Firmware, Timing};
use botsim::kcpsm6::asm::Options;
use botsim::kcpsm6::image::{Format, Image};
use botsim::script::MotorScript;
use botsim::world::World;
use botsim::{BotSim, Snapshot};

/// Run the BotSim 2.0 RTL (Verilator) on a world with a motor script.
///
/// MotCtl_in follows the motor script: the first segment's value from reset, each later
/// value applied right after an upd_sysregs pulse, so main-loop iteration k sees the segment
/// that covers k. Sample 0 is the register dump after reset.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  botsim run --timing fast --motors drive.txt --trace-csv trace.csv\n  botsim run --map world_map_lr.txt --program bot_pgm.hex --samples 50 --vcd bot.vcd\n\nMotor script lines: '<MOTCTL> <COUNT>', e.g. '33 15' or 'forward 15'; '#' starts a comment."
)]
pub struct Args {
    /// Program: .psm (assembled with the constants below), .hex, .mem or a ROM .v
    /// [default: the built-in BotSim firmware]
    #[arg(long, value_name = "FILE")]
    program: Option<PathBuf>,
    /// World: .txt, .coe, .mem or .png [default: the built-in course]
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    /// Motor script [default: stopped]
    #[arg(long, value_name = "FILE")]
    motors: Option<PathBuf>,
    /// Main-loop iterations to run [default: the script's total, else 20]
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
    /// Write a VCD waveform of the whole run
    #[arg(long, value_name = "FILE")]
    vcd: Option<PathBuf>,
    /// Print only errors
    #[arg(short, long)]
    quiet: bool,
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

/// Check that `path` can be written before a long run (and leave nothing behind).
fn check_writable(path: &Path) -> Result<(), String> {
    write_atomic(path, b"")
        .and_then(|()| std::fs::remove_file(path).map_err(|e| format!("{}: error: {e}", path.display())))
}

pub fn run(args: Args) -> Result<(), String> {
    let firmware = Firmware {
        threshold: args.threshold.unwrap_or(15),
        timing: args.timing.unwrap_or_default(),
        compat: args.compat.unwrap_or_default(),
    };
    let image = match &args.program {
        None => firmware.assemble().map_err(|d| d.to_string())?,
        Some(p) => {
            let opts = Options { defines: firmware.defines(), ..Options::default() };
            if Format::of(p) != Some(Format::Psm)
                && (args.threshold.is_some() || args.timing.is_some() || args.compat.is_some())
                && !args.quiet
            {
                eprintln!("{}: warning: --threshold, --timing and --compat only apply to .psm programs", p.display());
            }
            Image::load(p, &opts).map_err(|d| d.to_string())?
        }
    };
    let world = match &args.map {
        Some(p) => World::load(p).map_err(|d| d.to_string())?,
        None => World::builtin(),
    };
    let script = match &args.motors {
        Some(p) => MotorScript::load(p).map_err(|d| d.to_string())?,
        None => MotorScript::default(),
    };
    let samples = args.samples.unwrap_or(if args.motors.is_some() { script.total() } else { 20 });
    for p in args.trace_csv.iter().chain(args.vcd.iter()) {
        check_writable(p)?;
    }

    let vcd_tmp = args
        .vcd
        .as_ref()
        .map(|p| p.with_file_name(format!(".{}.part", p.file_name().unwrap_or_default().to_string_lossy())));
    let mut builder = BotSim::builder().firmware(firmware).program(image).world(world).motors(script.initial());
    if let Some(t) = &vcd_tmp {
        builder = builder.vcd(t);
    }
    let mut bot = builder.build().map_err(|e| e.to_string())?;

    let start = Instant::now();
    let mut csv = String::from(CSV_HEADER);
    csv.push('\n');
    let mut last = None;
    for k in 0..=samples {
        let s = bot.wait_update().map_err(|e| format!("error: sample {k}: {e}"))?;
        csv.push_str(&csv_row(&s));
        bot.set_motors(script.value_for(k + 1));
        last = Some(s);
    }
    let cycles = bot.cycle();
    let wall = start.elapsed().as_secs_f64();
    bot.close_vcd();
    drop(bot);

    let mut written = vec![];
    if let Some(p) = &args.trace_csv {
        write_atomic(p, csv.as_bytes())?;
        written.push(p.display().to_string());
    }
    if let (Some(p), Some(t)) = (&args.vcd, &vcd_tmp) {
        std::fs::rename(t, p).map_err(|e| format!("{}: error: cannot write file: {e}", p.display()))?;
        written.push(p.display().to_string());
    }
    if !args.quiet {
        let mut out = String::new();
        let s = last.expect("at least sample 0");
        let _ = writeln!(out, "samples      {} (iterations 1-{samples} after the reset dump)", samples + 1);
        let _ = writeln!(out, "cycles       {cycles} ({:.3} s at 100 MHz)", cycles as f64 / 1e8);
        let _ = writeln!(out, "wall time    {wall:.2} s ({:.1} Mcycles/s)", cycles as f64 / wall.max(1e-9) / 1e6);
        let _ = writeln!(
            out,
            "final        ({}, {}) facing {} {}, sensors {:02X}",
            s.regs.loc_x,
            s.regs.loc_y,
            s.orientation().name(),
            s.movement().name(),
            s.regs.sensors
        );
        for w in written {
            let _ = writeln!(out, "wrote        {w}");
        }
        print!("{out}");
    }
    Ok(())
}
