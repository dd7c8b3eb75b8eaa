//! The fast-forward on random board designs (tests/common/random_design.rs): each design's
//! run under random switch changes, presses and a CPU reset (and, for a design with the
//! board's UART or keyboard, text and keys at random times) must record exactly what the run
//! that simulates every edge records (every pin change of the display and the LEDs, the bot's
//! samples, the display as read, every change of the peripherals' lines), with the pins asked
//! for and without them (the display decoder then takes the skipped periods whole); and a
//! design the generator knows to repeat within reach must skip at least 95 % of its run. A
//! design with a net of several drivers is warned of once (Vivado's DRC MDRV-1) and records
//! what the same design with the net's resolution written out by hand records (seed 1 has one:
//! two `assign`s to one wire).
//!
//! `BOTSIM_RANDOM_DESIGNS` (default 2) designs from seed `BOTSIM_RANDOM_SEED` (default 1) on,
//! and the seeds of `BOTSIM_RANDOM_ALSO` (default 28, 316, 3086, 88 and 123: a second bot and a
//! watchdog, a nested delay, a team's VGA timing generator, a watchdog whose heartbeat clears
//! it in the middle of a period, two free parts), and the first `BOTSIM_RANDOM_GAMES`
//! (default 1) from the first seed on with a game (seed 17: a frame tick whose limit the game's
//! state chooses interrupts the team CPU, whose firmware places a sprite and reads a
//! collision flag and the raster's comparison); seed 1 has a second KCPSM6 in nested delays;
//! each design is kept in target/random-designs/<seed>/ (its parts listed in parts.txt), and
//! its runs' outputs beside it when they differ (a design whose LEDs show an LFSR writes
//! gigabytes of pin changes: kept only when there is something to look at).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use crate::common;

use common::random_design::{generate, Design};
use common::root;

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// What one run recorded.
struct Run {
    pins: Option<String>,
    lines: String,
    trace: String,
    display: String,
    summary: serde_json::Value,
    /// What botsim said on the way (its warnings).
    said: String,
}

fn run(d: &Design, dir: &Path, name: &str, fast_forward: bool, pins: bool) -> Run {
    let file = |n: &str| dir.join(format!("{name}.{n}")).to_str().unwrap().to_string();
    let (pins_f, trace, display, lines) = (file("pins.csv"), file("trace.csv"), file("display.txt"), file("lines.csv"));
    let simulate = format!("SIMULATE={}", d.simulate as u8);
    let seconds = d.seconds.to_string();
    let mut args = vec![
        ".",
        "--param",
        &simulate,
        "--seconds",
        &seconds,
        "--stimulus",
        "stimulus.txt",
        "--trace-csv",
        &trace,
        "--display",
        &display,
        "--lines",
        &lines,
        "--json",
    ];
    if pins {
        args.extend(["--pins", &pins_f]);
    }
    if !fast_forward {
        args.push("--no-fast-forward");
    }
    let o = common::board_in(dir, &args);
    assert!(
        o.status.success(),
        "seed {}: {name}: {}\n{}",
        d.seed,
        String::from_utf8_lossy(&o.stderr),
        d.parts.join("\n")
    );
    let read = |p: &str| std::fs::read_to_string(p).unwrap();
    Run {
        pins: pins.then(|| read(&pins_f)),
        lines: read(&lines),
        trace: read(&trace),
        display: read(&display),
        summary: serde_json::from_slice(&o.stdout).unwrap(),
        said: String::from_utf8_lossy(&o.stderr).into_owned(),
    }
}

/// The first row where two logs differ, for the message.
fn first_difference(a: &str, b: &str) -> String {
    let (a, b): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    let i = a.iter().zip(&b).position(|(x, y)| x != y).unwrap_or(a.len().min(b.len()));
    format!("row {i}: every edge {:?}, fast-forward {:?} ({} and {} rows)", a.get(i), b.get(i), a.len(), b.len())
}

/// One design: the runs compared, the skip checked. Returns the fraction skipped, or what
/// went wrong.
fn check(seed: u64) -> Result<f64, String> {
    std::panic::catch_unwind(|| check_one(seed)).map_err(|e| {
        e.downcast_ref::<String>()
            .cloned()
            .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default()
    })
}

