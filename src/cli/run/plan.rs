//! A run resolved from the arguments: the program, the world, the driver, what to write. Every
//! input is read and every output path checked here, before the (possibly long) run starts.

use std::path::PathBuf;

use botsim::driver::{Driver, LineFollower, ScriptDriver};
use botsim::files::check_writable;
use botsim::kcpsm6::asm::{Options, RomSize};
use botsim::kcpsm6::image::{Format, Image};
use botsim::script::MotorScript;
use botsim::sim::check_program_size;
use botsim::sim::rtl::Point;
use botsim::{Firmware, MotCtl, World};

use super::Args;
use crate::cli::args::{BackendKind, DriverKind};

/// The waveform asked for.
pub struct WaveformPlan {
    pub path: PathBuf,
    pub from: Option<Point>,
    pub to: Option<Point>,
}

/// Course-display frames every `every` samples into `dir`.
pub struct FramesPlan {
    pub dir: PathBuf,
    pub every: u64,
}

pub struct Plan {
    pub firmware: Firmware,
    pub image: Image,
    pub world: World,
    pub driver: Box<dyn Driver>,
    /// Main-loop iterations after the reset dump.
    pub samples: u64,
    /// MotCtl_in from reset.
    pub initial: MotCtl,
    pub backend: BackendKind,
    pub waveform: Option<WaveformPlan>,
    pub frames: Option<FramesPlan>,
    /// `botsim frame`'s picture of the end.
    pub end_frame: Option<PathBuf>,
    pub trace_csv: Option<PathBuf>,
    pub trace_json: Option<PathBuf>,
    pub png: Option<PathBuf>,
}

impl Plan {
    pub fn resolve(args: &Args, end_frame: Option<PathBuf>) -> Result<Plan, String> {
        let firmware = args.firmware.firmware();
        let image = match &args.program {
            None => firmware.assemble().map_err(|d| d.to_string())?,
            Some(p) => {
                if Format::of(p) != Some(Format::Psm) && args.firmware.any() && !args.quiet {
                    eprintln!(
                        "{}: warning: --threshold, --timing and --compat only apply to .psm programs",
                        p.display()
                    );
                }
                // bot_pgm is a 1K ROM: a .psm that runs past it fails at the line that does.
                let opts = Options { defines: firmware.defines(), rom_size: Some(RomSize::K1), ..Options::default() };
                let image = botsim::kcpsm6::loader::load(p, &opts).map_err(|d| d.errors_text())?;
                check_program_size(&image.words[..]).map_err(|e| format!("{}: error: {e}", p.display()))?;
                image
            }
        };
        let world = match &args.map {
            Some(p) => World::load(p).map_err(|d| d.to_string())?,
            None => World::builtin(),
        };
        // MotCtl_in from reset is the script's first value (a driver starts stopped).
        let (driver, samples, initial): (Box<dyn Driver>, u64, MotCtl) = match (&args.motors, args.driver) {
            (Some(p), _) => {
                let script = MotorScript::load(p).map_err(|d| d.to_string())?;
                let (n, first) = (args.samples.unwrap_or(script.total()), script.initial());
                (Box::new(ScriptDriver::new(script)), n, first)
            }
            (None, Some(DriverKind::LineFollow)) => {
                (Box::new(LineFollower::new(firmware.threshold)), args.samples.unwrap_or(50_000), MotCtl::STOP)
            }
            (None, None) => {
                (Box::new(ScriptDriver::new(MotorScript::default())), args.samples.unwrap_or(20), MotCtl::STOP)
            }
        };
        if args.backend != BackendKind::Rtl && args.vcd.is_some() {
            let name = clap::ValueEnum::to_possible_value(&args.backend).map(|v| v.get_name().to_string());
            return Err(format!(
                "error: --vcd needs the RTL backend; --backend {} has no waveform",
                name.unwrap_or_default()
            ));
        }
        let outputs = [&args.trace_csv, &args.trace_json, &args.vcd, &args.png, &end_frame];
        for p in outputs.into_iter().flatten() {
            check_writable(p)?;
        }
        Ok(Plan {
            firmware,
            image,
            world,
            driver,
            samples,
            initial,
            backend: args.backend,
            waveform: args.vcd.clone().map(|path| WaveformPlan { path, from: args.trace_from, to: args.trace_to }),
            frames: args.frames.clone().map(|dir| FramesPlan { dir, every: args.frame_every.max(1) }),
            end_frame,
            trace_csv: args.trace_csv.clone(),
            trace_json: args.trace_json.clone(),
            png: args.png.clone(),
        })
    }
}
