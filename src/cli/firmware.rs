//! `botsim firmware`: the built-in BotSim firmware with chosen constants, as a file.

use std::path::{Path, PathBuf};

use botsim::files::write_atomic;
use botsim::firmware::{SOURCE, SOURCE_PATH};
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
    #[command(flatten)]
    firmware: super::args::FirmwareArgs,
}

pub fn run(args: Args) -> Result<(), String> {
    let program = args.firmware.firmware().program(super::asm::timestamp()).map_err(|d| d.to_string())?;
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