fn check_one(seed: u64) -> f64 {
    let d = generate(seed);
    let dir: PathBuf = root().join("target/random-designs").join(seed.to_string());
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    d.write(&dir);
    let about = || format!("seed {seed} ({}):\n{}", dir.display(), d.parts.join("\n"));
    let every = run(&d, &dir, "every", false, true);
    let fast = run(&d, &dir, "fast", true, false);
    let fast_pins = run(&d, &dir, "fast_pins", true, true);
    assert_eq!(every.summary["fast_forward"]["skips"], 0, "{}", about());
    // A net with several drivers is warned of, as Vivado's DRC names it (the second bot's
    // distances on the team bot's wires: both nets); no other net is.
    for (name, r) in [("every", &every), ("fast", &fast)] {
        let warned = r.said.matches("DRC MDRV-1").count();
        match &d.shared {
            Some(net) => assert!(
                r.said.contains(&format!("`{net}` in `nexys4fpga` has 2 drivers")) && warned <= 2,
                "{name}: {}\n{}",
                r.said,
                about()
            ),
            None => assert_eq!(warned, 0, "{name}: {}\n{}", r.said, about()),
        }
    }
    assert!(every.trace.lines().count() >= 2, "no bot sample: {}", about());
    let every_pins = every.pins.as_deref().unwrap();
    for (what, a, b) in [
        ("--pins", every_pins, fast_pins.pins.as_deref().unwrap()),
        ("--trace-csv", &every.trace, &fast.trace),
        ("--trace-csv (with --pins)", &every.trace, &fast_pins.trace),
        ("--display", &every.display, &fast.display),
        ("--display (with --pins)", &every.display, &fast_pins.display),
        ("--lines", &every.lines, &fast.lines),
    ] {
        assert!(a == b, "{what}: {}\n{}", first_difference(a, b), about());
    }
    // A net with several drivers records what the same design with the net's resolution
    // written out records (each driver on a wire of its own, the net their AND).
    if let Some(top) = &d.resolved {
        let by_hand = dir.join("resolved");
        std::fs::create_dir_all(&by_hand).unwrap();
        d.write(&by_hand);
        std::fs::write(d.top_file(&by_hand), top).unwrap();
        let r = run(&d, &by_hand, "fast_pins", true, true);
        assert!(!r.said.contains("DRC MDRV-1"), "resolved by hand: {}\n{}", r.said, about());
        for (what, a, b) in [
            ("--pins", every_pins, r.pins.as_deref().unwrap()),
            ("--trace-csv", &every.trace, &r.trace),
            ("--display", &every.display, &r.display),
            ("--lines", &every.lines, &r.lines),
        ] {
            assert!(a == b, "resolved by hand: {what}: {}\n{}", first_difference(a, b), about());
        }
        let _ = std::fs::remove_dir_all(&by_hand);
    }
    // Every other bot's trace, beside the first's (named by its instance path).
    let others = |name: &str| -> Vec<(String, String)> {
        let prefix = format!("{name}.trace.");
        let mut found: Vec<(String, String)> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|f| f.starts_with(&prefix) && f.ends_with(".csv") && f.len() > prefix.len() + ".csv".len())
            .map(|f| (f[prefix.len()..].to_string(), std::fs::read_to_string(dir.join(&f)).unwrap()))
            .collect();
        found.sort();
        found
    };
    let every_others = others("every");
    assert_eq!(every_others.len(), usize::from(d.monster.is_some()), "{}", about());
    for name in ["fast", "fast_pins"] {
        let theirs = others(name);
        assert_eq!(theirs.len(), every_others.len(), "{name}: {}", about());
        for ((path, a), (_, b)) in every_others.iter().zip(&theirs) {
            assert!(a.lines().count() >= 2, "the second bot {path} has no sample: {}", about());
            assert!(a == b, "{name}: the second bot's trace ({path}): {}\n{}", first_difference(a, b), about());
        }
    }
    let ff = &fast.summary["fast_forward"];
    // What kept it busy is named in the design's words (a variable or port of its source,
    // or a part of botsim's board), never by a name only Verilator knows.
    if let Some(module) = ff["kept_busy_by"]["module"].as_str() {
        assert!(!module.contains("Verilator's own"), "{ff}: {}", about());
    }
    let skipped = ff["skipped_seconds"].as_f64().unwrap() / fast.summary["simulated_seconds"].as_f64().unwrap();
    if let Ok(period) = d.reach {
        assert!(
            skipped >= 0.95,
            "periodic every {period} clocks, yet skipped {:.1} % ({ff}): {}",
            skipped * 100.0,
            about()
        );
    }
    eprintln!(
        "seed {seed}: skipped {:.1} % ({}), {} pin changes, equal",
        skipped * 100.0,
        match &d.reach {
            Ok(p) => format!("periodic every {p} clocks"),
            Err(why) => why.clone(),
        },
        every_pins.lines().count() - 1
    );
    for e in std::fs::read_dir(&dir).unwrap().flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        if ["every.", "fast.", "fast_pins."].iter().any(|run| name.starts_with(run)) {
            let _ = std::fs::remove_file(e.path());
        }
    }
    skipped
}

