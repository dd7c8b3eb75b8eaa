//! Final projects: designs without a bot on the virtual board. examples/nexys4_game (a
//! VGA game: a box that bounces by itself, steered by the buttons, its bounces counted on the
//! display and its place on the LEDs; the team's PicoBlaze interrupted at each vertical
//! sync) is checked against a model of game.psm written from its header: every LED write of
//! the run, the display, and the box in every VGA frame; the fast-forward against every edge;
//! the CPU trace; and one clear line for each option that needs a bot.

use crate::common;

use std::path::Path;

use common::game::{box_place, Game, GAME};
use common::{board_in, root, stderr};
use serde_json::Value;

/// The LED values the firmware writes, in order, when the left button is held for frames
/// `held` (x is written before y, so each frame is two values), and the game after `frames`.
fn expected_leds(frames: usize, held: std::ops::Range<usize>) -> (Vec<u16>, Game) {
    let mut g = Game::start();
    let mut leds = vec![g.x as u16, g.leds()];
    for f in 0..frames {
        g.frame(held.contains(&f));
        leds.push((leds.last().unwrap() & 0xFF00) | g.x as u16);
        leds.push(g.leds());
    }
    (leds, g)
}

/// The LED values and the display texts of a `--display` log, in order.
fn display_log(text: &str) -> (Vec<u16>, Vec<String>) {
    let (mut leds, mut shown) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let rest = line.split_once(" ms  ").map(|(_, r)| r).unwrap_or("");
        if let Some(v) = rest.strip_prefix("leds    ") {
            leds.push(u16::from_str_radix(v.trim(), 2).unwrap());
        } else if let Some(v) = rest.strip_prefix("display ") {
            shown.push(v.to_string());
        }
    }
    (leds, shown)
}

