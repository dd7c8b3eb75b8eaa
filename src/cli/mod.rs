//! Subcommands of `botsim`. Every error is one line on stderr and exit status 1; a run stopped
//! by Ctrl-C writes its outputs up to there and exits with 130.

mod args;
mod asm;
mod bench;
mod board;
mod disasm;
mod firmware;
mod frame;
mod live;
mod map;
mod rows;
mod run;
mod size;
mod suite;

use clap::{Parser, Subcommand};

/// Exit status for success.
pub const EXIT_OK: i32 = 0;
/// Exit status for any error: bad input, bad usage, a failed run.
pub const EXIT_ERROR: i32 = 1;
/// Exit status after Ctrl-C (SIGINT) stopped a run: its outputs are complete up to there.
pub const EXIT_INTERRUPTED: i32 = 130;

pub use botsim::interrupt::interrupted;

#[derive(Parser)]
#[command(name = "botsim", version, about = "Cycle-exact RTL co-simulation of the Rojobot BotSim 2.0", long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    Run(run::Args),
    Board(Box<board::Args>),
    Suite(suite::Args),
    Frame(frame::Args),
    Map(map::Args),
    Firmware(firmware::Args),
    Bench(bench::Args),
    Asm(asm::Args),
    Disasm(disasm::Args),
}

/// Parse the command line and run; returns the exit status.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { EXIT_ERROR } else { EXIT_OK };
            let _ = e.print();
            return code;
        }
    };
    let result = match cli.command {
        Command::Run(a) => run::run(a),
        Command::Board(a) => board::run(*a),
        Command::Suite(a) => suite::run(a),
        Command::Frame(a) => frame::run(a),
        Command::Map(a) => map::run(a),
        Command::Firmware(a) => firmware::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Asm(a) => asm::run(a),
        Command::Disasm(a) => disasm::run(a),
    };
    match result {
        Ok(()) if interrupted() => EXIT_INTERRUPTED,
        Ok(()) => EXIT_OK,
        Err(msg) => {
            eprintln!("{msg}");
            if interrupted() {
                EXIT_INTERRUPTED
            } else {
                EXIT_ERROR
            }
        }
    }
}
