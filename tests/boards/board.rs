//! `botsim board` on real board designs: the example Nexys4 Project 2 designs
//! (examples/common with examples/nexys4_proj2, or with examples/nexys4_vga for the VGA
//! display: their own KCPSM6 and firmware, debounce, seven-segment driver, interface, a
//! Clocking-Wizard-style MMCM, DTG, icon and colorizer), a clock test design, and small broken
//! designs for the errors. Each design is verilated and
//! compiled once per cache folder (target/botsim-board-cache).

use std::path::Path;
use std::process::{Command, Output};

use crate::common;

use common::root;

fn board(args: &[&str]) -> Output {
    common::board_in(&root(), args)
}

/// `botsim board` on an example design (examples/common with the top in `top_dir`), its
/// debounce in simulation mode, with `args`.
fn example(top_dir: &str, args: &[&str]) -> Output {
    let mut all = vec!["examples/common", top_dir, "--param", "SIMULATE=1"];
    all.extend_from_slice(args);
    board(&all)
}

/// The Project 2 example running the line follower (examples/common/linefollow.psm) at `fast`
/// timing, as the course maps were made (`--compat botsim20`), with `extra` arguments.
fn follower(extra: &[&str]) -> Output {
    let mut args = vec!["--program", "examples/common/linefollow.psm", "--timing", "fast", "--compat", "botsim20"];
    args.extend_from_slice(extra);
    example("examples/nexys4_proj2", &args)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The spec's hexadecimal glyphs as the display decoder names them (board.md 1).
fn hex(v: u8) -> char {
    "0123456789AbCdEF".as_bytes()[v as usize & 15] as char
}

#[test]
fn the_example_design_shows_the_bots_registers_on_its_display() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, disp) = (dir.path().join("t.csv"), dir.path().join("d.txt"));
    let o = example(
        "examples/nexys4_proj2",
        &["--seconds", "0.045", "--trace-csv", csv.to_str().unwrap(), "--display", disp.to_str().unwrap(), "--json"],
    );
    let summary = summary(&o);
    assert_eq!(summary["top"], "nexys4fpga");
    // hw timing: sample 0 after reset (released at 1 ms), sample 1 right after, the next
    // ~50 ms later.
    let rows: Vec<Vec<u64>> = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2, "{rows:?}");
    let last = &rows[1];
    let (x, y, info, sensors) = (last[2] as u8, last[3] as u8, last[4] as u8, last[5] as u8);
    // The firmware writes LocX to digits 7-6, LocY to 5-4, the heading to digit 0, the
    // sensors to LED[7:0]: what the display decoder reads must be those registers.
    let want = format!("{}{}{}{}   {}", hex(x >> 4), hex(x), hex(y >> 4), hex(y), hex(info & 7));
    let log = std::fs::read_to_string(&disp).unwrap();
    let shown: Vec<&str> = log.lines().filter(|l| l.contains("display")).collect();
    assert_eq!(shown.last().unwrap().split("display ").nth(1).unwrap(), want, "{log}");
    assert_eq!(summary["display"], want);
    assert_eq!(summary["leds"].as_u64().unwrap(), sensors as u64);
    // The reset is held by the debounce until 1 ms: the first sample is just after it.
    let first_cycle = rows[0][1];
    assert!((100_000..101_000).contains(&first_cycle), "{first_cycle}");
}

#[test]
fn the_trace_follows_the_samples_asked_for_and_reruns_reuse_the_build() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("t.csv");
    let a = ["--timing", "fast", "--samples", "40", "--trace-csv", csv.to_str().unwrap()];
    let first = example("examples/nexys4_proj2", &a);
    assert!(first.status.success(), "{}", stderr(&first));
    let again = example("examples/nexys4_proj2", &a);
    assert!(again.status.success());
    assert!(stderr(&again).contains("reused the build"), "{}", stderr(&again));
    // The same sources named by absolute paths (as a suite file gives them): the same build.
    let (common, top) = (root().join("examples/common"), root().join("examples/nexys4_proj2"));
    let mut args = vec![common.to_str().unwrap(), top.to_str().unwrap(), "--param", "SIMULATE=1"];
    args.extend_from_slice(&a);
    let absolute = board(&args);
    assert!(stderr(&absolute).contains("reused the build"), "{}", stderr(&absolute));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), "sample,cycle,loc_x,loc_y,bot_info,sensors,lm_dist,rm_dist");
    let rows: Vec<&str> = lines.collect();
    // Samples 0 (the dump after reset) to 40, as botsim run --samples 40 gives.
    assert_eq!(rows.len(), 41);
    assert!(rows[40].starts_with("40,"));
    // Driving forward (switches off) from (64, 64) facing east: LocX grows.
    let x = |r: &str| r.split(',').nth(2).unwrap().parse::<u32>().unwrap();
    assert!(x(rows[40]) > x(rows[0]), "{rows:?}");
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// The `--json` summary of a run that must have succeeded.
fn summary(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", stderr(o));
    serde_json::from_slice(&o.stdout).unwrap()
}

fn one_line_error(o: &Output) -> String {
    assert_eq!(o.status.code(), Some(1), "{}", stderr(o));
    let e = stderr(o);
    let errors: Vec<&str> =
        e.lines().filter(|l| !["botsim board:", "  ", "warning:", "note:"].iter().any(|p| l.starts_with(p))).collect();
    assert_eq!(errors.len(), 1, "{e}");
    errors[0].to_string()
}