/// Run the game in `dir` (its outputs there); the summary.
fn run(dir: &Path, extra: &[&str]) -> Value {
    let game = root().join(GAME);
    let mut args = vec![game.to_str().unwrap(), "--param", "SIMULATE=1", "--json"];
    args.extend(extra);
    let o = board_in(dir, &args);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn a_game_without_a_bot_runs_every_led_write_and_the_display_as_its_program_says() {
    let dir = tempfile::tempdir().unwrap();
    let v = run(dir.path(), &["--seconds", "3", "--display", "d.txt"]);
    // The summary leaves the bot out.
    for key in ["samples", "end", "blocked_moves"] {
        assert!(v.get(key).is_none(), "{key} in {v}");
    }
    let (leds, shown) = display_log(&std::fs::read_to_string(dir.path().join("d.txt")).unwrap());
    // 60 frames a second for 3 s, less the MMCM's lock and the reset's release.
    let frames = (leds.len() - 2) / 2;
    assert!((170..=180).contains(&frames), "{frames} frames");
    let (want, end) = expected_leds(frames, 0..0);
    assert_eq!(leds, want[..leds.len()], "the LED writes");
    // Two bounces by then (y at frame 96, x at 146), shown in decimal on digits 3-0.
    assert_eq!(end.bounces, 2);
    assert_eq!(shown.last().map(String::as_str), Some("    0002"), "{shown:?}");
    assert_eq!(v["display"], "    0002");
    assert_eq!(v["leds"].as_u64(), Some(end.leds() as u64));
}

#[test]
fn a_held_button_steers_the_box_and_the_fast_forward_equals_every_edge() {
    let dir = tempfile::tempdir().unwrap();
    let press = ["--seconds", "0.6", "--press", "btnL@100+400"];
    held_left_steers(dir.path(), &press);
    // The keyboard's left arrow held as long (E0 6B, then E0 F0 6B) steers it the same way.
    std::fs::write(dir.path().join("key.txt"), "100ms key ArrowLeft 400ms\n").unwrap();
    held_left_steers(dir.path(), &["--seconds", "0.6", "--stimulus", "key.txt"]);
}

/// The box steered by the left button or arrow key held from 100 ms for 400 ms (`press`).
fn held_left_steers(dir: &Path, press: &[&str]) {
    let fast = run(dir, &[press, &["--display", "fast.txt"]].concat());
    let every = run(dir, &[press, &["--display", "every.txt", "--no-fast-forward"]].concat());
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
    assert!(read("fast.txt") == read("every.txt"), "the display logs differ");
    assert_eq!(every["fast_forward"]["skips"], 0);
    assert!(fast["fast_forward"]["skips"].as_u64() > Some(0), "{fast}");
    // Held for 400 ms: from the frame the press is seen (x is 16 or so), the box goes left
    // into the edge and bounces there every other frame until the release (a frame that
    // finds it at 0 going left is the same held or not: the end is known to a frame).
    let (leds, shown) = display_log(&read("fast.txt"));
    let frames = (leds.len() - 2) / 2;
    let fits: Vec<(usize, usize)> = (0..frames)
        .flat_map(|from| (1..frames - from).map(move |n| (from, from + n)))
        .filter(|&(from, to)| expected_leds(frames, from..to).0[..leds.len()] == leds[..])
        .collect();
    assert!(!fits.is_empty(), "no press of the left button explains the LED writes: {leds:x?}");
    for &(from, to) in &fits {
        assert!((5..=8).contains(&from) && (28..=32).contains(&to), "held for frames {from}..{to}: {fits:?}");
    }
    let (_, end) = expected_leds(frames, fits[0].0..fits[0].1);
    assert!(end.bounces >= 4, "{end:?}");
    assert_eq!(shown.last(), Some(&format!("    {:04}", end.bounces)));
}

#[test]
fn every_vga_frame_shows_the_box_where_the_program_put_it() {
    let dir = tempfile::tempdir().unwrap();
    run(dir.path(), &["--seconds", "0.2", "--frames", "frames"]);
    let mut places = Vec::new();
    let mut k = 0;
    while let Ok(png) = std::fs::read(dir.path().join(format!("frames/frame_{k:05}.png"))) {
        places.push(box_place(&png).unwrap_or_else(|e| panic!("frame {k}: {e}")));
        k += 1;
    }
    assert!(places.len() >= 9, "{} frames", places.len());
    // Consecutive frames show consecutive frames of the game.
    let track = Game::track(40);
    let first = track.iter().position(|p| *p == places[0]).expect("the first frame's box on the track");
    assert_eq!(places[..], track[first..first + places.len()], "the box frame by frame");
}

#[test]
fn the_team_cpu_is_traced_without_a_bot() {
    let dir = tempfile::tempdir().unwrap();
    run(dir.path(), &["--seconds", "0.05", "--cpu-trace", "trace"]);
    let trace = std::fs::read_to_string(dir.path().join("trace/GAMECPU.trace.txt")).unwrap();
    assert!(trace.contains("game.psm:"), "{}", &trace[..trace.len().min(2000)]);
    let profile = std::fs::read_to_string(dir.path().join("trace/GAMECPU.profile.txt")).unwrap();
    assert!(profile.contains("wait"), "{profile}");
    // Only the team's CPU: the board has no bot.
    let files: Vec<String> = std::fs::read_dir(dir.path().join("trace"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(files.len(), 2, "{files:?}");
}

#[test]
fn an_option_that_needs_a_bot_is_one_line_on_a_design_without_one() {
    let dir = tempfile::tempdir().unwrap();
    let game = root().join(GAME);
    for (args, want) in [
        (&["--samples", "3"][..], "--samples counts the bot's samples, and the design has no bot: use --seconds"),
        (&["--trace-csv", "t.csv"][..], "--trace-csv records the bot's samples, and the design has no bot"),
        (&["--png", "p.png"][..], "--png draws the bot's path, and the design has no bot (--frames saves"),
        (&["--break", "bot=blocked"][..], "--break bot=blocked: the design has no bot"),
        (&["--vcd", "w.vcd", "--trace-from", "3"][..], "--trace-from N counts the bot's samples"),
    ] {
        let mut a = vec![game.to_str().unwrap(), "--param", "SIMULATE=1", "--quiet"];
        a.extend(args);
        let o = board_in(dir.path(), &a);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert_eq!(e.lines().count(), 1, "{args:?}: {e}");
        assert!(e.contains(want), "{args:?}: {e}");
    }
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none(), "nothing written");
}

#[test]
fn the_bench_measures_a_design_without_a_bot() {
    // The same run as the plain one, beside the all-RTL board (which has no bot to set).
    let dir = tempfile::tempdir().unwrap();
    let plain = run(dir.path(), &["--seconds", "0.05"]);
    let bench = run(dir.path(), &["--seconds", "0.05", "--bench"]);
    assert_eq!(bench["skips"], plain["fast_forward"]["skips"], "{bench}\n{plain}");
    assert!(bench["rtl_mcycles_per_s"].as_f64() > Some(0.0), "{bench}");
    assert!(bench["frames_per_s"].is_null() && bench["vga_frames"] == 0, "no frames asked for: {bench}");
    // With --frames: the frames a second each board simulates and writes, the run's the
    // same frames as the plain run's.
    let frames = dir.path().join("frames");
    let f = frames.to_str().unwrap();
    let plain = run(dir.path(), &["--seconds", "0.05", "--frames", f]);
    let bench = run(dir.path(), &["--seconds", "0.05", "--frames", f, "--bench"]);
    assert_eq!(bench["vga_frames"], plain["vga_frames"], "{bench}\n{plain}");
    assert!(plain["vga_frames"].as_u64() >= Some(2), "{plain}");
    for board in ["frames_per_s", "rtl_frames_per_s"] {
        assert!(bench[board].as_f64() > Some(0.0), "{board}: {bench}");
    }
}

#[test]
fn the_uart_and_ps2_lines_idle_high_and_an_open_collector_pulls_low() {
    // tests/board_designs/idle_lines: RsRx, PS2_DATA and PS2_CLK on LEDs 2-0; switch 0 pulls
    // PS2_CLK low. (Held low, an idle UART line reads as a break, a PS/2 clock as an inhibit.)
    let dir = tempfile::tempdir().unwrap();
    let design = root().join("tests/board_designs/idle_lines");
    for (switches, want) in [("0000", 0b111), ("0001", 0b110)] {
        let o =
            board_in(dir.path(), &[design.to_str().unwrap(), "--seconds", "0.0001", "--switches", switches, "--json"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(v["leds"].as_u64(), Some(want), "switches {switches}: {v}");
    }
}

/// `design` run for `seconds` with the stimulus `stimulus` (written to s.txt) with and without
/// the fast-forward: their `--pins` logs must be equal. The fast run's summary, and the log as
/// (time in clocks of 100 MHz, LEDs) rows.
fn pins_both_ways(dir: &Path, design: &str, seconds: &str, stimulus: &str) -> (Value, Vec<(u64, u16)>) {
    let design = root().join(design);
    std::fs::write(dir.join("s.txt"), stimulus).unwrap();
    let mut runs = Vec::new();
    for ff in [true, false] {
        let pins = dir.join(format!("{ff}.csv"));
        let mut args = vec![design.to_str().unwrap(), "--seconds", seconds, "--stimulus", "s.txt", "--json"];
        args.extend(["--pins", pins.to_str().unwrap()]);
        if !ff {
            args.push("--no-fast-forward");
        }
        let o = board_in(dir, &args);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: Value = serde_json::from_slice(&o.stdout).unwrap();
        runs.push((v, std::fs::read_to_string(&pins).unwrap()));
    }
    assert!(runs[0].1 == runs[1].1, "the fast-forward differs from every edge");
    assert_eq!(runs[1].0["fast_forward"]["skips"], 0);
    let rows = runs[0]
        .1
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0].parse::<u64>().unwrap() / 10_000, u16::from_str_radix(f[4], 16).unwrap())
        })
        .collect();
    (runs.swap_remove(0).0, rows)
}

