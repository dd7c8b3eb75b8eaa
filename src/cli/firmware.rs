//! `botsim firmware`: the built-in BotSim firmware with chosen constants, as a file.

use std::path::{Path, PathBuf};

use botsim::files::write_atomic;
use botsim::firmware::{Compat, Firmware, Timing, SOURCE, SOURCE_PATH};
use botsim::kcpsm6::asm::RomSize;
use botsim::kcpsm6::output::{render, OutputFormat};

/// Write the built-in BotSim firmware (rtl/bot_pgm.psm) assembled with chosen constants:
/// a bot_pgm.v for an FPGA design or a Verilog simulator, or .hex, .mem, .log, or the .psm.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  botsim firmware --threshold 4 -o bot_pgm.v\n  botsim firmware --timing fast --compat botsim20 -o bot_pgm.hex"
)]
pub struct Args {
    /// Output file(s): .v (ROM module named after the file), .hex, .mem, .log or .psm
    #[arg(short, long = "output", value_name = "OUT", required = true)]
    output: Vec<PathBuf>,
    /// Samples per move or 45-degree turn
    #[arg(long, default_value_t = 15)]
    threshold: u8,
    /// Sample interval: hw (~50 ms at 100 MHz) or fast (~2,000 clocks)
    #[arg(long, value_name = "hw|fast", default_value = "hw", value_parser = ["hw", "fast"])]
    timing: String,
    /// Behave as the 2014 BotSim 2.0 program (its facing-SW right-front cell)
    #[arg(long, value_name = "botsim20", value_parser = ["botsim20"])]
    compat: Option<String>,
}

pub fn run(args: Args) -> Result<(), String> {
    let fw = Firmware {
        threshold: args.threshold,
        timing: Timing::parse(&args.timing).unwrap_or_default(),
        compat: if args.compat.is_some() { Compat::BotSim20 } else { Compat::Symmetric },
    };
    let program = fw.program(super::asm::timestamp()).map_err(|d| d.to_string())?;
    for out in &args.output {
        if out.extension().is_some_and(|e| e.eq_ignore_ascii_case("psm")) {
            write_atomic(out, SOURCE.as_bytes())?;
            continue;
        }
        let f = OutputFormat::of(out).ok_or_else(|| {
            format!("{}: error: unknown output format (expected .v, .hex, .mem, .log or .psm)", out.display())
        })?;
        write_atomic(out, render(&program, f, out, Path::new(SOURCE_PATH), Some(RomSize::K1)).as_bytes())?;
    }
    Ok(())
}