#[test]
fn every_missing_module_is_one_error_listing_each_instance() {
    let dir = tempfile::tempdir().unwrap();
    let top = write(
        dir.path(),
        "top.v",
        "module top(input clk, output [15:0] led);\n  bot b (.clk(clk), .reset(1'b0));\n  blinker u (.clk(clk), .q(led));\n  uart tx (.clk(clk));\nendmodule\n",
    );
    let o = board(&[&top]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    let lines: Vec<&str> = e.lines().collect();
    assert_eq!(lines[0], "2 modules of the design are missing:", "{e}");
    assert_eq!(
        lines[1],
        format!("  {top}:3:3: `blinker` (instance `u` in `top`): add its file, or tie it off with --stub blinker")
    );
    assert_eq!(
        lines[2],
        format!("  {top}:4:3: `uart` (instance `tx` in `top`): add its file, or tie it off with --stub uart")
    );
    assert_eq!(lines[3], "  --stub blinker --stub uart gets past all 2", "{e}");
    assert_eq!(lines.len(), 4, "{e}");
}

#[test]
fn a_clock_with_the_wrong_direction_is_one_error_at_the_top() {
    // Other pins declared the wrong way run as the board would (tests/boards/peripherals.rs); a
    // board without its clock has nothing to run.
    let dir = tempfile::tempdir().unwrap();
    let top = write(dir.path(), "top.v", "module top(output clk, input [6:0] seg);\n  bot b (.clk(clk));\nendmodule\n");
    let e = one_line_error(&board(&[&top]));
    assert!(e.starts_with(&format!("{top}:1:8: port `clk` is the board's clock pin, an input")), "{e}");
}

#[test]
fn a_verilog_syntax_error_is_one_error_at_the_users_line() {
    let dir = tempfile::tempdir().unwrap();
    let top = write(
        dir.path(),
        "top.v",
        "module top(input clk, output [15:0] led);\n  bot b (.clk(clk), .reset(1'b0));\n  assign led = 16'h00 +;\nendmodule\n",
    );
    let e = one_line_error(&board(&[&top]));
    assert!(e.starts_with(&format!("{top}:3:")), "{e}");
}

/// LED value after 1 ms of `tests/board_designs/clocks` with `--param KIND=kind`.
fn edges_in_one_ms(kind: u8) -> u64 {
    let o = board(&["tests/board_designs/clocks", "--param", &format!("KIND={kind}"), "--seconds", "0.001", "--json"]);
    let summary = summary(&o);
    summary["leds"].as_u64().unwrap()
}

#[test]
fn an_mmcm_at_a_non_integer_ratio_puts_every_edge_at_its_true_time() {
    // 100 MHz x 9.75 / 15 = 65 MHz: period 1e6/65 ps = 15,384.615... ps. The oscillator's
    // rising edges are at 10 ns, 20 ns, ...; LOCKED rises on the 16th (160 ns); the output
    // runs from its first grid edge after that, k = 11 (169.23 ns), and its edge k = 65,000
    // falls exactly on 1 ms. Edges 11..=65,000: 64,990 (with drift, or with the period
    // rounded to 15,385 ps, edge 65,000 would land 25 ns late and be missed).
    assert_eq!(edges_in_one_ms(0), 64_990);
}

#[test]
fn a_dcm_clkfx_runs_at_its_multiply_and_divide() {
    // 100 MHz x 2 / 8 = 25 MHz (40 ns): locked at 160 ns, edges k = 5 (200 ns) ..= 25,000.
    assert_eq!(edges_in_one_ms(1), 24_996);
}

#[test]
fn a_vga_frame_from_the_designs_pins_equals_botsim_frame_for_the_same_state() {
    let dir = tempfile::tempdir().unwrap();
    let (frames, csv) = (dir.path().join("frames"), dir.path().join("t.csv"));
    // hw timing: samples 0 and 1 come right after reset (1 ms), the next about 53 ms later;
    // frames (16.8 ms each) start when the DTG's first vertical sync falls, about 15.7 ms
    // after the MMCM locks, so frames 0 and 1 show the bot standing at sample 1.
    let o = example(
        "examples/nexys4_vga",
        &["--seconds", "0.052", "--frames", frames.to_str().unwrap(), "--trace-csv", csv.to_str().unwrap(), "--json"],
    );
    let summary = summary(&o);
    assert_eq!(summary["vga_frames"], 2, "{summary}");
    common::frames_show_sample(&frames, &csv, 1, &[0, 1]);
}

/// The rows of a `--trace-csv` file, each as its columns.
fn rows(path: &Path) -> Vec<Vec<u64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// The team firmware examples/common/linefollow.psm (the `line-follow` algorithm in KCPSM6
/// assembly, loaded with --program into the example's ROM) drives the bot through the whole
/// board; `botsim run --driver line-follow` is the reference. The board runs with `cpu`:
/// `lockstep` runs the all-RTL board and the board with both KCPSM6s on the ISS, compared
/// pin for pin and port for port in every cycle.
fn follow_through_the_board(map: Option<&Path>, cpu: &str, bot: &str) {
    let dir = tempfile::tempdir().unwrap();
    let (reference, through_board) = (dir.path().join("run.csv"), dir.path().join("board.csv"));
    let mut run_args = vec!["run", "--timing", "fast", "--compat", "botsim20", "--driver", "line-follow", "--json"];
    let map_arg = map.map(|m| m.to_str().unwrap().to_string());
    if let Some(m) = &map_arg {
        run_args.extend(["--map", m]);
    }
    run_args.extend(["--trace-csv", reference.to_str().unwrap()]);
    let o = Command::new(env!("CARGO_BIN_EXE_botsim")).args(&run_args).output().unwrap();
    let summary = summary(&o);
    assert_eq!(summary["driver"], "reached the end of the line");
    let want = rows(&reference);

    // Samples 0 to want.len(): one more than the reference's.
    let samples = want.len().to_string();
    let mut args = vec![
        "--program",
        "examples/common/linefollow.psm",
        "--timing",
        "fast",
        "--compat",
        "botsim20",
        "--samples",
        &samples,
        "--trace-csv",
        through_board.to_str().unwrap(),
        "--cpu",
        cpu,
        "--bot",
        bot,
        "--json",
    ];
    if let Some(m) = &map_arg {
        args.extend(["--map", m]);
    }
    let o = example("examples/nexys4_proj2", &args);
    assert!(o.status.success(), "{}", stderr(&o));
    // What examples/ci/botsim-board.yml checks.
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["end"]["at_line_end"], true, "{summary}");
    // --json keeps stderr for warnings and errors only: the substitution report is not there.
    let got = rows(&through_board);
    assert_eq!(got.len(), want.len() + 1);
    // Samples 0 and 1 come 246 clocks apart right after reset: too soon for the team CPU's
    // interrupt, its decision and its MotCtl write, which reach the bot one sample later than
    // botsim run's driver (it sets MotCtl between two clocks). From then on the board follows
    // the reference one sample behind, register for register.
    assert_eq!(got[1][2..], got[0][2..], "sample 1 still has the start state");
    for i in 1..want.len() {
        assert_eq!(got[i + 1][2..], want[i][2..], "board sample {} against reference sample {i}", i + 1);
    }
    let end = got.last().unwrap();
    assert_eq!(end[5], 0x18, "on the line (sensors 000) with a wall ahead (both proximity bits)");
}

#[test]
fn the_team_firmware_follows_the_line_of_the_builtin_course_through_the_board() {
    follow_through_the_board(None, "lockstep", "rtl");
}

#[test]
fn the_team_firmware_follows_the_line_of_the_course_maps_through_the_board() {
    for name in ["world_map_part1", "world_map_lr", "world_map_loop"] {
        let Some(map) = common::reference_map(&format!("{name}.txt")) else { return };
        // part1 in lock-step too, with the bot's model on the ISS board; the others on the
        // ISS board with the bot's model (both proven equal to the RTL).
        follow_through_the_board(Some(&map), if name == "world_map_part1" { "lockstep" } else { "iss" }, "model");
    }
}

#[test]
fn a_vivado_project_gives_its_design_sources_and_its_top() {
    // tests/board_designs/vivado/proj2.xpr lists the example design relative to $PPRDIR,
    // names the top, and has a simulation file set with a file that is not Verilog.
    let o = board(&["tests/board_designs/vivado/proj2.xpr", "--param", "SIMULATE=1", "--seconds", "0.045", "--json"]);
    let summary = summary(&o);
    assert_eq!(summary["top"], "nexys4fpga");
    // The bot at its start (64, 64) facing east, shown by the team firmware.
    assert_eq!(summary["display"], "4040   2");
}

#[test]
fn block_and_distributed_memory_cores_come_from_their_xci_and_init_files() {
    // tests/board_designs/memcore: the switches address rom_b (a Block Memory Generator ROM
    // from rom_b.xci and rom_b.coe: word k = 0x0A + 7k) on LED[7:0] and rom_d (a Distributed
    // Memory Generator ROM from rom_d.xci and rom_d.mif: word k = 0xF0 + k) on LED[15:8].
    // The Vivado simulation wrapper of rom_b, which instantiates Xilinx's library model, is
    // in the sources and must be replaced.
    for (k, want) in [(3u16, 0xF31Fu64), (1, 0xF111), (0, 0xF00A)] {
        let sw = format!("{k:04X}");
        let o = board(&["tests/board_designs/memcore", "--switches", &sw, "--seconds", "0.0001", "--json"]);
        let summary = summary(&o);
        assert_eq!(summary["leds"].as_u64().unwrap(), want, "switches {sw}");
    }
}

#[test]
fn a_stimulus_file_drives_the_switches_and_a_waveform_window_covers_its_times() {
    let dir = tempfile::tempdir().unwrap();
    let (stim, vcd) = (dir.path().join("stim.txt"), dir.path().join("w.vcd"));
    // The example firmware drives the bot with the switches' motor byte (forward when 0).
    std::fs::write(&stim, "# reverse from 1.5 ms (after the reset and the first samples)\n1.5ms switches 22\n")
        .unwrap();
    let o = example(
        "examples/nexys4_proj2",
        &[
            "--timing",
            "fast",
            "--seconds",
            "0.005",
            "--stimulus",
            stim.to_str().unwrap(),
            "--vcd",
            vcd.to_str().unwrap(),
            "--trace-from",
            "2ms",
            "--trace-to",
            "201000c",
            "--json",
        ],
    );
    let summary = summary(&o);
    assert_eq!(summary["end"]["movement"], "reverse");
    assert!(summary["end"]["loc_x"].as_u64().unwrap() < 64, "{summary}");
    // The window: from 2 ms to 201,000 cycles of 100 MHz (2.01 ms): its first and last time
    // stamps are its ends, in picoseconds, with both edges of every cycle between.
    let (first, last, stamps) = vcd_span(&vcd);
    assert_eq!((first, last), (2_000_000_000, 2_010_000_000));
    assert_eq!(stamps, 2 * 1_000 + 1);
}

