//! `botsim frame`: what the course's 640 x 480 display shows at the end of a run.

use std::path::PathBuf;

/// Render the course display (640 x 480 PNG) after a run: the world read through the RTL video
/// port at 4 x 4 pixels per cell, the bot's icon at its location and heading.
///
/// Takes every option of `botsim run`; without --samples, --motors or --driver it shows the
/// start (the register dump after reset).
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  botsim frame -o start.png\n  botsim frame --timing fast --driver line-follow -o end.png\n  botsim frame --map world_map_lr.txt --motors drive.txt -o lr.png"
)]
pub struct Args {
    /// The PNG to write
    #[arg(short, long = "output", value_name = "FILE")]
    output: PathBuf,
    #[command(flatten)]
    run: super::run::Args,
}

pub fn run(args: Args) -> Result<(), String> {
    if args.run.is_live() {
        return Err("--live is botsim run's (botsim run --live): a frame is a picture of a run's end".into());
    }
    super::run::run_with_frame(args.run, Some(args.output))
}
