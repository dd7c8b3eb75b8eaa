//! The fast-forward on the shapes teams' designs have (tests/board_designs/shapes: a polling
//! team CPU, a display refreshed from a 2^18 or 2^20 counter, a 32-bit free-running counter,
//! 25 Hz and 10 Hz toggles, clocks from a DCM_SP or an MMCM): each skips nearly all of its
//! board time, and its records are those of every edge simulated, pin for pin, across
//! button presses, a switch change and a CPU reset.

use std::process::Output;

use crate::common;

use common::root;

fn board(args: &[&str]) -> Output {
    common::board_in(&root(), args)
}

/// The shapes design with `params`, for 0.3 s of board time at hw timing under a stimulus;
/// its records and summary, fast-forwarding or every edge simulated.
struct Run {
    pins: String,
    trace: String,
    display: String,
    summary: serde_json::Value,
}

fn run(params: &[&str], fast_forward: bool) -> Run {
    let params = [&["SIMULATE=1"], params].concat();
    run_design(&["tests/board_designs/shapes", "examples/common/nexys4_bot_if.v"], &params, fast_forward)
}

/// `design` (its sources) with `params`, as [`run`] runs the shapes design.
fn run_design(design: &[&str], params: &[&str], fast_forward: bool) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let file = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    // Buttons (debounced in four ticks of 6 clocks), the switches that drive the bot, and the CPU reset.
    std::fs::write(
        dir.path().join("stimulus.txt"),
        "60ms press btnC 20ms\n130ms switches 0033\n170ms press btnCpuReset 5ms\n230ms press btnU 1ms\n250ms switches 0000\n",
    )
    .unwrap();
    let stimulus = file("stimulus.txt");
    let (pins, trace, display) = (file("pins.csv"), file("trace.csv"), file("display.txt"));
    let mut args = design.to_vec();
    args.extend([
        "--seconds",
        "0.3",
        "--stimulus",
        &stimulus,
        "--pins",
        &pins,
        "--trace-csv",
        &trace,
        "--display",
        &display,
        "--json",
    ]);
    for p in params {
        args.extend(["--param", p]);
    }
    if !fast_forward {
        args.push("--no-fast-forward");
    }
    let o = board(&args);
    assert!(o.status.success(), "{params:?}: {}", String::from_utf8_lossy(&o.stderr));
    let read = |p: &str| std::fs::read_to_string(p).unwrap();
    Run {
        pins: read(&pins),
        trace: read(&trace),
        display: read(&display),
        summary: serde_json::from_slice(&o.stdout).unwrap(),
    }
}

/// The first row where two logs differ, for the message.
fn first_difference(a: &str, b: &str) -> String {
    let (a, b): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    let i = a.iter().zip(&b).position(|(x, y)| x != y).unwrap_or(a.len().min(b.len()));
    format!("row {i}: every edge {:?}, fast-forward {:?} ({} and {} rows)", a.get(i), b.get(i), a.len(), b.len())
}

fn skips_and_equals_every_edge(params: &[&str]) {
    skips_and_equals_every_edge_at_least(params, 0.95);
}

fn skips_and_equals_every_edge_at_least(params: &[&str], fraction: f64) {
    let (every, fast) = (run(params, false), run(params, true));
    // The LEDs showed the buttons.
    assert!(every.display.contains("leds    0000000000010000"), "{params:?}: {}", every.display);
    equal_and_skipped(params, &every, &fast, fraction);
}

fn equal_and_skipped(params: &[&str], every: &Run, fast: &Run, fraction: f64) {
    let ff = &fast.summary["fast_forward"];
    let skipped = ff["skipped_seconds"].as_f64().unwrap() / fast.summary["simulated_seconds"].as_f64().unwrap();
    assert!(skipped > fraction, "{params:?}: skipped {:.1} % ({ff})", skipped * 100.0);
    assert_eq!(every.summary["fast_forward"]["skips"], 0);
    // The run did what the stimulus asked: samples, the CPU reset blanking the display.
    let rows = (every.trace.lines().count(), every.pins.lines().count());
    assert!(rows.0 > 5 && rows.1 > 50, "{params:?}: {rows:?}");
    for (what, a, b) in [
        ("--pins", &every.pins, &fast.pins),
        ("--trace-csv", &every.trace, &fast.trace),
        ("--display", &every.display, &fast.display),
    ] {
        assert!(a == b, "{params:?} {what}: {}", first_difference(a, b));
    }
}