#[test]
fn a_build_past_its_budget_is_stopped_with_one_error_and_leaves_nothing() {
    let cache = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_botsim"))
        .args(["board", "tests/board_designs/clocks", "--seconds", "0.0001"])
        .current_dir(root())
        .env("BOTSIM_CACHE", cache.path())
        .env("BOTSIM_BUILD_TIMEOUT", "1")
        .output()
        .unwrap();
    let e = one_line_error(&o);
    assert_eq!(e, "the build took longer than 1 s and was stopped (BOTSIM_BUILD_TIMEOUT sets the limit)");
    let boards = cache.path().join("boards");
    let left: Vec<_> = std::fs::read_dir(&boards).map(|d| d.flatten().map(|e| e.path()).collect()).unwrap_or_default();
    assert!(left.is_empty(), "{left:?}");
}

/// The first and last time stamps of a VCD file.
fn vcd_span(path: &Path) -> (u64, u64, usize) {
    let mut times = vec![];
    for cmd in vcd::Parser::new(std::io::BufReader::new(std::fs::File::open(path).unwrap())) {
        if let vcd::Command::Timestamp(t) = cmd.unwrap() {
            times.push(t);
        }
    }
    (times[0], *times.last().unwrap(), times.len())
}

#[test]
fn a_waveform_window_in_samples_holds_the_iteration_and_its_pulse_as_botsim_run_does() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, vcd) = (dir.path().join("t.csv"), dir.path().join("w.vcd"));
    let o = example(
        "examples/nexys4_proj2",
        &[
            "--timing",
            "fast",
            "--samples",
            "12",
            "--trace-csv",
            csv.to_str().unwrap(),
            "--vcd",
            vcd.to_str().unwrap(),
            "--trace-from",
            "10",
            "--trace-to",
            "10",
            "--json",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // The bot runs on the 100 MHz clock, whose k-th rising edge is at k x 10 ns: a sample at
    // cycle c was seen at c x 10,000 ps. The window opens at sample 9's pulse and closes three
    // clocks after sample 10's began.
    let cycle = |k: usize| rows(&csv)[k][1];
    let (first, last, _) = vcd_span(&vcd);
    assert_eq!(first, cycle(9) * 10_000);
    assert_eq!(last, cycle(10) * 10_000 + 30_000);
}

/// A small deterministic generator for stimulus (xorshift64*).
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 32) % n
    }
}

/// A stimulus file of random presses of every button (the CPU reset among them: the team
/// CPU, the bot and the interface restart) and switch changes over `ms` milliseconds.
fn random_stimulus(seed: u64, ms: u64) -> String {
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let names = ["btnC", "btnU", "btnD", "btnL", "btnR", "btnCpuReset"];
    // One CPU reset for certain, somewhere in the middle; more may come at random.
    let mut text = format!("{}us press btnCpuReset {}us\n", ms * 300 + rng.below(ms * 400), 5 + rng.below(200));
    for _ in 0..14 {
        let at_us = 1_200 + rng.below(ms * 1000 - 1_500);
        if rng.below(3) == 0 {
            text.push_str(&format!("{at_us}us switches {:04X}\n", rng.below(1 << 16)));
        } else {
            let held_us = 20 + rng.below(400);
            text.push_str(&format!("{at_us}us press {} {held_us}us\n", names[rng.below(6) as usize]));
        }
    }
    text
}

#[test]
fn rtl_and_iss_boards_agree_pin_for_pin_under_random_buttons_switches_and_resets() {
    let dir = tempfile::tempdir().unwrap();
    // With --bot model the ISS board's bot is botsim's model (every change of its outputs is
    // compared too); the VGA design (its MMCM, two clocks) reads the map through the video
    // port of the model's map.
    for (design, seed, bot) in [
        ("examples/nexys4_proj2", 1, "rtl"),
        ("examples/nexys4_vga", 2, "model"),
        ("examples/nexys4_proj2", 3, "model"),
    ] {
        let stim = dir.path().join(format!("stim{seed}.txt"));
        let text = random_stimulus(seed, 12);
        assert!(text.contains("btnCpuReset") && text.contains("switches"), "seed {seed}: {text}");
        std::fs::write(&stim, text).unwrap();
        let o = example(
            design,
            &[
                "--timing",
                "fast",
                "--seconds",
                "0.012",
                "--stimulus",
                stim.to_str().unwrap(),
                "--cpu",
                "lockstep",
                "--bot",
                bot,
                "--json",
            ],
        );
        assert!(o.status.success(), "{design}, seed {seed}, --bot {bot}: {}", stderr(&o));
        let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert!(summary["samples"].as_u64().unwrap() > 100, "{summary}");
    }
}

#[test]
fn iss_and_rtl_boards_write_identical_traces() {
    let dir = tempfile::tempdir().unwrap();
    let stim = dir.path().join("stim.txt");
    std::fs::write(&stim, random_stimulus(7, 8)).unwrap();
    let mut traces = Vec::new();
    for cpu in ["rtl", "iss"] {
        let csv = dir.path().join(format!("{cpu}.csv"));
        let args = [
            "--timing",
            "fast",
            "--seconds",
            "0.008",
            "--stimulus",
            stim.to_str().unwrap(),
            "--switches",
            "0022",
            "--cpu",
            cpu,
            "--trace-csv",
            csv.to_str().unwrap(),
            "-q",
        ];
        let o = example("examples/nexys4_proj2", &args);
        assert!(o.status.success(), "{cpu}: {}", stderr(&o));
        traces.push(std::fs::read_to_string(&csv).unwrap());
    }
    assert!(traces[0].lines().count() > 100);
    assert_eq!(traces[0], traces[1]);
}

