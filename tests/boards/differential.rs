//! The fast board against the all-RTL board: `botsim board --check` on the project's own
//! designs under random stimuli (`--random-stimulus`), and a game whose two bots drive the
//! same wires (tests/board_designs/repos/two_drivers): warned, and resolved alike on every
//! board. scripts/dev/corpus.py runs the same check on the real repositories.

use crate::common;

use common::repo::clone_of;
use common::{board_in, root, stderr};

/// What `--check` says when every record is equal.
const EQUAL: &str = "check: equal to the all-RTL board, every record: ";

#[test]
fn the_example_boards_equal_the_all_rtl_board_under_random_stimuli() {
    let dir = tempfile::tempdir().unwrap();
    let frames = dir.path().join("frames");
    let frames = frames.to_str().unwrap();
    for (design, seed, seconds, extra) in [
        ("examples/nexys4_proj2", "11", "0.03", &["--timing", "fast"][..]),
        ("examples/nexys4_vga", "12", "0.06", &["--frames", frames][..]),
    ] {
        let mut args = vec!["examples/common", design, "--param", "SIMULATE=1", "--seconds", seconds];
        args.extend(["--random-stimulus", seed, "--check"]);
        args.extend(extra);
        let o = board_in(&root(), &args);
        let e = stderr(&o);
        assert!(o.status.success(), "{design}: {e}");
        assert!(e.contains("  random stimulus ") && e.contains(" press btnCpuReset "), "{design}: {e}");
        let said = e.lines().find(|l| l.starts_with(EQUAL)).unwrap_or_else(|| panic!("{design}: {e}"));
        for record in ["--pins (", "--display (", "--lines (", "--trace-csv (", "--design-log ("] {
            assert!(said.contains(record), "{design}: {said}");
        }
        if design.ends_with("vga") {
            let n: u32 = said.split("--frames (").nth(1).and_then(|r| r.split(' ').next()?.parse().ok()).unwrap_or(0);
            assert!(n >= 2, "{said}");
        }
    }
}

