//! `botsim asm`: assemble KCPSM6 source into .hex, .mem, .v or .log.

use std::path::PathBuf;

use kcpsm6::asm::{assemble_file, Options, RomSize};
use kcpsm6::output::{render, OutputFormat};

use botsim::files::write_atomic;

/// Assemble a KCPSM6 program (KCPSM6 v2.70 syntax).
///
/// The output format follows each OUT file's extension: .hex (KCPSM6, 4096 lines, CR LF),
/// .mem ($readmemh), .v (a program ROM module named after the file) or .log (listing).
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  botsim asm rtl/bot_pgm.psm -o bot_pgm.v\n  botsim asm prog.psm -o prog.hex -o prog.log -D THRESHOLD=04 --rom-size 1K"
)]
pub struct Args {
    /// The top source file (.psm); INCLUDE paths are relative to the including file.
    input: PathBuf,
    /// Output file(s); the extension chooses the format (.hex, .mem, .v, .log).
    #[arg(short, long = "output", value_name = "OUT", required = true)]
    output: Vec<PathBuf>,
    /// Define or override a CONSTANT (value as in the source: 0F, 15'd, 00001111'b, "A") or a
    /// STRING (`-D 'datestamp$=11 Oct 2014'`, also the predefined ones, to rebuild an old ROM).
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    define: Vec<(String, String)>,
    /// Refuse a program that does not fit this ROM (1K, 2K or 4K); also sizes the .v ROM.
    #[arg(long, value_name = "SIZE", value_parser = parse_rom_size)]
    rom_size: Option<RomSize>,
    /// Do not print warnings (also when the assembly fails).
    #[arg(short, long)]
    quiet: bool,
}

fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((n, v)) if !n.is_empty() => Ok((n.to_string(), v.to_string())),
        _ => Err(format!("expected NAME=VALUE, found '{s}'")),
    }
}

fn parse_rom_size(s: &str) -> Result<RomSize, String> {
    RomSize::parse(s).ok_or_else(|| format!("expected 1K, 2K or 4K, found '{s}'"))
}

/// Seconds since 1970 for the predefined time stamps: SOURCE_DATE_EPOCH if set (reproducible
/// builds), else now.
pub fn timestamp() -> u64 {
    std::env::var("SOURCE_DATE_EPOCH").ok().and_then(|s| s.trim().parse().ok()).unwrap_or_else(|| {
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs())
    })
}

pub fn run(args: Args) -> Result<(), String> {
    let mut formats = Vec::new();
    for out in &args.output {
        let f = OutputFormat::of(out).ok_or_else(|| {
            format!("{}: error: unknown output format (expected .hex, .mem, .v or .log)", out.display())
        })?;
        formats.push(f);
    }
    let opts = Options {
        defines: args.define.clone(),
        env: std::env::vars().filter(|(k, _)| k.to_ascii_uppercase().starts_with("PSM_")).collect(),
        rom_size: args.rom_size,
        timestamp: timestamp(),
    };
    let program =
        assemble_file(&args.input, &opts).map_err(|d| if args.quiet { d.without_warnings() } else { d }.to_string())?;
    if !args.quiet {
        for w in &program.warnings {
            eprintln!("{w}");
        }
    }
    for (out, f) in args.output.iter().zip(formats) {
        let text = render(&program, f, out, &args.input, args.rom_size);
        write_atomic(out, text.as_bytes())?;
    }
    Ok(())
}