/// A block built of Xilinx primitives by hand, as the KCPSM6 package's UART macros are
/// (tests/board_designs/primitives: an SRLC32E ring pulsing every 32 clocks steps a counter of
/// FDREs and CARRY4s; a LUT6 and a MUXF7 of the switches): the counter steps exactly every 32
/// clocks, the LUT and the multiplexer follow the switches, and the fast-forward (the design
/// repeats every 8,192 clocks) records what every edge does.
#[test]
fn a_block_of_xilinx_primitives_runs_as_their_library_guides_say() {
    let dir = tempfile::tempdir().unwrap();
    let stimulus = "0 switches 003F\n300us switches 0181\n";
    let (fast, rows) = pins_both_ways(dir.path(), "tests/board_designs/primitives", "0.003", stimulus);
    assert!(fast["fast_forward"]["skips"].as_u64() > Some(0), "{fast}");
    // The counter's steps (the first row is the board at power-up): one every 32 clocks.
    let mut steps: Vec<(u64, u8)> = Vec::new();
    for w in rows.windows(2) {
        if w[1].1 as u8 != w[0].1 as u8 {
            steps.push((w[1].0, w[1].1 as u8));
        }
    }
    for w in steps.windows(2) {
        assert_eq!((w[1].0 - w[0].0, w[1].1), (32, w[0].1.wrapping_add(1)), "the counter at clock {}", w[1].0);
    }
    for &(t, led) in &rows {
        // Switches 5-0 all on: the LUT's bit 63; then 000001: off; MUXF7: S = 1 picks sw[7].
        let (lut, mux) = if t < 30_000 { (true, false) } else { (false, true) };
        assert_eq!((led >> 15 == 1, led >> 14 & 1 == 1), (lut, mux), "LEDs {led:04X} at clock {t}");
    }
    assert!(steps.len() > 9000, "{} steps", steps.len());
}