#[test]
fn a_nexys3_design_with_a_dcm_and_the_course_modules_at_simulate_1_and_0() {
    // The course's debounce and four-digit sevensegment, CLK0 and CLKDV of a DCM_SP, VGA,
    // a firmware waiting on its scratchpad (tests/board_designs/nexys3_dcm).
    let design = ["tests/board_designs/nexys3_dcm"];
    for simulate in ["SIMULATE=1", "SIMULATE=0"] {
        let (every, fast) = (run_design(&design, &[simulate], false), run_design(&design, &[simulate], true));
        equal_and_skipped(&[simulate], &every, &fast, 0.95);
    }
}

#[test]
fn a_pwm_on_a_32_bit_counters_low_byte() {
    // The low byte repeats every 256 clocks while the rest counts (a split counter). With the
    // debounce's 6 clocks and the CPU's 18-clock loop the board repeats every 2,304 clocks,
    // and each of the display's digits (2^15 clocks) costs two of them to prove the counters'
    // drift, and a settle: at most about 85 % can be skipped.
    skips_and_equals_every_edge_at_least(&["FREE32=2"], 0.8);
}

#[test]
fn a_polling_cpu_beside_a_2_18_refresh_counter() {
    skips_and_equals_every_edge(&[]);
}

#[test]
fn a_32_bit_counter_and_toggles_the_display_and_leds_show() {
    skips_and_equals_every_edge(&["FREE32=1", "TOGGLES=2"]);
}

/// A tone on an LED whose half period a `case` on the switches chooses (Verilator inlines the
/// choice of constants into the counter's comparison: `c + 1 >= (sw == 0 ? 190840 : ...)`):
/// the counter is moved on up to the nearest of those constants, switches changing or not.
#[test]
fn a_tone_whose_note_a_case_on_the_switches_chooses() {
    skips_and_equals_every_edge(&["TOGGLES=3"]);
}

#[test]
fn a_dcm_with_the_display_on_its_divided_clock() {
    skips_and_equals_every_edge(&["CLOCKING=1", "TOGGLES=1"]);
}

#[test]
fn an_mmcm_at_25_mhz_with_a_2_20_refresh() {
    skips_and_equals_every_edge(&["CLOCKING=2", "REFRESH_BITS=20", "FREE32=1"]);
}

/// A sprite where the bot is on a VGA raster whose pixel clock the design toggles, its pixel
/// on an LED (pdxrayw_p2video's icon): the LED changes as the raster crosses the sprite, so
/// the line counter cannot be skipped across the window's rows, nor the pixel counter across
/// its columns; between them the sprite's row within the window (`v - top`, read only inside
/// it) tells nothing, and lines are skipped three at a time (with the CPU's 12-clock loop),
/// the pixel counter taken as state. Each digit of the display (2^17 clocks) costs one of
/// those periods to prove again (no counter took a constant it may be set to); in the
/// window's rows the trial ends (the line counter leaves its interval at every line) and
/// each line is skipped in parts, between the columns the design compares: about 89 % is
/// skipped (87.5 % when the trial waits out its patience there, 78 % with two periods of
/// proof as well; 1.5 % when the row's read inside the window counts everywhere).
#[test]
fn a_sprite_on_a_raster_clocked_in_logic_whose_pixel_an_led_shows() {
    skips_and_equals_every_edge_at_least(&["SPRITE=1", "REFRESH_BITS=20"], 0.88);
}

/// A watchdog (WATCHDOG=1): a count cleared by a heartbeat every 511 clocks while armed and
/// held at 0 while not, lighting LED 12 at 1000 (never). The heartbeat's first clear after
/// the arming may come in the middle of the first period marked: the count then moved by
/// what looks like a drift that no later period repeats. That period took the constant the
/// count is set to, so it proves nothing alone and the next must move it as far; taken for
/// proof alone, the skips drove the count past 1000 and lit LED 12 (measured). About 70 %
/// is skipped (the board's period is the heartbeat's 511 clocks times the CPU's loop).
#[test]
fn a_watchdog_cleared_by_a_heartbeat_in_the_middle_of_the_period() {
    skips_and_equals_every_edge_at_least(&["WATCHDOG=1", "REFRESH_BITS=20"], 0.6);
}

#[test]
fn a_part_that_runs_apart_from_everything_observed() {
    // FREE_PART=1: an LFSR of a 32,767-clock cycle that only a register reads, and that only
    // while a switch is on (it is off): the rest repeats with it every 32,767 x its own
    // period only. Its cycle apart, the rest's period skips.
    skips_and_equals_every_edge_at_least(&["FREE_PART=1"], 0.88);
}