/// Seeds checked besides the range, so that every run meets the generator's newer classes:
/// 28 (a second bot in the world, a watchdog), 316 (a delay of three nested loops), 3086 (VGA
/// from the team's own timing generator on a DCM's CLKDV, counting its totals inclusively,
/// skipped whole: 189 was, until a free part took one of its parts and with it the claim),
/// 88 (a watchdog armed every 2^15 clocks whose heartbeat, every 1138, may first clear it in
/// the middle of the first period after the arming: its records differed from every edge's
/// at the second pin change when one period was taken for proof; so did 305's and, before
/// the watchdog's heartbeats grew longer, 292's), 123 (two free parts: LFSRs stepped at baud
/// ticks beside idle transmitters, whose contacts the random buttons change; 22 was, until a
/// second KCPSM6 that reads a port its mux leaves out took one of its plain parts). A sprite
/// on the raster whose pixel an LED shows (pdxrayw_p2video's icon) is checked edge for edge
/// in 62, 67, 87, 102, 250 and 295 (each a variant: constant or moving, nested or one `if`,
/// `?:`), locally; CI checks its shape in tests/boards/shapes.rs. `BOTSIM_RANDOM_ALSO`
/// replaces them (empty: none).
const ALSO: &str = "28,316,3086,88,123";

#[test]
fn random_designs_record_what_every_edge_does_and_skip_what_repeats() {
    let first = env("BOTSIM_RANDOM_SEED", 1);
    let count = env("BOTSIM_RANDOM_DESIGNS", 2);
    let also = std::env::var("BOTSIM_RANDOM_ALSO").unwrap_or_else(|_| ALSO.into());
    let also: Vec<u64> = also.split(',').filter_map(|s| s.trim().parse().ok()).collect();
    // And the first `BOTSIM_RANDOM_GAMES` (default 1) designs from there with a game's logic
    // and firmware (never quiet: a frame tick interrupting the CPU, a raster it reads).
    let games = env("BOTSIM_RANDOM_GAMES", 1) as usize;
    let games = (first..first + 5_000).filter(|s| generate(*s).game).take(games);
    let mut seeds: Vec<u64> = (first..first + count).chain(also).collect();
    for g in games {
        if !seeds.contains(&g) {
            seeds.push(g);
        }
    }
    // Every design is tried, as many at once as the machine has cores (each run is one
    // thread: a design's build and its runs leave the other cores idle); the failures are
    // listed at the end, by seed.
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get()).clamp(1, seeds.len().max(1));
    let next = AtomicUsize::new(0);
    let failed = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| {
                while let Some(&seed) = seeds.get(next.fetch_add(1, Ordering::Relaxed)) {
                    if let Err(e) = check(seed) {
                        failed.lock().unwrap().push((seed, e));
                    }
                }
            });
        }
    });
    let mut failed = failed.into_inner().unwrap();
    failed.sort();
    let failed: Vec<String> = failed.into_iter().map(|(_, e)| e).collect();
    assert!(failed.is_empty(), "{} of {} designs failed:\n\n{}", failed.len(), seeds.len(), failed.join("\n\n"));
}

/// The parts of `BOTSIM_RANDOM_DESIGNS` designs from `BOTSIM_RANDOM_SEED` on, without running
/// them: `cargo test --release --test boards random_designs::parts -- --ignored --nocapture`.
#[test]
#[ignore = "a listing for developers"]
fn parts() {
    let first = env("BOTSIM_RANDOM_SEED", 1);
    for seed in first..first + env("BOTSIM_RANDOM_DESIGNS", 2) {
        println!("{}\n", generate(seed).parts.join("\n"));
    }
}