/// A counter compared with a register that does not hold (tests/board_designs/bounds: a
/// limit alternating every clock between 60,000 and 30,001): the fast-forward skips what
/// repeats and records what every edge does, LED 0 toggling every 30,002 clocks (a
/// fast-forward that took the register for a constant would skip past 30,001). The tone
/// player (tests/boards/peripherals.rs) has a register that holds.
#[test]
fn a_counter_compared_with_a_register_that_changes_keeps_every_edge() {
    let dir = tempfile::tempdir().unwrap();
    let (fast, rows) = pins_both_ways(dir.path(), "tests/board_designs/bounds", "0.04", "20ms switches 0001\n");
    assert!(fast["fast_forward"]["skipped_fraction"].as_f64() > Some(0.5), "{fast}");
    let mut last = 0u16;
    let mut toggles = Vec::new();
    for &(t, led) in &rows {
        if led & 1 != last {
            toggles.push(t);
            last = led & 1;
        }
    }
    assert!(toggles.len() > 100 && toggles.windows(2).all(|w| w[1] - w[0] == 30_002), "{toggles:?}");
}

#[test]
fn trailing_commas_in_a_games_lists_under_a_folder_named_with_a_space_are_read_as_vivado_reads_them() {
    // `.gameover(gameover),` then `);`, a parameter override and a module's port list ending
    // in a comma, in `Verilog files/`: Verilator alone stops (`Duplicate pin connection`);
    // botsim reads each list without its comma, one note a file at the user's path.
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("Verilog files");
    std::fs::create_dir_all(&src).unwrap();
    std::fs::write(
        src.join("top.v"),
        "module top(input clk, input [15:0] sw, output [15:0] led,);\n  wire gameover;\n  scorer #(.W(4),) s (\n    .clk(clk),\n    .sw(sw[3:0]),\n    .gameover(gameover),\n  );\n  assign led = {15'd0, gameover};\nendmodule\n",
    )
    .unwrap();
    std::fs::write(
        src.join("scorer.v"),
        "module scorer #(parameter W = 2) (input clk, input [W-1:0] sw, output reg gameover = 1'b0);\n  always @(posedge clk) gameover <= &sw;\nendmodule\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("s.txt"), "0.2ms switches 000F\n").unwrap();
    let o = board_in(dir.path(), &[".", "--seconds", "0.001", "--stimulus", "s.txt", "--json"]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    let s: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(s["leds"], 1, "the four switches reach `gameover` through the override's width: {s}");
    let o = board_in(dir.path(), &[".", "--seconds", "0.001"]);
    let e = stderr(&o);
    let note = e.lines().find(|l| l.contains("a comma before the `)`")).unwrap_or_else(|| panic!("{e}"));
    assert_eq!(
        note,
        "note: Verilog files/top.v:1:57: a comma before the `)` that ends the ports of module `top` (Verilog has no empty item there; Vivado reads the list without it): botsim reads it so (2 more in the file)"
    );
    assert!(!e.contains("pinNumber") && !e.contains("%Error"), "{e}");
}

#[test]
fn verilators_findings_in_folders_named_with_spaces_commas_and_accents_are_said_at_the_users_path() {
    // Verilator 5.006 cuts a file's name at its first space in what it prints; botsim gives
    // it such files by plain names and says its findings at the user's own path.
    let dir = tempfile::tempdir().unwrap();
    let folder = "Verilog files, v2 & (jeu é)";
    let src = dir.path().join(folder);
    std::fs::create_dir_all(&src).unwrap();
    std::fs::write(
        src.join("top.v"),
        "module top(input clk, input [15:0] sw, output [15:0] led);\n  lamp u (.a(sw[0]), .b(led[0]), .c(led[1]));\n  assign led[15:2] = 0;\nendmodule\n",
    )
    .unwrap();
    std::fs::write(src.join("lamp.v"), "module lamp(input a, output b);\n  assign b = a;\nendmodule\n").unwrap();
    let o = board_in(dir.path(), &[".", "--seconds", "0.001"]);
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert_eq!(
        e.lines().last(),
        Some(format!("{folder}/top.v:2:35: `lamp` has no port `c` (its ports: a, b)").as_str()),
        "{e}"
    );
    // Fixed, it runs from there.
    std::fs::write(
        src.join("top.v"),
        "module top(input clk, input [15:0] sw, output [15:0] led);\n  lamp u (.a(sw[0]), .b(led[0]));\n  assign led[15:1] = 0;\nendmodule\n",
    )
    .unwrap();
    let o = board_in(dir.path(), &[".", "--seconds", "0.001"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// `words` 12-bit words of a screen, different for each `seed`.
fn screen_words(seed: u64, words: usize) -> Vec<u64> {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..words)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x & 0xFFF
        })
        .collect()
}

#[test]
fn memory_cores_without_configuration_take_the_coe_that_fits_and_resembles_their_name() {
    // A game's screens committed as cores without configuration (`player1wins`, `tie`...)
    // beside `.coe` files named otherwise (`Player1_wins_final.coe`), a frame buffer with a
    // write port and no `.coe`, in folders named as users name them.
    let dir = tempfile::tempdir().unwrap();
    let (src, art) = (dir.path().join("Verilog files"), dir.path().join("IP & art (v2)"));
    std::fs::create_dir_all(&src).unwrap();
    std::fs::create_dir_all(&art).unwrap();
    std::fs::write(
        src.join("top.v"),
        "module top(input clk, input btnCpuReset, input [15:0] sw, output [15:0] led);\n\
         \x20 wire [9:0] addr = sw[9:0];\n\
         \x20 wire [11:0] p1, p2, t, g;\n\
         \x20 wire [7:0] fbq;\n\
         \x20 player1wins P1 (.clka(clk), .addra(addr), .douta(p1));\n\
         \x20 player2wins P2 (.clka(clk), .addra(addr), .douta(p2));\n\
         \x20 tie T (.clka(clk), .addra(addr), .douta(t));\n\
         \x20 game_init G (.clka(clk), .addra(addr), .douta(g));\n\
         \x20 frame_buffer FB (.clka(clk), .wea(sw[15]), .addra(addr), .dina({sw[14:10], 3'b101}), .douta(fbq));\n\
         \x20 assign led = sw[14] ? {fbq, 8'd0} : {4'd0, p1 ^ p2 ^ t ^ g};\n\
         endmodule\n",
    )
    .unwrap();
    let files = ["Player1_wins_final", "Player2_wins_final", "tie_final", "start_screen_key"];
    let mut screens = Vec::new();
    for (k, name) in files.iter().enumerate() {
        let words = screen_words(k as u64 + 1, 1000);
        let vector: Vec<String> = words.iter().map(|w| format!("{w:03X}")).collect();
        let text = format!("memory_initialization_radix=16;\nmemory_initialization_vector=\n{};\n", vector.join(",\n"));
        std::fs::write(art.join(format!("{name}.coe")), text).unwrap();
        screens.push(words);
    }
    // A file too deep for the 10-bit address is never offered.
    std::fs::write(
        art.join("game_init_big.coe"),
        format!("memory_initialization_radix=16;\nmemory_initialization_vector=\n{};\n", vec!["0"; 2000].join(",")),
    )
    .unwrap();

    // `game_init`'s name resembles no file's: one line at the instance, the files that fit
    // closest first (those closer to another core's name last), ready to paste.
    let o = board_in(dir.path(), &[".", "--seconds", "0.0001"]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert_eq!(
        e.lines().nth(1).map(str::trim),
        Some(
            "Verilog files/top.v:8:3: `game_init` (instance `G` in `top`): a memory core with no configuration and no game_init.coe, and no .coe's name resembles the module's; those that fit its 10-bit address and 12-bit data, closest first: start_screen_key.coe, tie_final.coe (closer to `tie`), Player1_wins_final.coe (closer to `player1wins`), Player2_wins_final.coe (closer to `player2wins`); --memory game_init=start_screen_key.coe names the first (or another FILE), or tie it off with --stub game_init"
        ),
        "{e}"
    );
    assert!(!e.contains("game_init_big"), "{e}");

    let run = |sw: u32| {
        let sw = format!("{sw:04X}");
        let args =
            [".", "--memory", "game_init=start_screen_key.coe", "--switches", &sw, "--seconds", "0.0001", "--json"];
        let o = board_in(dir.path(), &args);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_slice::<Value>(&o.stdout).unwrap()
    };
    let o = board_in(dir.path(), &[".", "--memory", "game_init=start_screen_key.coe", "--seconds", "0.0001"]);
    let said = stderr(&o);
    assert!(o.status.success(), "{said}");
    for (module, file) in
        [("player1wins", "Player1_wins_final"), ("player2wins", "Player2_wins_final"), ("tie", "tie_final")]
    {
        let note = format!(
            "note: `{module}` (instance `{}` in `top`) is a memory core with no configuration and no {module}.coe: its contents are {file}.coe, whose 1000 words fit its 10-bit address and 12-bit data and whose name is the closest to the module's (name another with --memory {module}=FILE)",
            match module { "player1wins" => "P1", "player2wins" => "P2", _ => "T" }
        );
        assert!(said.lines().any(|l| l == note), "{note}\n{said}");
    }
    assert!(
        said.lines().any(|l| l
            == "note: `frame_buffer` (instance `FB` in `top`) is a memory core with no configuration and no frame_buffer.coe, with a write port: a RAM of 1024 x 8 bits (what its 10-bit address and 8-bit data reach) starting at zero, as the Block Memory Generator makes one without a .coe"),
        "{said}"
    );
    // Each screen reads its own file: the LEDs show the four words at the address XORed.
    for addr in [0u32, 1, 517, 999] {
        let want = screens.iter().fold(0, |x, s| x ^ s[addr as usize]);
        let s = run(addr);
        assert_eq!(s["leds"].as_u64(), Some(want), "address {addr}: {s}");
    }
    // The frame buffer reads 0 where nothing was written, and what is written (write-first).
    assert_eq!(run(0x4000 | 3)["leds"].as_u64(), Some(0), "a RAM starting at zero");
    assert_eq!(run(0x8000 | 0x7C00 | 3)["leds"].as_u64(), Some(0xFD00), "written {{11111, 101}}");
}

#[test]
fn includes_and_memory_files_in_folders_named_with_spaces_and_accents_are_found() {
    // `include` of a file in a folder of its own, `$readmemh` of a file whose name has a
    // space and an accent: as Vivado finds them.
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("Verilog files");
    std::fs::create_dir_all(src.join("incl (v2)")).unwrap();
    std::fs::write(
        src.join("top.v"),
        "`include \"defs.vh\"\nmodule top(input clk, input [15:0] sw, output [15:0] led);\n  reg [15:0] rom [0:3];\n  initial $readmemh(\"pic data é.mem\", rom);\n  assign led = rom[sw[1:0]] ^ `MASK;\nendmodule\n",
    )
    .unwrap();
    std::fs::write(src.join("incl (v2)/defs.vh"), "`define MASK 16'h00F0\n").unwrap();
    std::fs::write(src.join("pic data é.mem"), "1234\n5678\n9abc\ndef0\n").unwrap();
    for (sw, want) in [("0001", 0x5688), ("0003", 0xDE00)] {
        let o = board_in(dir.path(), &[".", "--switches", sw, "--seconds", "0.0001", "--json"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let s: Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(s["leds"], want, "switches {sw}: {s}");
    }
}