#[test]
fn a_board_without_a_bot_equals_the_all_rtl_board_with_its_uart_and_keyboard() {
    // The console design: text typed on the UART and keys of the keyboard, echoed; no bot,
    // so neither a bot trace nor --bot on the all-RTL side.
    let o =
        board_in(&root(), &["tests/board_designs/console", "--seconds", "0.02", "--random-stimulus", "21", "--check"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(e.contains(" uart \"") && e.contains(" key "), "the stimulus types on both: {e}");
    let said = e.lines().find(|l| l.starts_with(EQUAL)).unwrap_or_else(|| panic!("{e}"));
    assert!(said.contains("--uart (") && said.contains("--lines (") && !said.contains("--trace-csv"), "{said}");
}

#[test]
fn the_same_seed_gives_the_same_random_stimulus_and_another_seed_another() {
    let said = |seed: &str| {
        let o = board_in(
            &root(),
            &["examples/common", "examples/nexys4_proj2", "--seconds", "0.002", "--random-stimulus", seed],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        let e = stderr(&o);
        e.lines()
            .filter(|l| l.starts_with("    ") && l.contains(" press ") || l.contains(" switches "))
            .map(String::from)
            .collect::<Vec<_>>()
    };
    let (a, b) = (said("5"), said("6"));
    assert!(a.len() >= 10, "{a:?}");
    assert_eq!(a, said("5"));
    assert_ne!(a, b);
}

#[test]
fn two_bots_driving_the_same_wires_are_warned_and_resolved_alike_on_every_board() {
    let game = clone_of("two_drivers");
    let d = game.path();
    // One warning a net, at its first driver, naming both places as Vivado's DRC would.
    let args = [".", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.25", "--trace-csv", "t.csv"];
    let o = board_in(d, &args);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    let warned: Vec<&str> = e.lines().filter(|l| l.contains("Multiple Driver Nets")).collect();
    assert_eq!(warned.len(), 2, "{e}");
    for (net, port) in [("lmdist", "LMDist_reg"), ("rmdist", "RMDist_reg")] {
        let w = warned.iter().find(|l| l.contains(&format!("`{net}` in `proj2_system` has 2 drivers"))).unwrap();
        assert!(w.starts_with("warning: src/proj2_system.v:68:"), "{w}");
        assert!(w.contains(&format!("output `{port}` of `bot_66` (src/proj2_system.v:68:")), "{w}");
        assert!(w.contains(&format!("output `{port}` of `bot31_74` (src/proj2_system.v:76:")), "{w}");
    }
    // The LEDs show {lmdist, rmdist}: what both bots' registers agree on, bit for bit (each
    // bot's own registers are in its trace), not whichever the simulator evaluated last. The
    // hero (fast timing) moves on every 2,000 clocks, the monster (its own ROM, hw timing)
    // every 50 ms: at every change of the LEDs, they are a bit-subset of the monster's
    // distances then, and at the end they are the AND of both bots' last.
    let o = board_in(d, &[&args[..], &["--display", "d.txt", "--json"]].concat());
    let s: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = |f: &str| -> Vec<Vec<u64>> {
        let text = std::fs::read_to_string(d.join(f)).unwrap();
        text.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect()
    };
    let (hero, monster) = (rows("t.csv"), rows("t.SYS.bot31_74.csv"));
    let display = std::fs::read_to_string(d.join("d.txt")).unwrap();
    let mut checked = 0;
    for l in display.lines().filter(|l| l.contains(" leds ")) {
        let w: Vec<&str> = l.split_whitespace().collect();
        let (ms, leds) = (w[0].parse::<f64>().unwrap(), u64::from_str_radix(w[3], 2).unwrap());
        let cycle = (ms * 1e5) as u64;
        // Not within 10 us of a monster sample (its registers change in the pulse).
        if monster.iter().any(|r| r[1].abs_diff(cycle) < 1_000) {
            continue;
        }
        let Some(m) = monster.iter().rev().find(|r| r[1] < cycle) else { continue };
        assert_eq!(leds >> 8 & !m[6], 0, "{l}: the monster's distances {m:?}");
        assert_eq!(leds & 0xFF & !m[7], 0, "{l}: the monster's distances {m:?}");
        checked += 1;
    }
    assert!(checked > 1_000, "{checked} LED changes");
    let (h, m) = (hero.last().unwrap(), monster.last().unwrap());
    assert!(m[6] != 0 && h[6] & m[6] != h[6], "a run that tells the resolutions apart: {h:?} {m:?}");
    assert_eq!(s["leds"].as_u64().unwrap(), (h[6] & m[6]) << 8 | (h[7] & m[7]), "{h:?} {m:?}");
    // Every board alike: the bot's model and the ISS beside the all-RTL board.
    let o = board_in(d, &[".", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.02", "--check"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(e.contains(EQUAL), "{e}");
}

/// Random designs (tests/common/random_design.rs) against the all-RTL board under a random
/// stimulus of their seed: one of each way the generator gives a net several drivers (the
/// second bot's distances on the team bot's wires, an `assign` to the bot's output, two
/// `assign`s to one wire), the first of each from `BOTSIM_DIFFERENTIAL_SEED` (default 1) on,
/// the first with a game (a frame tick interrupting the CPU, a raster it reads), and
/// `BOTSIM_DIFFERENTIAL_DESIGNS` (default 0) designs of any kind from there. Each is kept
/// in target/random-differential/<seed>/.
#[test]
fn random_designs_with_shared_nets_equal_the_all_rtl_board() {
    use common::random_design::generate;
    let env = |name: &str, default: u64| std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default);
    let first = env("BOTSIM_DIFFERENTIAL_SEED", 1);
    let mut seeds: Vec<u64> = (first..first + env("BOTSIM_DIFFERENTIAL_DESIGNS", 0)).collect();
    for kind in ["the second bot's distances", "the team bot's RMDist and", "(`assign shared ="] {
        let shaped = |s: &u64| generate(*s).parts.iter().any(|p| p.contains("two drivers") && p.contains(kind));
        let seed = (first..first + 5_000).find(shaped).unwrap_or_else(|| panic!("no design with {kind}"));
        if !seeds.contains(&seed) {
            seeds.push(seed);
        }
    }
    // And the first with a game's logic and firmware.
    let game = (first..first + 5_000).find(|s| generate(*s).game).expect("no design with a game");
    if !seeds.contains(&game) {
        seeds.push(game);
    }
    let check = |seed: u64| -> Result<(), String> {
        let d = generate(seed);
        let dir = root().join("target/random-differential").join(seed.to_string());
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        d.write(&dir);
        let (simulate, seconds, stimulus) =
            (format!("SIMULATE={}", d.simulate as u8), d.seconds.to_string(), seed.to_string());
        let o = board_in(
            &dir,
            &[".", "--param", &simulate, "--seconds", &seconds, "--random-stimulus", &stimulus, "--check"],
        );
        let e = stderr(&o);
        let about = || format!("seed {seed} ({}):\n{}\n{e}", dir.display(), d.parts.join("\n"));
        if !o.status.success() || !e.contains(EQUAL) {
            return Err(about());
        }
        if let Some(net) = &d.shared {
            if !e.contains(&format!("`{net}` in `nexys4fpga` has 2 drivers")) {
                return Err(format!("no warning for `{net}`: {}", about()));
            }
        }
        Ok(())
    };
    // Two at a time (each run is one thread).
    let failed: Vec<String> = std::thread::scope(|s| {
        let runs: Vec<_> = seeds
            .chunks(seeds.len().div_ceil(2))
            .map(|c| s.spawn(move || c.iter().map(|&seed| check(seed)).collect::<Vec<_>>()))
            .collect();
        runs.into_iter().flat_map(|r| r.join().unwrap()).filter_map(Result::err).collect()
    });
    assert!(failed.is_empty(), "{} of {} designs differ:\n\n{}", failed.len(), seeds.len(), failed.join("\n\n"));
}