#[test]
fn an_iss_cpu_whose_rom_does_not_give_it_the_program_is_one_error() {
    let o = board(&[
        "tests/board_designs/rom_unwired",
        "--program",
        "tests/board_designs/rom_unwired/prog.psm",
        "--cpu",
        "iss",
        "--seconds",
        "0.002",
    ]);
    let e = one_line_error(&o);
    assert!(e.contains("the KCPSM6 `cpu` decoded 0105A at address 000"), "{e}");
    assert!(e.contains("its ROM gave 00000"), "{e}");
    // The same design on the RTL core runs (the CPU executes what its ROM gives).
    let o = board(&[
        "tests/board_designs/rom_unwired",
        "--program",
        "tests/board_designs/rom_unwired/prog.psm",
        "--cpu",
        "rtl",
        "--seconds",
        "0.002",
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Without --cpu, the default ISS gives way to the RTL core, said.
    let o = board(&[
        "tests/board_designs/rom_unwired",
        "--program",
        "tests/board_designs/rom_unwired/prog.psm",
        "--seconds",
        "0.002",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("its ROM gave 00000") && e.contains("running it on the RTL core (--cpu rtl)"), "{e}");
}

/// The trace lines of `file`: (pc, source file name and line, instruction text).
#[test]
fn the_cpu_trace_names_the_source_lines_of_the_assemblers_listing() {
    let dir = tempfile::tempdir().unwrap();
    let t = dir.path().join("traces");
    let o = follower(&[
        "--samples",
        "60",
        "--cpu-trace",
        t.to_str().unwrap(),
        "--cpu-trace-from",
        "1.2ms",
        "--cpu-trace-to",
        "1.4ms",
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The team's CPU against linefollow.psm's listing, the bot's against botsim's firmware.
    let team = kcpsm6::asm::assemble_file(&root().join("examples/common/linefollow.psm"), &Default::default()).unwrap();
    let fw = botsim::Firmware { timing: botsim::Timing::Fast, compat: botsim::Compat::BotSim20, ..Default::default() };
    let bot = fw.program(0).unwrap();
    for (cpu, program, name) in
        [("SYS.APPCPU", &team, "linefollow.psm"), ("SYS.ROJOBOT.BOTSIMCPU", &bot, "bot_pgm.psm")]
    {
        common::debug::check_trace_against_listing(&t.join(format!("{cpu}.trace.txt")), program, name, 1000);
    }

    // Without --program the team's ROM runs its INIT strings, and the .psm beside the ROM's
    // .v (examples/common/proj2demo.psm), which assembles to them, is its source.
    let t = dir.path().join("own");
    let o = example(
        "examples/nexys4_proj2",
        &["--timing", "fast", "--seconds", "0.0012", "--cpu-trace", t.to_str().unwrap(), "-q"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let own = kcpsm6::asm::assemble_file(&root().join("examples/common/proj2demo.psm"), &Default::default()).unwrap();
    common::debug::check_trace_against_listing(&t.join("SYS.APPCPU.trace.txt"), &own, "proj2demo.psm", 100);
}

/// Every line of `cpu`'s trace in `dir` names the source line the assembler's listing of
/// `program` (from the file `name`) gives for its address, and its instruction text
/// assembles to the word there.
#[test]
fn a_breakpoint_stops_at_the_instruction_and_the_sample_the_full_run_records() {
    let dir = tempfile::tempdir().unwrap();
    let (t, csv) = (dir.path().join("t"), dir.path().join("full.csv"));
    let with = follower;
    // The full run: every instruction of the team CPU and every sample.
    let o = with(&["--samples", "400", "--cpu-trace", t.to_str().unwrap(), "--trace-csv", csv.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let trace = std::fs::read_to_string(t.join("SYS.APPCPU.trace.txt")).unwrap();
    let first_isr = trace.lines().skip(1).find(|l| l.split_whitespace().nth(3) == Some("isr")).unwrap();
    let f: Vec<&str> = first_isr.split_whitespace().collect();

    // The breakpoint at the label: the same instruction, cycle and time.
    let o = with(&["--samples", "400", "--break", "label=isr", "--json"]);
    let s = summary(&o);
    let what = s["break"]["what"].as_str().unwrap();
    assert_eq!(s["stopped_by"], "break");
    assert!(what.contains(&format!("SYS.APPCPU at pc {} isr (linefollow.psm:", f[2])), "{what}");
    assert!(what.contains(&format!("in its cycle {},", f[0])), "{what} / {first_isr}");
    assert!(what.ends_with(&format!("at {} ms", f[1])), "{what} / {first_isr}");

    // The bot off the line: the first sample of the full run with no line sensor on the line.
    let want = rows(&csv).into_iter().find(|r| r[5] & 7 == 7).expect("the follower loses the line at a corner");
    let o = with(&["--samples", "400", "--break", "bot=off-line", "--json"]);
    let s: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(s["samples"].as_u64().unwrap(), want[0] + 1, "{s}");
    assert!(s["break"]["what"].as_str().unwrap().contains(&format!("sample {} ", want[0])), "{s}");

    // A label no program has is one error.
    let e = one_line_error(&with(&["--break", "label=nowhere"]));
    assert!(e.starts_with("--break label=nowhere: no CPU's program has it"), "{e}");
}

/// A vector's value as a number (up to 64 bits) and as ASCII text (VCD drops leading zeros:
/// the text is a whole number of characters).
#[test]
fn waveforms_show_each_cpus_instruction_as_the_disassembler_writes_it() {
    let dir = tempfile::tempdir().unwrap();
    for cpu in ["rtl", "iss"] {
        let vcd = dir.path().join(format!("{cpu}.vcd"));
        let o = example(
            "examples/nexys4_proj2",
            &[
                "--timing",
                "fast",
                "--seconds",
                "0.0013",
                "--vcd",
                vcd.to_str().unwrap(),
                "--cpu",
                cpu,
                "--bot",
                "rtl",
                "-q",
            ],
        );
        assert!(o.status.success(), "{cpu}: {}", stderr(&o));
        let team: &[&str] = &["TOP", "botsim_board", "user", "SYS", "APPCPU"];
        let bot: &[&str] = &["TOP", "botsim_board", "user", "SYS", "ROJOBOT", "BOTSIMCPU"];
        let checked = common::debug::check_debug_signals(&vcd, &[team, bot]);
        assert!(checked.iter().all(|&n| n > 1000), "{cpu}: {checked:?}");
        // The save file beside it names the groups and the signals.
        let gtkw = std::fs::read_to_string(vcd.with_extension("gtkw")).unwrap();
        assert!(gtkw.contains(&format!("[dumpfile] \"{}\"", vcd.display())), "{gtkw}");
        for s in
            ["TOP.botsim_board.user.SYS.APPCPU.kcpsm6_opcode[1:160]", "TOP.botsim_board.bot_locx[7:0]", "-SYS.APPCPU"]
        {
            assert!(gtkw.lines().any(|l| l == s), "{s} in {gtkw}");
        }
    }
}

/// GTKWave (under a virtual X display) run on a save file with a Tcl script; what the script
/// printed. None when GTKWave or xvfb-run is not installed, unless BOTSIM_REQUIRE_TOOLS is
/// set (CI, where scripts/setup.sh installs them): then that is a failure.
fn gtkwave_script(save_file: &Path, script: &str) -> Option<String> {
    let have = |tool: &str| {
        Command::new("sh").args(["-c", &format!("command -v {tool}")]).output().is_ok_and(|o| o.status.success())
    };
    let missing: Vec<&str> = ["gtkwave", "xvfb-run"].into_iter().filter(|t| !have(t)).collect();
    if !missing.is_empty() {
        assert!(std::env::var_os("BOTSIM_REQUIRE_TOOLS").is_none(), "{missing:?} not installed: run scripts/setup.sh");
        eprintln!("skipped: {missing:?} not installed");
        return None;
    }
    let tcl = save_file.with_extension("tcl");
    std::fs::write(&tcl, format!("{script}\ngtkwave::/File/Quit\n")).unwrap();
    let o = Command::new("xvfb-run").args(["-a", "gtkwave", "-S"]).arg(&tcl).arg(save_file).output().unwrap();
    assert!(o.status.success(), "gtkwave: {}", stderr(&o));
    Some(String::from_utf8_lossy(&o.stdout).into_owned())
}

#[test]
fn the_save_file_opens_in_gtkwave_on_the_breakpoint_with_labels_and_decoded_registers() {
    let dir = tempfile::tempdir().unwrap();
    let vcd = dir.path().join("w.vcd");
    let o = follower(&["--break", "label=isr", "--break-window", "20us", "--vcd", vcd.to_str().unwrap(), "--json"]);
    let s = summary(&o);
    let stop = s["break"]["time_ps"].as_u64().unwrap();
    let gtkw = vcd.with_extension("gtkw");
    let listed = std::fs::read_to_string(&gtkw).unwrap().lines().filter(|l| l.starts_with("TOP.")).count();
    let cpu = "TOP.botsim_board.user.SYS.APPCPU";
    let script = [
        "puts \"signals [llength [gtkwave::getDisplayedSignals]]\"".to_string(),
        "puts \"view [gtkwave::getWindowStartTime] [gtkwave::getWindowEndTime]\"".to_string(),
        "puts \"marker [gtkwave::getMarker]\"".to_string(),
        format!("puts \"address [gtkwave::getTraceValueAtMarkerFromName {{{cpu}.address[11:0]}}]\""),
        format!("puts \"instruction [gtkwave::getTraceValueAtMarkerFromName {{{cpu}.instruction[17:0]}}]\""),
        format!("puts \"opcode [gtkwave::getTraceValueAtMarkerFromName {{{cpu}.kcpsm6_opcode[1:160]}}]\""),
        "puts \"info [gtkwave::getTraceValueAtMarkerFromName {TOP.botsim_board.bot_info[7:0]}]\"".to_string(),
    ]
    .join("\n");
    let Some(out) = gtkwave_script(&gtkw, &script) else { return };
    let said = |key: &str| {
        let line = out.lines().find(|l| l.starts_with(&format!("{key} "))).unwrap_or_else(|| panic!("{key} in {out}"));
        line[key.len() + 1..].trim_end().to_string()
    };
    // Every signal of the save file is found in the waveform and shown.
    assert_eq!(said("signals").parse::<usize>().unwrap(), listed, "{out}");
    // The window opens on the instructions before the stop, with the marker on the stop.
    assert_eq!(said("marker").parse::<u64>().unwrap(), stop, "{out}");
    let view: Vec<u64> = said("view").split(' ').map(|v| v.parse().unwrap()).collect();
    assert!(view[0] < stop && stop < view[1] && view[1] - view[0] < 1_000_000, "{out}");
    // The translate filters: the address as its label, BotInfo as heading and movement; the
    // instruction's text is the disassembler's.
    assert!(said("address").starts_with("isr"), "{out}");
    assert!(said("info").contains('_'), "{out}");
    let word = u32::from_str_radix(&said("instruction"), 16).unwrap();
    assert_eq!(said("opcode").trim_end(), kcpsm6::disasm::disassemble_word(word), "{out}");
}

#[test]
fn a_bot_condition_writes_the_firmwares_answer_to_that_sample() {
    let dir = tempfile::tempdir().unwrap();
    let (vcd, t, csv) = (dir.path().join("w.vcd"), dir.path().join("t"), dir.path().join("t.csv"));
    let o = follower(&[
        "--samples",
        "400",
        "--break",
        "bot=off-line",
        "--break-window",
        "20us",
        "--vcd",
        vcd.to_str().unwrap(),
        "--cpu-trace",
        t.to_str().unwrap(),
        "--trace-csv",
        csv.to_str().unwrap(),
        "--json",
    ]);
    let s = summary(&o);
    let stop = s["break"]["time_ps"].as_u64().unwrap();
    // The other outputs end at the stop: the sample that stopped it is the last row, with
    // no line sensor on the line.
    let what = s["break"]["what"].as_str().unwrap();
    let sample: u64 = what.split("sample ").nth(1).and_then(|r| r.split(' ').next()).unwrap().parse().unwrap();
    let rows = rows(&csv);
    assert_eq!(rows.len() as u64, s["samples"].as_u64().unwrap(), "{s}");
    assert_eq!(rows.last().unwrap()[0], sample, "{what}");
    assert_eq!(rows.last().unwrap()[5] & 7, 7, "{rows:?}");
    // The team CPU's trace goes on past it: the interrupt of that sample and the firmware
    // reading the registers it brought.
    let trace = std::fs::read_to_string(t.join("SYS.APPCPU.trace.txt")).unwrap();
    let after: Vec<&str> = trace
        .lines()
        .skip(1)
        .filter(|l| l.split_whitespace().nth(1).is_some_and(|ms| ms.parse::<f64>().unwrap() * 1e9 > stop as f64))
        .collect();
    let isr =
        after.iter().position(|l| l.split_whitespace().nth(3) == Some("isr")).expect("the interrupt after the sample");
    assert!(after[isr..].iter().any(|l| l.contains("IN 0D=07")), "the sensors read after the interrupt");
    // The waveform opens on the sample, the view running on from it.
    let Some(out) = gtkwave_script(
        &vcd.with_extension("gtkw"),
        "puts \"view [gtkwave::getWindowStartTime] [gtkwave::getWindowEndTime] [gtkwave::getMarker]\"",
    ) else {
        return;
    };
    let line = out.lines().find(|l| l.starts_with("view ")).unwrap();
    let v: Vec<u64> = line[5..].split(' ').map(|x| x.trim().parse().unwrap()).collect();
    assert_eq!(v[2], stop, "{out}");
    assert!(v[0] < stop && stop - v[0] <= 40_000 && v[1] > stop + 100_000, "{out}");
}

#[test]
fn the_fast_forward_skips_what_repeats_and_changes_nothing_the_board_shows() {
    // The Project 2 example at the bot's hw timing (a sample every 5.3 M clocks), its own
    // firmware showing the bot's registers, a button pressed, the switches changed and the CPU
    // reset pressed along the way: every edge simulated, then with the fast-forward.
    fast_forward_against_every_edge("examples/nexys4_proj2");
}

#[test]
fn a_vga_design_skips_what_repeats_of_what_the_run_records() {
    // The VGA example: the same system beside a 25 MHz pixel clock, a display timing generator
    // and a colour pipeline, whose frame (1.68 M clocks) and display refresh (2^20) repeat
    // together only every 13.7 G clocks. Nothing the run records reads the VGA part, so the
    // fast-forward compares and puts back the rest (src/fastforward/observed.rs) and skips as on the
    // one-clock design, with the same samples, display and pins as every edge simulated.
    fast_forward_against_every_edge("examples/nexys4_vga");
}

#[test]
fn a_late_waveform_of_a_vga_design_skips_ahead_and_shows_x_for_what_the_run_did_not_simulate() {
    // The same window of the VGA example's waveform, the last 200 us of 120.2 ms, two ways:
    // skipping ahead as a run without a waveform does (the pixel clock not run, what nothing
    // recorded reads left behind; all of it before the window, which is simulated edge by
    // edge), and with every edge of every clock simulated up to it (--vcd-all-signals
    // --every-edge: the first evaluates rising edges only before the window, its debug
    // build's `always @(instruction)` notwithstanding). Every signal the first shows equals
    // the second's at every change; the VGA part reads x.
    let dir = tempfile::tempdir().unwrap();
    let (mut changes, mut x_counts) = (Vec::new(), Vec::new());
    for all in [false, true] {
        let vcd = dir.path().join(format!("{all}.vcd"));
        let mut args = vec![
            "--cpu",
            "iss",
            "--seconds",
            "0.1202",
            "--vcd",
            vcd.to_str().unwrap(),
            "--trace-from",
            "120ms",
            "--json",
        ];
        if all {
            args.extend(["--vcd-all-signals", "--every-edge"]);
        }
        let s = summary(&example("examples/nexys4_vga", &args));
        let skipped = s["fast_forward"]["skipped_seconds"].as_f64().unwrap();
        assert_eq!(skipped > 0.04, !all, "{s}");
        changes.push(vcd_changes(&vcd));
        x_counts.push(s["vcd_x_signals"].as_u64().unwrap());
    }
    let (skipping, every_edge) = (&changes[0], &changes[1]);
    let x: Vec<&String> =
        skipping.iter().filter(|(_, c)| c.len() == 1 && c[0].1.contains('x')).map(|(n, _)| n).collect();
    let is_x = |name: &str| x.iter().any(|n| n.ends_with(name));
    // The VGA part (the pixel clock's): x; the board's pins and registers, the bot, each
    // KCPSM6's debug view, a parameter: shown.
    for n in ["TOP.vga_r[3:0]", "TOP.hsync", ".DTG.pixel_row[9:0]", ".CLKGEN.clk_out1"] {
        assert!(is_x(n), "{n} is not x: {x:?}");
    }
    for n in
        ["TOP.led[15:0]", "TOP.an[7:0]", "TOP.bot_locx[7:0]", ".APPCPU.sim_s0[7:0]", ".APPCPU.kcpsm6_opcode[1:160]"]
    {
        assert!(skipping.keys().any(|k| k.ends_with(n)) && !is_x(n), "{n} is x or missing: {x:?}");
    }
    // A parameter, and a variable nothing writes after the initial blocks (the clock's period).
    for n in [".SIMULATE[31:0]", ".out0.botsim_period_num[31:0]"] {
        assert!(skipping.keys().any(|k| k.ends_with(n)) && !is_x(n), "{n} is x or missing");
    }
    // A model's handle and a temporary file's name differ from run to run.
    let per_process = ["botsim_iss_cpu[63:0]", "model[63:0]", "rom_file[32767:0]", "world_path[32767:0]"];
    let mut compared = 0;
    for (name, c) in skipping {
        if x.contains(&name) || per_process.iter().any(|p| name.ends_with(&format!(".{p}"))) {
            continue;
        }
        assert_eq!(Some(c), every_edge.get(name), "{name}");
        compared += 1;
    }
    assert!(compared > 100 && x.len() > 20, "{compared} signals compared, {} x", x.len());
    // The summary counts them, an alias's names once (46 signals under 132 names).
    assert!(x_counts[0] > 20 && x_counts[0] as usize <= x.len() && x_counts[1] == 0, "{x_counts:?}, {}", x.len());
}

/// Every signal of a VCD file (named as GTKWave names them) with its value changes (time,
/// value), an alias listed under each of its names.
fn vcd_changes(path: &Path) -> std::collections::BTreeMap<String, Vec<(u64, String)>> {
    let mut parser = vcd::Parser::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let names = common::debug::vcd_names(&parser.parse_header().unwrap());
    let mut by_code: std::collections::HashMap<vcd::IdCode, Vec<(u64, String)>> = Default::default();
    let mut t = 0;
    for cmd in parser {
        match cmd.unwrap() {
            vcd::Command::Timestamp(ts) => t = ts,
            vcd::Command::ChangeScalar(id, v) => by_code.entry(id).or_default().push((t, v.to_string())),
            vcd::Command::ChangeVector(id, v) => by_code.entry(id).or_default().push((t, v.to_string())),
            vcd::Command::ChangeReal(id, v) => by_code.entry(id).or_default().push((t, v.to_string())),
            _ => {}
        }
    }
    let mut out = std::collections::BTreeMap::new();
    for (code, ns) in names {
        for n in ns {
            out.insert(n, by_code.get(&code).cloned().unwrap_or_default());
        }
    }
    out
}

/// Run an example design with and without the fast-forward; the same records, pin for pin.
fn fast_forward_against_every_edge(example_dir: &str) {
    let dir = tempfile::tempdir().unwrap();
    let stim = dir.path().join("stim.txt");
    std::fs::write(&stim, "80ms press btnU 5ms\n120ms switches 00A5\n170ms press btnCpuReset 2ms\n").unwrap();
    let (mut outputs, mut pin_logs) = (Vec::new(), Vec::new());
    for ff in [false, true] {
        let (csv, display) = (dir.path().join(format!("{ff}.csv")), dir.path().join(format!("{ff}.txt")));
        let pins = dir.path().join(format!("{ff}-pins.csv"));
        let mut args = vec![
            "--cpu",
            "iss",
            "--bot",
            "model",
            "--samples",
            "5",
            "--stimulus",
            stim.to_str().unwrap(),
            "--trace-csv",
            csv.to_str().unwrap(),
            "--display",
            display.to_str().unwrap(),
            "--pins",
            pins.to_str().unwrap(),
            "--json",
        ];
        if !ff {
            args.push("--no-fast-forward");
        }
        let o = example(example_dir, &args);
        let s = summary(&o);
        let skipped = s["fast_forward"]["skipped_seconds"].as_f64().unwrap();
        if ff {
            // Several periods of the display's refresh (2^20 clocks, 10.5 ms) skipped.
            assert!(skipped > 0.04, "{s}");
        } else {
            assert_eq!(skipped, 0.0, "{s}");
        }
        let read = |p: &Path| std::fs::read_to_string(p).unwrap();
        outputs.push((read(&csv), read(&display), s["samples"].clone(), s["leds"].clone()));
        pin_logs.push(read(&pins));
    }
    // The same samples (with the bot's cycle counts), the same display and LED changes at the
    // same times (without the display's refresh repeated into the skipped periods, its digits
    // would go dark: a digit not refreshed for 20 ms is).
    assert!(outputs[0].0.lines().count() == 7 && !outputs[0].1.is_empty(), "{:?}", outputs[0]);
    assert_eq!(outputs[0], outputs[1]);
    // And every change of every display and LED pin at the same picosecond: the whole periods
    // repeated, the part of one after them (a snapshot of that phase put back) too.
    let (every_edge, skipping) = (&pin_logs[0], &pin_logs[1]);
    assert!(every_edge.lines().count() > 100, "{}", every_edge.lines().count());
    if every_edge != skipping {
        let (a, b): (Vec<&str>, Vec<&str>) = (every_edge.lines().collect(), skipping.lines().collect());
        let i = a.iter().zip(&b).position(|(x, y)| x != y).unwrap_or(a.len().min(b.len()));
        panic!(
            "--pins row {i}: every edge {:?}, fast-forward {:?} ({} and {} rows)",
            a.get(i),
            b.get(i),
            a.len(),
            b.len()
        );
    }
}

#[test]
fn a_second_clock_that_drives_what_the_run_records_runs_and_the_board_still_skips() {
    // tests/board_designs/pixel_clock: the phases design (a CPU waiting beside a refresh
    // counter of 2^16 clocks) and a frame counter of 1,000 clocks of 25 MHz, which repeat
    // together only every 8.2 M clocks. FEEDBACK 0: the frame counter drives VGA pins alone,
    // and the board skips; 1: each frame toggles LED 15 (through a condition, the counter's
    // wrap), so the second clock runs and the fast-forward compares where it is in its
    // period too, and moves the frame counter on by arithmetic between its wraps. Either way
    // the pins equal every edge simulated.
    let sources = ["tests/board_designs/pixel_clock", "tests/board_designs/phases", "examples/nexys4_vga/clk_wiz_0.v"];
    for feedback in ["0", "1"] {
        let param = format!("FEEDBACK={feedback}");
        let (every_edge, _) = phases_pins(&sources, &["--param", &param], false);
        let (skipping, s) = phases_pins(&sources, &["--param", &param], true);
        let skipped = s["fast_forward"]["skipped_seconds"].as_f64().unwrap();
        assert!(skipped > 0.1, "FEEDBACK={feedback}: {s}");
        // LED 15 toggles every 40 us with FEEDBACK 1: thousands of rows.
        assert!(every_edge.lines().count() > 1000, "{}", every_edge.lines().count());
        assert!(every_edge == skipping, "FEEDBACK={feedback}: --pins differ with the fast-forward");
    }
}

/// A design around tests/board_designs/phases (its program in the ROM; the bot a model)
/// for four samples: its `--pins` log and summary, with the fast-forward or without.
fn phases_pins(sources: &[&str], extra: &[&str], fast_forward: bool) -> (String, serde_json::Value) {
    let dir = tempfile::tempdir().unwrap();
    let pins = dir.path().join("pins.csv");
    let mut args = sources.to_vec();
    args.extend(["--program", "tests/board_designs/phases/phases.psm", "--cpu", "iss", "--bot", "model"]);
    args.extend(["--samples", "4", "--pins", pins.to_str().unwrap(), "--json"]);
    args.extend(extra);
    if !fast_forward {
        args.push("--no-fast-forward");
    }
    let s = summary(&board(&args));
    // Samples 1 to 4 pulse upd_sysregs (sample 0 is the registers after reset): four
    // interrupts, each counted on the LEDs.
    assert_eq!(s["leds"], 4, "an interrupt at every sample: {s}");
    let skipped = s["fast_forward"]["skipped_seconds"].as_f64().unwrap();
    assert!(fast_forward || skipped == 0.0, "{s}");
    (std::fs::read_to_string(&pins).unwrap(), s)
}

#[test]
fn a_design_that_reads_the_time_runs_every_edge_and_says_why() {
    // tests/board_designs/timed lights LED 0 at $time 30 ms. Its flops repeat every clock, so
    // a fast-forward that trusted them would skip from the first quiet period to the bot's
    // next sample (53 ms) and light the LED there; the build's check keeps it off.
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("display.txt");
    let o = board(&[
        "tests/board_designs/timed",
        "--cpu",
        "iss",
        "--bot",
        "model",
        "--seconds",
        "0.06",
        "--display",
        log.to_str().unwrap(),
        "--json",
    ]);
    let s = summary(&o);
    assert_eq!(s["fast_forward"]["off_because"], "the design reads the simulation time ($time, $realtime)", "{s}");
    assert_eq!(s["fast_forward"]["skips"], 0, "{s}");
    let log = std::fs::read_to_string(&log).unwrap();
    assert_eq!(log.trim(), "30.000 ms  leds    0000000000000001");
    // Without --json the run says so in a note.
    let o = board(&["tests/board_designs/timed", "--cpu", "iss", "--bot", "model", "--seconds", "0.001"]);
    assert!(stderr(&o).contains("note: no fast-forward: the design reads the simulation time"), "{}", stderr(&o));
}

#[test]
fn the_fast_forward_puts_every_model_back_at_the_phase_it_skips_to() {
    // tests/board_designs/phases: a CPU waiting in a loop of six cycles beside a refresh
    // counter of 2^16 clocks repeats itself every 3 x 2^16 clocks; the skips end part-way
    // into a period (a snapshot of that phase put back), where the CPU is not where it was
    // at the period's start: with the CPU left at the wrong phase its ROM check stops the run.
    let (every_edge, _) = phases_pins(&["tests/board_designs/phases"], &[], false);
    let (skipping, s) = phases_pins(&["tests/board_designs/phases"], &[], true);
    assert!(s["fast_forward"]["skipped_seconds"].as_f64().unwrap() > 0.14, "{s}");
    assert!(every_edge.lines().count() > 1000, "{}", every_edge.lines().count());
    assert!(every_edge == skipping, "--pins differ with the fast-forward");
}

#[test]
fn rising_edges_only_change_nothing_the_board_shows() {
    // The Project 2 example on the RTL cores at hw timing: the build finds that nothing
    // happens at the clock's falling edges, so the board evaluates rising edges only; the
    // same run evaluating both edges shows the same pins, samples and display.
    let dir = tempfile::tempdir().unwrap();
    let mut runs = Vec::new();
    for every_edge in [false, true] {
        let out = |name: &str| dir.path().join(format!("{every_edge}-{name}"));
        let (pins, csv, display) = (out("pins.csv"), out("trace.csv"), out("display.txt"));
        let mut args = vec![
            "--samples",
            "2",
            "--pins",
            pins.to_str().unwrap(),
            "--trace-csv",
            csv.to_str().unwrap(),
            "--display",
            display.to_str().unwrap(),
            "--json",
        ];
        if every_edge {
            args.push("--every-edge");
        }
        let o = example("examples/nexys4_proj2", &args);
        let s = summary(&o);
        let read = |p: &Path| std::fs::read_to_string(p).unwrap();
        runs.push((s["evaluations"].as_u64().unwrap(), read(&pins), read(&csv), read(&display)));
    }
    let (rising, both) = (&runs[0], &runs[1]);
    assert!(rising.1.lines().count() > 30 && rising.2.lines().count() == 4, "{rising:?}");
    assert_eq!((&rising.1, &rising.2, &rising.3), (&both.1, &both.2, &both.3));
    // One evaluation per clock against two (the reset's evaluation and the inputs' aside).
    assert!(rising.0 * 2 - both.0 < 10, "{} and {} evaluations", rising.0, both.0);
    // The VGA example (the MMCM's 25 MHz beside the oscillator) too: its frames equal
    // botsim's own (a_vga_frame_from_the_designs_pins_equals_botsim_frame_for_the_same_state).
    let evaluations = |extra: &[&str]| {
        let mut args = vec!["--seconds", "0.001", "--json"];
        args.extend_from_slice(extra);
        let o = example("examples/nexys4_vga", &args);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()["evaluations"].as_u64().unwrap()
    };
    let (rising, both) = (evaluations(&[]), evaluations(&["--every-edge"]));
    assert!(rising <= 100_002 && both >= 200_000, "{rising} and {both} evaluations");
}

#[test]
fn falling_edges_are_evaluated_where_the_design_has_logic_on_them() {
    // tests/board_designs/falling counts the clock's falling edges on its LEDs. The
    // oscillator rises at 10 ns, 20 ns, ... and falls 5 ns later: by 1 ms it has fallen
    // 99,999 times (at 15 ns ... 999,995 ns); with the falling edges left out it would count
    // none. Both edges of 100,000 clocks are evaluated.
    for extra in [None, Some("--every-edge")] {
        let mut args = vec!["tests/board_designs/falling", "--seconds", "0.001", "--json"];
        args.extend(extra);
        let o = board(&args);
        let s = summary(&o);
        assert_eq!((s["leds"].as_u64(), s["evaluations"].as_u64()), (Some(99_999 % 65_536), Some(200_000)), "{s}");
    }
}

#[test]
fn clocks_made_from_a_generated_clocks_level_get_its_falling_edges_evaluated() {
    // tests/board_designs/clocks with KIND 2 counts the rising edges of an MMCM's inverted
    // output and of a BUFGCE-gated clock: the first rises when the generated clock falls, the
    // second is computed from its level. Evaluating rising edges only would miss them (the
    // counts then read 0x08 and 0x08 after 0.2 ms); the build sees the logic and keeps every
    // edge, with the same LEDs and evaluations as --every-edge.
    let run = |extra: Option<&str>| {
        let mut args = vec!["tests/board_designs/clocks", "--param", "KIND=2", "--seconds", "0.0002", "--json"];
        args.extend(extra);
        let s = summary(&board(&args));
        (s["leds"].as_u64().unwrap(), s["evaluations"].as_u64().unwrap())
    };
    let (leds, evaluations) = run(None);
    assert_eq!((leds, evaluations), run(Some("--every-edge")));
    // 65 MHz for 0.2 ms less the MMCM's lock: about 12,900 edges of each, both counters alike.
    assert!(leds >> 8 == leds & 0xff && evaluations > 2 * 20_000, "{leds:#x}, {evaluations}");
}

#[test]
fn a_run_counted_in_samples_stops_when_the_bot_stops_sampling() {
    // The CPU reset held from 60 ms holds the bot in reset too: --samples 3 would wait forever
    // for sample 3; the run gives up after 1 s of board time without a sample.
    let dir = tempfile::tempdir().unwrap();
    let stim = dir.path().join("stim.txt");
    std::fs::write(&stim, "60ms press btnCpuReset 5s\n").unwrap();
    let o = board(&[
        "tests/board_designs/phases",
        "--program",
        "tests/board_designs/phases/phases.psm",
        "--cpu",
        "iss",
        "--bot",
        "model",
        "--samples",
        "3",
        "--stimulus",
        stim.to_str().unwrap(),
    ]);
    // Samples 0 and 1 come after reset, sample 2 about 53 ms later, sample 3 would come after
    // the reset is pressed.
    let e = one_line_error(&o);
    assert!(e.starts_with("no bot sample in 1 s of board time after sample 2 at 5"), "{e}");
    assert!(e.ends_with(" ms (upd_sysregs never pulsed: is the bot held in reset, or its clock stopped?)"), "{e}");
    // A bot that keeps sampling runs on past 1 s (25 samples, 1.33 s), however long one call
    // into the model runs (the Project 2 example shows little: the whole run is one call).
    let o = example("examples/nexys4_proj2", &["--cpu", "iss", "--samples", "25", "--json"]);
    let s = summary(&o);
    assert_eq!(s["samples"], 26, "{s}");
}

/// The signals a VCD file declares, named as GTKWave names them (`TOP.a.b.sig[7:0]`).
#[test]
fn the_save_file_lists_only_signals_the_waveform_has() {
    // --cpu iss runs the bot as its model: the waveform has the bot's ports but no bot CPU,
    // and the save file must not list one (GTKWave would open with missing signals).
    let dir = tempfile::tempdir().unwrap();
    for bot in ["model", "rtl"] {
        let vcd = dir.path().join(format!("{bot}.vcd"));
        let o = follower(&["--cpu", "iss", "--bot", bot, "--seconds", "0.0003", "--vcd", vcd.to_str().unwrap(), "-q"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let have = common::debug::vcd_signals(&vcd);
        let gtkw = std::fs::read_to_string(vcd.with_extension("gtkw")).unwrap();
        let listed: Vec<&str> = gtkw.lines().filter(|l| l.starts_with("TOP.")).collect();
        let missing: Vec<&&str> = listed.iter().filter(|l| !have.contains(**l)).collect();
        assert!(missing.is_empty(), "{bot}: {} of {} listed signals missing: {missing:?}", missing.len(), listed.len());
        assert_eq!(listed.iter().any(|l| l.contains("BOTSIMCPU")), bot == "rtl", "{bot}");
    }
}

#[test]
fn a_run_stops_at_the_first_move_the_world_refuses_when_asked() {
    // The demo firmware drives forward (its switches all off) until a wall stops the bot.
    let demo = |extra: &[&str]| {
        let mut args = vec!["--timing", "fast", "--compat", "botsim20", "--cpu", "iss", "--json"];
        args.extend_from_slice(extra);
        summary(&example("examples/nexys4_proj2", &args))
    };
    let whole = demo(&["--samples", "1500"]);
    let k = whole["first_blocked_sample"].as_u64().expect("the demo drives into a wall within 1500 samples");
    assert_eq!(whole["stopped_by"], "samples");
    let stopped = demo(&["--samples", "1500", "--stop-when-blocked"]);
    assert_eq!(stopped["stopped_by"], "blocked", "{stopped}");
    assert_eq!(stopped["first_blocked_sample"], k);
    // Sample k shows the forward move's event, sample k + 1 the bot still in place: 0..=k+1.
    assert_eq!(stopped["samples"], k + 2);
    assert_eq!(stopped["blocked_moves"], 1);
}

#[test]
fn memory_cores_committed_as_a_coe_alone_are_memories_of_its_words() {
    // Two cores instantiated by module name with no configuration and no wrapper: `sprite`
    // beside its `sprite.coe` (in another folder), `knitg` whose contents the team keeps in
    // `frt.coe` (a renamed core: --memory names it). Radix 16 and 2, 12 and 4 bits wide.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir_all(d.join("hdl")).unwrap();
    std::fs::create_dir_all(d.join("art")).unwrap();
    std::fs::write(
        d.join("hdl/top.v"),
        "module top(input clk, input btnCpuReset, input [15:0] sw, output [15:0] led);\n\
         \x20 knitg SPRITE_A (.clka(clk), .addra(sw[1:0]), .douta(led[11:0]));\n\
         \x20 sprite SPRITE_B (.clka(clk), .ena(sw[15]), .addra(sw[3:2]), .douta(led[15:12]));\n\
         endmodule\n",
    )
    .unwrap();
    std::fs::write(
        d.join("art/frt.coe"),
        "; knitting pattern\nmemory_initialization_radix=16;\nmemory_initialization_vector=\n0A5, 3C0,\nFFF, 001;\n",
    )
    .unwrap();
    std::fs::write(
        d.join("art/sprite.coe"),
        "memory_initialization_radix = 2;\nmemory_initialization_vector = 0001 0010 0100 1000;\n",
    )
    .unwrap();
    // Without --memory: `knitg` is missing, offered the file that fits (not `sprite.coe`,
    // `sprite`'s own), whose name resembles the module's too little to be taken.
    let o = common::board_in(d, &[".", "--seconds", "0.0001"]);
    let e = common::stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("`knitg` (instance `SPRITE_A` in `top`): a memory core with no configuration and no knitg.coe, and no .coe's name resembles the module's; those that fit its 2-bit address and 12-bit data, closest first: frt.coe; --memory knitg=frt.coe names the first (or another FILE), or tie it off with --stub knitg"),
        "{e}"
    );
    let o = common::board_in(d, &[".", "--memory", "knitg=art/frt.coe", "--seconds", "0.0001"]);
    let said = common::stderr(&o);
    assert!(o.status.success(), "{said}");
    for line in [
        "replaced knitg with a Block Memory Generator core, read latency 1, 12 x 4, from art/frt.coe alone (no configuration)",
        "replaced sprite with a Block Memory Generator core, read latency 1, 4 x 4, from art/sprite.coe alone (no configuration)",
    ] {
        assert!(said.contains(line), "{said}");
    }
    for (sw, want) in [(0x8000u32, 0x10A5u64), (0x8005, 0x23C0), (0x800A, 0x4FFF), (0x800F, 0x8001), (0x000F, 0x0001)] {
        let sw = format!("{sw:04X}");
        let o = common::board_in(
            d,
            &[".", "--memory", "knitg=art/frt.coe", "--switches", &sw, "--seconds", "0.0001", "--json"],
        );
        assert!(o.status.success(), "{}", common::stderr(&o));
        let s: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(s["leds"].as_u64().unwrap(), want, "switches {sw}: {s}");
    }
    // A connection wider than the file's words: one warning at the instance, as Vivado's.
    let top = std::fs::read_to_string(d.join("hdl/top.v")).unwrap();
    std::fs::write(d.join("hdl/top.v"), top.replace(".douta(led[15:12])", ".douta(led[15:8])")).unwrap();
    let o = common::board_in(d, &[".", "--memory", "knitg=art/frt.coe", "--seconds", "0.0001"]);
    let said = common::stderr(&o);
    let warned: Vec<&str> = said.lines().filter(|l| l.contains("douta")).collect();
    assert_eq!(warned.len(), 1, "{said}");
    assert!(
        warned[0].starts_with("warning: hdl/top.v:3:")
            && warned[0].contains(
                "the design connects 8 bits to `douta` of `sprite`, 4 bits wide in a Block Memory Generator core"
            )
            && warned[0].ends_with(
                "from art/sprite.coe alone (no configuration): as Vivado builds it, the design's upper 4 bits read 0"
            ),
        "{}",
        warned[0]
    );
}

/// A 1024 x 768 timing generator written as many teams write theirs: it counts to its totals
/// inclusively (`col == 1344`, `row >= 806`: 1345 pixels a line, 807 lines a frame) and ends
/// its syncs with `<=` (137 pixels, 7 lines). A monitor shows it as 1024 x 768 at 60 Hz, and so
/// does `--frames`: every pixel where the design draws it (the colour bands, the bot's box at
/// a location of the run's trace).
#[test]
fn a_vga_generator_counting_its_totals_inclusively_still_gives_frames() {
    let dir = tempfile::tempdir().unwrap();
    let top = dir.path().join("top");
    std::fs::create_dir(&top).unwrap();
    let original = std::fs::read_to_string(root().join("tests/board_designs/vga1024/nexys4fpga.v")).unwrap();
    let mut text = original.clone();
    for (from, to) in [
        ("col == 11'd1343", "col == 11'd1344"),
        ("row == 10'd805", "row >= 10'd806"),
        ("col < 11'd1184", "col <= 11'd1184"),
        ("row < 10'd777", "row <= 10'd777"),
    ] {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    std::fs::write(top.join("nexys4fpga.v"), text).unwrap();
    let (frames, csv) = (dir.path().join("frames"), dir.path().join("t.csv"));
    let o = example(
        top.to_str().unwrap(),
        &["--seconds", "0.06", "--frames", frames.to_str().unwrap(), "--trace-csv", csv.to_str().unwrap(), "--json"],
    );
    let summary = summary(&o);
    assert!(summary["vga_frames"].as_u64().unwrap() >= 2, "{summary}");
    assert_eq!(summary["vga_unknown_frames"], 0, "{summary}");
    let places: Vec<(u64, u64)> = rows(&csv).iter().map(|r| (r[2], r[3])).collect();
    let png = std::fs::read(frames.join("frame_00001.png")).unwrap();
    let (w, h, rgb) = common::rgb(&png);
    assert_eq!((w, h), (1024, 768));
    let white: Vec<(u64, u64)> = rgb
        .chunks(3)
        .enumerate()
        .filter(|(_, px)| px == &[255, 255, 255])
        .map(|(k, _)| (k as u64 % 1024, k as u64 / 1024))
        .collect();
    let (x0, y0) = white[0];
    assert!(places.contains(&(x0 / 8, y0 / 6)) && x0 % 8 == 0 && y0 % 6 == 0, "box at ({x0}, {y0}): {places:?}");
    for (k, px) in rgb.chunks(3).enumerate() {
        let (col, row) = (k as u64 % 1024, k as u64 / 1024);
        let in_box = (x0..x0 + 8).contains(&col) && (y0..y0 + 6).contains(&row);
        let c = if in_box { 0xFFF } else { (col >> 6 & 15) << 8 | (row >> 6 & 15) << 4 | 3 };
        let want = [(c >> 8 & 15) as u8 * 17, (c >> 4 & 15) as u8 * 17, (c & 15) as u8 * 17];
        assert_eq!(px, want, "pixel ({col}, {row})");
    }
}
