//! `botsim disasm`: a program image back to KCPSM6 source.

use std::path::PathBuf;

use kcpsm6::asm::Options;
use kcpsm6::disasm::disassemble;

use botsim::files::write_atomic;

/// Disassemble a program (.hex, .mem, a ROM .v, or .psm) into source that re-assembles to the
/// same 4096 words.
#[derive(clap::Args)]
#[command(after_help = "Examples:\n  botsim disasm bot_pgm.v\n  botsim disasm prog.hex -o prog.psm")]
pub struct Args {
    /// The program: .hex, .mem, .v (Xilinx-template or botsim ROM) or .psm.
    input: PathBuf,
    /// Write the source here instead of standard output.
    #[arg(short, long = "output", value_name = "OUT")]
    output: Option<PathBuf>,
}

pub fn run(args: Args) -> Result<(), String> {
    let opts = Options { timestamp: super::asm::timestamp(), ..Options::default() };
    let image = kcpsm6::loader::load(&args.input, &opts).map_err(|d| d.to_string())?;
    let text = disassemble(&image);
    match args.output {
        Some(out) => write_atomic(&out, text.as_bytes()),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}
