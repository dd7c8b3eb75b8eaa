//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod cdp;
pub mod cpu_coverage;
pub mod debug;
pub mod game;
pub mod icarus;
pub mod lines;
pub mod live;
pub mod lockstep;
pub mod random_design;
pub mod repo;
pub mod strategies;
pub mod variants;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Output};
use std::time::{Duration, Instant};

/// The repository's folder.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The board builds every test shares: one build per design key for the whole test run.
pub fn board_cache() -> PathBuf {
    root().join("target/botsim-board-cache")
}

/// Run the `botsim` binary in `dir` (a board built in [`board_cache`]).
pub fn botsim(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_botsim"))
        .args(args)
        .current_dir(dir)
        .env("BOTSIM_CACHE", board_cache())
        .output()
        .unwrap()
}

/// `botsim board ARGS` in `dir`.
pub fn board_in(dir: &Path, args: &[&str]) -> Output {
    botsim(&[&["board"], args].concat(), dir)
}

/// A command's standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The course reference folder: $BOTSIM_REFERENCE, else ../shared/reference beside the repo.
pub fn reference_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("BOTSIM_REFERENCE")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/reference"));
    dir.join("maps").is_dir().then_some(dir)
}

/// A course map file, or None (with a note) when the reference folder is absent. CI sets
/// BOTSIM_REFERENCE, and there a missing file is an error.
pub fn reference_map(name: &str) -> Option<PathBuf> {
    match reference_dir() {
        Some(d) => {
            let p = d.join("maps").join(name);
            assert!(p.is_file(), "{} is missing", p.display());
            Some(p)
        }
        None => {
            assert!(std::env::var_os("BOTSIM_REFERENCE").is_none(), "BOTSIM_REFERENCE has no maps/ folder");
            eprintln!("note: course maps not found (set BOTSIM_REFERENCE); skipping");
            None
        }
    }
}

/// The course's "Proj2 Bot tracker" for world_map_part1: start, the six turn points and the
/// end, as (LocX, LocY) (reference README).
pub const PART1_TRACKER: [(u8, u8); 8] =
    [(0x40, 0x40), (0x49, 0x40), (0x49, 0x4A), (0x46, 0x4D), (0x33, 0x4D), (0x2C, 0x46), (0x2C, 0x3F), (0x3B, 0x3F)];

/// An 8-bit RGB PNG file: (width, height, pixels).
pub fn decode_png(path: &std::path::Path) -> (u32, u32, Vec<u8>) {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut dec = png::Decoder::new(file).read_info().unwrap();
    let mut buf = vec![0; dec.output_buffer_size().unwrap()];
    let info = dec.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Decode a PNG into (width, height, RGB bytes).
pub fn rgb(png_bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let mut r = png::Decoder::new(std::io::Cursor::new(png_bytes)).read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// The VGA frames `frames` (numbers, in the `--frames` folder) of a run on the built-in world
/// equal, pixel for pixel, botsim's own frame of the bot at `sample` of the run's
/// `--trace-csv`.
pub fn frames_show_sample(dir: &Path, csv: &Path, sample: usize, frames: &[u32]) {
    let text = std::fs::read_to_string(csv).unwrap();
    let row: Vec<u8> = text.lines().nth(sample + 1).unwrap().split(',').skip(2).map(|v| v.parse().unwrap()).collect();
    let snapshot = botsim::Snapshot {
        sample: sample as u64,
        cycle: 0,
        regs: botsim::Registers {
            loc_x: row[0],
            loc_y: row[1],
            bot_info: row[2],
            sensors: row[3],
            lm_dist: row[4],
            rm_dist: row[5],
        },
    };
    let want = rgb(&botsim::render::display::frame(&botsim::World::builtin(), Some(&snapshot)));
    for k in frames {
        let got = rgb(&std::fs::read(dir.join(format!("frame_{k:05}.png"))).unwrap());
        assert_eq!((got.0, got.1), (640, 480));
        if let Some(i) = (0..got.2.len() / 3).find(|&i| got.2[3 * i..3 * i + 3] != want.2[3 * i..3 * i + 3]) {
            panic!(
                "frame {k}: pixel ({}, {}) is {:?}, botsim frame has {:?}",
                i % 640,
                i / 640,
                &got.2[3 * i..3 * i + 3],
                &want.2[3 * i..3 * i + 3]
            );
        }
    }
}

/// Wait for `child` to end, failing the test with `what` if it has not within `budget`.
pub fn exit_within(child: &mut Child, budget: Duration, what: &str) -> ExitStatus {
    let start = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s;
        }
        assert!(start.elapsed() < budget, "{what}");
        std::thread::sleep(Duration::from_millis(20));
    }
}
