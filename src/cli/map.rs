//! `botsim map`: look at a world, convert it between formats.

use std::path::{Path, PathBuf};

use botsim::files::write_atomic;
use botsim::world::{Cell, World, WorldFormat, SIZE};

/// Show or convert world maps (.txt, .coe, .mem, .png; `builtin` names the built-in course).
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  botsim map show world_map_part1.txt\n  botsim map convert world_map_lr.coe lr.png\n  botsim map convert builtin my_world.txt"
)]
pub struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(clap::Subcommand)]
enum Command {
    /// Print a world on the terminal: ' ' floor, '#' obstruction, '.' line, 'o' reserved
    #[command(after_help = "Example:\n  botsim map show builtin")]
    Show {
        /// The world file, or `builtin`
        file: PathBuf,
    },
    /// Convert a world file; the formats follow the extensions
    #[command(after_help = "Example:\n  botsim map convert world_map_part1.txt part1.mem")]
    Convert {
        /// The world to read (.txt, .coe, .mem, .png, or `builtin`)
        input: PathBuf,
        /// The file to write (.txt, .coe, .mem or .png)
        output: PathBuf,
    },
}

fn load(p: &Path) -> Result<World, String> {
    if p == Path::new("builtin") {
        return Ok(World::builtin());
    }
    World::load(p).map_err(|d| d.to_string())
}

/// The terminal picture: a header of column tens, then one line per row.
pub fn show(w: &World) -> String {
    let mut s = String::from("    ");
    s.extend((0..SIZE).map(|x| if x % 10 == 0 { char::from(b'0' + (x / 10 % 10) as u8) } else { ' ' }));
    s.push('\n');
    for y in 0..SIZE {
        s.push_str(&format!("{y:3} "));
        s.extend((0..SIZE).map(|x| match w.get(x as u8, y as u8) {
            Cell::Floor => ' ',
            Cell::Line => '.',
            Cell::Obstruction => '#',
            Cell::Reserved => 'o',
        }));
        s.push('\n');
    }
    let [f, l, o, r] = w.counts();
    s.push_str(&format!("floor {f}, line {l}, obstruction {o}, reserved {r}\n"));
    s
}

pub fn run(args: Args) -> Result<(), String> {
    match args.command {
        Command::Show { file } => {
            print!("{}", show(&load(&file)?));
            Ok(())
        }
        Command::Convert { input, output } => {
            let fmt = WorldFormat::of(&output).ok_or_else(|| {
                format!("{}: error: unknown world format (expected .txt, .coe, .mem or .png)", output.display())
            })?;
            let w = load(&input)?;
            write_atomic(&output, &w.to_format(fmt))
        }
    }
}