#[test]
fn a_second_core_in_nested_delays_runs_apart_from_the_board() {
    // OWN_CORE=1: a second KCPSM6 waits in four nested delay loops (17 ms) beside the team's
    // CPU and a display refreshed every 2.6 ms, as a team's own BotSim 3.1 bot does; its read
    // mux keeps its value at two ports. No common period of the loops and the display comes
    // within a refresh: the core runs apart, on its own over each skip (3.5 % skipped
    // without).
    skips_and_equals_every_edge_at_least(&["OWN_CORE=1"], 0.95);
}

/// The shapes design's arguments with `extra`.
fn shapes(extra: &[&str]) -> Output {
    let mut args = vec!["tests/board_designs/shapes", "examples/common/nexys4_bot_if.v"];
    args.extend(["--param", "SIMULATE=1", "--switches", "0300"]);
    args.extend(extra);
    board(&args)
}

fn json(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn the_bench_times_the_run_a_user_makes() {
    // The same skips and evaluations as the plain run of the same arguments: the bench cannot
    // measure another run than the one a user gets.
    let args = ["--param", "FREE32=1", "--seconds", "0.05", "--press", "btnC@20+5", "--json"];
    let plain = json(&shapes(&args));
    let mut bench_args = args.to_vec();
    bench_args.push("--bench");
    let bench = json(&shapes(&bench_args));
    assert_eq!(bench["skips"], plain["fast_forward"]["skips"], "{bench}\n{plain}");
    assert_eq!(bench["evaluations"], plain["evaluations"], "{bench}\n{plain}");
    assert!(bench["skips"].as_u64().unwrap() > 10, "{bench}");
    assert!(bench["speedup"].as_f64().unwrap() > 0.0 && bench["rtl_mcycles_per_s"].as_f64().unwrap() > 0.0, "{bench}");
}

#[test]
fn a_run_that_cannot_skip_names_what_kept_it_busy() {
    // FREE32=3: LED 15 shows a bit of an LFSR stepped every clock: the board never repeats
    // within the run. The run says which variable, where.
    let s = json(&shapes(&["--param", "FREE32=3", "--seconds", "0.02", "--json"]));
    let ff = &s["fast_forward"];
    assert!(ff["skipped_fraction"].as_f64().unwrap() < 0.5, "{ff}");
    let busy = &ff["kept_busy_by"];
    let text = std::fs::read_to_string(root().join("tests/board_designs/shapes/nexys4fpga.v")).unwrap();
    let line = text.lines().position(|l| l.contains("reg [31:0] lfsr")).unwrap() + 1;
    assert_eq!(
        (busy["variable"].as_str(), busy["module"].as_str(), busy["line"].as_u64()),
        (Some("lfsr"), Some("nexys4fpga"), Some(line as u64)),
        "{ff}"
    );
    // And in words, without --json.
    let o = shapes(&["--param", "FREE32=3", "--seconds", "0.02"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains(&format!("what kept it from skipping more: `lfsr` (module nexys4fpga, tests/board_designs/shapes/nexys4fpga.v:{line})")), "{out}");
}

#[test]
fn a_run_whose_skips_a_counter_ends_names_that_counter() {
    // FREE32=2 dims LED 15 from the free counter's low byte (a PWM, compared as state), and
    // TOGGLES=2 blinks a point and LED 14 from two long dividers: the
    // board repeats, and each skip ends where the display's refresh counter reaches the next
    // value its digit select compares it with (every 2^15 clocks). The run names that counter
    // where the design declares it, and says it ended the skips; so does --bench.
    let text = std::fs::read_to_string(root().join("tests/board_designs/shapes/nexys4fpga.v")).unwrap();
    let line = text.lines().position(|l| l.contains("reg [BITS-1:0] refresh")).unwrap() + 1;
    for bench in [false, true] {
        let mut args = vec!["--param", "FREE32=2", "--param", "TOGGLES=2", "--seconds", "0.02", "--json"];
        if bench {
            args.push("--bench");
        }
        let s = json(&shapes(&args));
        let busy = if bench { &s["kept_busy_by"] } else { &s["fast_forward"]["kept_busy_by"] };
        assert_eq!(
            (busy["variable"].as_str(), busy["module"].as_str(), busy["line"].as_u64(), busy["why"].as_str()),
            (Some("SSB.refresh"), Some("sevenseg"), Some(line as u64), Some("skips cut short")),
            "{s}"
        );
    }
    let o = shapes(&["--param", "FREE32=2", "--param", "TOGGLES=2", "--seconds", "0.02"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains(&format!(
            "what kept it from skipping more: `SSB.refresh` (module sevenseg, tests/board_designs/shapes/nexys4fpga.v:{line}), the next value the design compares it with ended"
        )),
        "{out}"
    );
}
