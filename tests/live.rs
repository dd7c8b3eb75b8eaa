//! `botsim board --live` over its WebSocket, as pages use it (docs/LIVE.md): the whole board
//! on connect, inputs that reach the design at the time the server states, two pages that
//! see the same, bad messages answered and ignored, a page that vanishes, ViDBo's shapes,
//! and a session replayed exactly from its recorded inputs.

mod common;

use std::time::Duration;

use common::live::{Live, BUDGET};
use serde_json::{json, Value};

/// The shapes design (a team CPU polling: the buttons on LED[4:0], the switches on the
/// motors), its debounce in simulation mode.
const SHAPES: [&str; 4] = ["tests/board_designs/shapes", "examples/common/nexys4_bot_if.v", "--param", "SIMULATE=1"];

fn shapes(extra: &[&str]) -> Vec<String> {
    SHAPES.iter().chain(extra).map(|s| s.to_string()).collect()
}

fn start(args: &[String]) -> Live {
    let a: Vec<&str> = args.iter().map(String::as_str).collect();
    Live::start(&a)
}

#[test]
fn a_page_gets_the_board_and_its_inputs_reach_the_design_at_the_stated_time() {
    let live = start(&shapes(&["--speed", "max"]));
    let mut a = live.client("/");
    // The whole board first: the design, the world, then its state.
    let hello = a.next(BUDGET).unwrap();
    assert_eq!(hello["type"], "hello", "{hello}");
    assert_eq!(hello["design"]["top"], "nexys4fpga");
    assert_eq!(hello["vga"], false, "the shapes design has no VGA pins");
    assert_eq!(hello["world"]["cells"].as_str().map(str::len), Some(128 * 128));
    // The board it is made for: a Nexys4 (lower-case names, no constraint file).
    assert_eq!((&hello["board"]["name"], &hello["board"]["digits"]), (&json!("NEXYS4"), &json!(8)), "{hello}");
    let s = a.state("a state", |s| s["samples"].as_u64() > Some(3));
    assert_eq!((s["switches"].as_u64(), s["leds"].as_u64().map(|l| l & 0x1F)), (Some(0), Some(0)), "{s}");
    // A second page, on another path, sees the same board.
    let mut b = live.client("/any/path");
    assert_eq!(b.next(BUDGET).unwrap()["type"], "hello");

    // Switches 7-0 drive the bot: 30 (right forward) instead of 33 (both forward) with them off.
    a.send(json!({"type": "switches", "value": "0030"}));
    let applied = b.log_entry("the input, in the other page's log", |e| e["kind"] == "input" && e["switches"] == 0x30);
    let t = applied["time_ps"].as_u64().unwrap();
    assert_eq!(t % 10_000, 0, "an input takes effect at a cycle boundary: {applied}");
    // Every sample before it shows the motors the switches at 0 gave, and from the first
    // one after it (the firmware polls them within a few cycles) the new ones.
    let mut seen_after = 0;
    b.until("three samples after the switches", |v| {
        for e in v["entries"].as_array().into_iter().flatten().filter(|e| e["kind"] == "sample") {
            let (at, motctl) = (e["time_ps"].as_u64().unwrap(), e["motctl"].as_u64().unwrap());
            if at < t {
                assert_eq!(motctl, 0x33, "{e}");
            } else {
                assert_eq!(motctl, 0x30, "a sample after the switches changed at {t} ps: {e}");
                seen_after += 1;
            }
        }
        seen_after >= 3
    });
    a.state("the switches in the state", |s| s["switches"] == 0x30);

    // A button is pressed while held: btnC lights LED 4 (the firmware copies the buttons).
    a.send(json!({"type": "button", "name": "btnC", "down": true}));
    let s = b.state("btnC's LED lit", |s| s["leds"].as_u64().unwrap() & 0x10 != 0);
    assert!(s["buttons"].as_array().unwrap().contains(&json!("btnC")), "{s}");
    a.send(json!({"type": "button", "name": "btnC", "down": false}));
    b.state("btnC's LED dark again", |s| s["leds"].as_u64().unwrap() & 0x10 == 0 && s["buttons"] == json!([]));
}

#[test]
fn a_bad_message_is_answered_and_changes_nothing_and_a_vanished_page_neither() {
    let live = start(&shapes(&["--speed", "max", "--switches", "0005"]));
    let mut a = live.client("/");
    a.next(BUDGET).unwrap();
    for bad in [
        "{nonsense",
        r#"{"type":"button","name":"btnZ","down":true}"#,
        r#"{"type":"switch","index":99,"on":true}"#,
        "[]",
    ] {
        a.send_text(bad);
        let e = a.until("an error", |v| v["type"] == "error");
        assert!(!e["message"].as_str().unwrap_or("").is_empty(), "{e}");
    }
    a.ws.send(tungstenite::Message::binary(vec![1, 2, 3])).unwrap();
    a.until("an error for a binary message", |v| v["type"] == "error");
    // Nothing changed: the switches are where they started, no input was logged.
    let s = a.state("a state after the bad messages", |_| true);
    assert_eq!(s["switches"], 5, "{s}");

    // A page that goes without a word (its socket shut): the board runs on for the others.
    let mut gone = live.client("/");
    gone.next(BUDGET).unwrap();
    if let tungstenite::stream::MaybeTlsStream::Plain(s) = gone.ws.get_mut() {
        s.shutdown(std::net::Shutdown::Both).unwrap();
    }
    drop(gone);
    let t0 = a.state("a state", |_| true)["time_ps"].as_u64().unwrap();
    a.state("the board running on", |s| s["time_ps"].as_u64().unwrap() > t0 + 50_000_000_000);
}

#[test]
fn vidbo_shapes_come_and_go() {
    let live = start(&shapes(&["--speed", "max"]));
    let mut v = live.client("/vidbo");
    v.next(BUDGET).unwrap();
    // Out: LEDs and the display's digits as ViDBo's front end shows them.
    let g = v.until("a gpio message", |m| m.get("gpio").is_some());
    assert!(g["gpio"]["LD0"].is_u64() && g["gpio"]["SevSegDispl7"].is_string(), "{g}");
    // In: a button by ViDBo's name.
    v.send(json!({"gpio": {"BTNC": true}}));
    v.until("LD4 lit", |m| m["gpio"]["LD4"] == 1);
    v.send(json!({"gpio": {"BTNC": false, "SW1": true}}));
    v.until("LD4 dark, switch 1 on", |m| {
        m["type"] == "state" && m["leds"].as_u64().unwrap() & 0x10 == 0 && m["switches"] == 2
    });
}

#[test]
fn a_live_session_replays_exactly_from_its_recorded_inputs() {
    let dir = tempfile::tempdir().unwrap();
    let record = dir.path().join("session.txt");
    let mut live = start(&shapes(&["--speed", "max", "--record", record.to_str().unwrap()]));
    let mut a = live.client("/");
    a.next(BUDGET).unwrap();
    // A session: switches, a button held for a while, a CPU reset, more switches.
    let mut samples: Vec<Value> = Vec::new();
    let mut keep = |v: &Value| {
        for e in v["entries"].as_array().into_iter().flatten() {
            if e["kind"] == "sample" {
                samples.push(e.clone());
            }
        }
    };
    let wait_samples = |a: &mut common::live::Client, n: usize, keep: &mut dyn FnMut(&Value)| {
        let mut got = 0;
        a.until("samples", |v| {
            keep(v);
            got += v["entries"].as_array().map_or(0, |e| e.iter().filter(|e| e["kind"] == "sample").count());
            got >= n
        });
    };
    wait_samples(&mut a, 3, &mut keep);
    a.send(json!({"type": "switches", "value": "0003"}));
    wait_samples(&mut a, 4, &mut keep);
    a.send(json!({"type": "button", "name": "btnU", "down": true}));
    wait_samples(&mut a, 2, &mut keep);
    a.send(json!({"type": "button", "name": "btnU", "down": false}));
    // The CPU reset, held a while: the bot restarts when it is released, so the cycle of
    // every sample after it tells the release's time to the cycle.
    a.send(json!({"type": "button", "name": "btnCpuReset", "down": true}));
    let t =
        a.log_entry("the reset pressed", |e| e["kind"] == "input" && e["down"] == true)["time_ps"].as_u64().unwrap();
    a.state("some time with the reset held", |s| s["time_ps"].as_u64().unwrap() > t + 30_000_000_000);
    a.send(json!({"type": "button", "name": "btnCpuReset", "down": false}));
    wait_samples(&mut a, 3, &mut keep);
    a.send(json!({"type": "switch", "index": 4, "on": true}));
    wait_samples(&mut a, 5, &mut keep);
    a.send(json!({"type": "stop"}));
    // The rest of the log up to the end.
    while let Some(v) = a.next(Duration::from_millis(500)) {
        keep(&v);
        if v["type"] == "closed" {
            break;
        }
    }
    assert!(live.wait().success());
    let text = std::fs::read_to_string(&record).unwrap();
    assert!(
        text.contains("press btnU") && text.contains("press btnCpuReset") && text.contains("switches 0013"),
        "{text}"
    );

    // Replayed without --live: the same samples, register for register.
    let last = samples.last().unwrap()["sample"].as_u64().unwrap();
    let trace = dir.path().join("trace.json");
    let mut args = shapes(&[]);
    args.extend(["--stimulus", record.to_str().unwrap(), "--samples", &last.to_string()].map(String::from));
    args.extend(["--trace-json", trace.to_str().unwrap(), "-q"].map(String::from));
    let o = common::board_in(&common::root(), &args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let replay: Vec<Value> =
        std::fs::read_to_string(&trace).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert!(samples.len() > 15, "{}", samples.len());
    for s in &samples {
        let n = s["sample"].as_u64().unwrap() as usize;
        let r = &replay[n];
        let regs = |v: &Value, keys: [&str; 8]| keys.map(|k| v[k].as_u64());
        assert_eq!(
            regs(s, ["cycle", "x", "y", "info", "sensors", "lmdist", "rmdist", "motctl"]),
            regs(r, ["cycle", "loc_x", "loc_y", "bot_info", "sensors", "lm_dist", "rm_dist", "next_motctl"]),
            "sample {n}: live {s}, replayed {r}"
        );
    }
}

/// `botsim run --live`: the bot alone, its motors from the page from the next iteration on,
/// the session's motor script replayed by `botsim run --motors` on the RTL: the same samples,
/// cycle for cycle. Switches are refused (the bot alone has none), and so are motors when a
/// driver drives.
#[test]
fn the_bot_alone_is_driven_from_the_page_and_replays_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let record = dir.path().join("motors.txt");
    let mut live =
        Live::start_command("run", &["--timing", "fast", "--speed", "max", "--record", record.to_str().unwrap()]);
    let mut a = live.client("/");
    let hello = a.next(BUDGET).unwrap();
    assert_eq!((hello["type"].as_str(), hello["mode"].as_str()), (Some("hello"), Some("bot")), "{hello}");
    let mut samples: Vec<Value> = Vec::new();
    let mut inputs: Vec<Value> = Vec::new();
    let seen =
        |a: &mut common::live::Client, what: &str, n: usize, samples: &mut Vec<Value>, inputs: &mut Vec<Value>| {
            let want = samples.len() + n;
            a.until(what, |v| {
                for e in v["entries"].as_array().into_iter().flatten() {
                    match e["kind"].as_str() {
                        Some("sample") => samples.push(e.clone()),
                        Some("input") => inputs.push(e.clone()),
                        _ => {}
                    }
                }
                samples.len() >= want
            });
        };
    seen(&mut a, "samples while stopped", 5, &mut samples, &mut inputs);
    a.send(json!({"type": "switch", "index": 0, "on": true}));
    let e = a.until("the switch refused", |v| v["type"] == "error");
    assert!(e["message"].as_str().unwrap().contains("motors"), "{e}");
    for (k, m) in ["33", "32", "03", "22"].into_iter().enumerate() {
        a.send(json!({"type": "motors", "value": m}));
        // Forty samples from the iteration the change applies to (the page may be far
        // behind the run: its log is read up to there).
        while inputs.len() <= k
            || samples.last().unwrap()["sample"].as_u64() < inputs[k]["iteration"].as_u64().map(|i| i + 40)
        {
            seen(&mut a, "samples after a motor change", 1, &mut samples, &mut inputs);
        }
    }
    a.send(json!({"type": "stop"}));
    while let Some(v) = a.next(Duration::from_millis(500)) {
        for e in v["entries"].as_array().into_iter().flatten() {
            match e["kind"].as_str() {
                Some("sample") => samples.push(e.clone()),
                Some("input") => inputs.push(e.clone()),
                _ => {}
            }
        }
        if v["type"] == "closed" {
            break;
        }
    }
    assert!(live.wait().success());
    // Each change from the iteration after the last sample then: every sample of an iteration
    // from there on (until the next change) was made with it.
    assert_eq!(inputs.len(), 4, "{inputs:?}");
    for (k, i) in inputs.iter().enumerate() {
        let from = i["iteration"].as_u64().unwrap();
        let to = inputs.get(k + 1).map_or(u64::MAX, |n| n["iteration"].as_u64().unwrap());
        for s in samples.iter().filter(|s| (from..to).contains(&s["sample"].as_u64().unwrap())) {
            assert_eq!(s["motctl"], i["motors"], "{s} after {i}");
        }
    }
    let moved = samples.iter().filter(|s| s["x"] != 64 || s["y"] != 64).count();
    assert!(moved > 20, "the bot moved in {moved} samples");

    // The recorded script, replayed on the RTL.
    let last = samples.last().unwrap()["sample"].as_u64().unwrap();
    let trace = dir.path().join("trace.json");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_botsim"))
        .args(["run", "--timing", "fast", "--motors", record.to_str().unwrap(), "--samples", &last.to_string()])
        .args(["--trace-json", trace.to_str().unwrap(), "-q"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let replay: Vec<Value> =
        std::fs::read_to_string(&trace).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(replay.len() as u64, last + 1);
    for s in &samples {
        let n = s["sample"].as_u64().unwrap() as usize;
        let r = &replay[n];
        let regs = |v: &Value, keys: [&str; 7]| keys.map(|k| v[k].as_u64());
        assert_eq!(
            regs(s, ["cycle", "x", "y", "info", "sensors", "lmdist", "rmdist"]),
            regs(r, ["cycle", "loc_x", "loc_y", "bot_info", "sensors", "lm_dist", "rm_dist"]),
            "sample {n}: live {s}, replayed {r}"
        );
        if n > 0 {
            assert_eq!(s["motctl"], replay[n - 1]["next_motctl"], "the motors of iteration {n}");
        }
    }

    // With a driver, the page's motors are refused.
    let live = Live::start_command("run", &["--timing", "fast", "--driver", "line-follow", "--paused"]);
    let mut b = live.client("/");
    assert_eq!(b.next(BUDGET).unwrap()["driver"], "the line follower");
    b.send(json!({"type": "motors", "value": 51}));
    let e = b.until("the motors refused", |v| v["type"] == "error");
    assert!(e["message"].as_str().unwrap().contains("line follower drives"), "{e}");
}

/// A page that vanishes in the middle of a VGA frame (its socket shut after the frame's
/// message, its PNG on the way) changes nothing: the board and its frames go on for the
/// other page, and a slow page is never waited for.
#[test]
fn a_page_that_vanishes_mid_frame_changes_nothing() {
    let live = Live::start(&["examples/common", "examples/nexys4_vga", "--param", "SIMULATE=1", "--speed", "max"]);
    let mut gone = live.client("/");
    // Read raw messages up to a frame's text message: its binary PNG comes next.
    let start = std::time::Instant::now();
    loop {
        assert!(start.elapsed() < BUDGET, "no frame came");
        match gone.ws.read() {
            Ok(tungstenite::Message::Text(t)) if t.contains("\"type\":\"frame\"") => break,
            Ok(_) => {}
            Err(tungstenite::Error::Io(e))
                if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {}
            Err(e) => panic!("{e}"),
        }
    }
    if let tungstenite::stream::MaybeTlsStream::Plain(s) = gone.ws.get_mut() {
        s.shutdown(std::net::Shutdown::Both).unwrap();
    }
    drop(gone);
    // Another page that never reads (a slow one) stays connected meanwhile.
    let _slow = live.client("/");
    let mut a = live.client("/");
    a.next(BUDGET).unwrap();
    let t0 = a.state("a state", |_| true)["time_ps"].as_u64().unwrap();
    let before = a.frames.len();
    a.state("the board running on", |s| s["time_ps"].as_u64().unwrap() > t0 + 200_000_000_000);
    let start = std::time::Instant::now();
    while a.frames.len() == before {
        assert!(start.elapsed() < BUDGET, "no frame after the page vanished");
        a.next(Duration::from_millis(200));
    }
    let (meta, png) = a.frames.last().unwrap();
    assert_eq!(common::rgb(png).0, 640, "{meta}");
}

/// A 1024 x 768 design (tests/board_designs/vga1024: a 65.04 MHz pixel clock from an MMCM,
/// colour bands and a box where the bot is) live: its frames come at that size, each pixel as
/// the design draws it for the bot of the frame's sample, and a later frame shows the bot
/// moved.
#[test]
fn a_1024_by_768_design_shows_its_frames_live() {
    let live =
        Live::start(&["examples/common", "tests/board_designs/vga1024", "--param", "SIMULATE=1", "--speed", "max"]);
    let mut a = live.client("/");
    assert_eq!(a.next(BUDGET).unwrap()["vga"], true);
    let mut samples: Vec<Value> = Vec::new();
    let mut checked: Vec<(u64, u64)> = Vec::new();
    let start = std::time::Instant::now();
    while checked.len() < 2 {
        assert!(start.elapsed() < BUDGET, "frames checked: {checked:?}");
        if let Some(v) = a.next(Duration::from_millis(200)) {
            samples.extend(v["entries"].as_array().into_iter().flatten().filter(|e| e["kind"] == "sample").cloned());
        }
        let Some((meta, png)) = a.frames.pop() else { continue };
        // A frame of one sample's bot, once that sample is in the log.
        let sample = meta["sample"].as_u64();
        if sample.is_none() || meta["sample_from"].as_u64() != sample {
            continue;
        }
        let Some(e) = samples.iter().find(|e| e["sample"].as_u64() == sample) else {
            a.frames.push((meta, png));
            continue;
        };
        let (x, y) = (e["x"].as_u64().unwrap(), e["y"].as_u64().unwrap());
        if checked.last().is_some_and(|c| *c == (x, y)) {
            continue;
        }
        let (w, h, rgb) = common::rgb(&png);
        assert_eq!((w, h), (1024, 768), "{meta}");
        for (k, px) in rgb.chunks(3).enumerate() {
            let (col, row) = (k as u64 % 1024, k as u64 / 1024);
            let in_box = (x * 8..x * 8 + 8).contains(&col) && (y * 6..y * 6 + 6).contains(&row);
            let c = if in_box { 0xFFF } else { (col >> 6 & 15) << 8 | (row >> 6 & 15) << 4 | 3 };
            let want = [(c >> 8 & 15) as u8 * 17, (c >> 4 & 15) as u8 * 17, (c & 15) as u8 * 17];
            assert_eq!(
                px, want,
                "pixel ({col}, {row}) of the frame of sample {sample:?}, the bot at ({x}, {y}): {meta}"
            );
        }
        checked.push((x, y));
    }
}

#[test]
fn a_board_that_cannot_keep_the_pace_says_why_in_one_line() {
    // FREE32=3: LED 15 shows an LFSR stepped every clock; nothing repeats, the board runs at
    // every edge's pace, well under real time.
    let live = start(&shapes(&["--param", "FREE32=3", "--speed", "1"]));
    let mut a = live.client("/");
    let s = a.state("a state saying the board is behind", |s| s["behind"].is_string());
    let line = s["behind"].as_str().unwrap();
    assert!(line.contains("x real time, not the 1 x asked"), "{line}");
    assert!(line.contains("`lfsr` (module nexys4fpga, tests/board_designs/shapes/nexys4fpga.v:"), "{line}");
    assert!(!line.contains('\n'), "{line}");
    // At full speed nothing is behind.
    let live = start(&shapes(&["--speed", "max"]));
    let mut b = live.client("/");
    let s = b.state("a state past a few samples", |s| s["samples"].as_u64() > Some(5));
    assert!(s["behind"].is_null(), "{s}");
}

#[test]
fn a_game_without_a_bot_plays_live_its_frames_following_the_animation() {
    use common::game::{box_place, Game, GAME};
    let live = Live::start(&[GAME, "--param", "SIMULATE=1", "--speed", "max"]);
    let mut a = live.client("/");
    let hello = a.next(BUDGET).unwrap();
    assert_eq!(hello["vga"], true, "{hello}");
    assert!(hello["world"].is_null(), "no world without a bot: {hello}");
    // No input: the box moves by itself, and the frames follow it (not one a second).
    let track = Game::track(2000);
    let mut places: Vec<(u8, u8)> = Vec::new();
    let start = std::time::Instant::now();
    while places.len() < 5 {
        assert!(start.elapsed() < BUDGET, "frames so far: {places:?}");
        a.next(Duration::from_millis(100));
        for (meta, png) in a.frames.drain(..) {
            let place = box_place(&png).unwrap_or_else(|e| panic!("{e}: {meta}"));
            assert!(track.contains(&place), "{place:?} is not on the box's track");
            places.push(place);
        }
    }
    // Each frame later than the one before: the box elsewhere each time.
    assert!(places.windows(2).all(|w| w[0] != w[1]), "{places:?}");
    // More than the one frame a second of a still picture.
    let s = a.state("a state with a frame rate", |s| s["frame_rate"].as_f64() > Some(0.0));
    assert!(s["bot"].is_null() && s["samples"] == 0, "{s}");
    // (More than one a second, not a margin above it: at `--speed max` a frame takes at most
    // half the wall time, so the rate follows the machine's load.)
    a.state("frames faster than a still picture's", |s| s["frame_rate"].as_f64() > Some(1.0));
    // Step on a board without a bot: 50 ms of board time and the frame that shows it (a
    // frame simulated from where its pixel path was parked: at most two frame periods),
    // then paused.
    a.send(json!({"type": "pause"}));
    let paused = a.state("paused", |s| s["running"] == false);
    let t0 = paused["time_ps"].as_u64().unwrap();
    a.send(json!({"type": "step"}));
    let stepped = a.state("a step's end", |s| s["running"] == false && s["time_ps"].as_u64() > Some(t0));
    let t1 = stepped["time_ps"].as_u64().unwrap();
    assert!((50_000_000_000..=84_000_000_000).contains(&(t1 - t0)), "stepped {} ps", t1 - t0);
}

/// A final project's peripherals over the WebSocket (tests/board_designs/console): the
/// design's greeting reaches the page as UART log entries (its rate measured), a line typed
/// comes back echoed, keys pressed and released reach the design's keyboard as scan codes
/// (its LEDs show the last two), an unknown key and a tilt the board cannot measure are
/// answered with one line each, and the session's inputs replay exactly without --live.
#[test]
fn the_console_plays_live_keys_and_uart_and_replays_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let record = dir.path().join("session.txt");
    let console = common::root().join("tests/board_designs/console");
    let mut live = Live::start(&[console.to_str().unwrap(), "--speed", "max", "--record", record.to_str().unwrap()]);
    let mut a = live.client("/");
    let hello = a.next(BUDGET).unwrap();
    assert_eq!(hello["peripherals"], json!({"uart": true, "keyboard": true, "accelerometer": false, "audio": false}));
    let mut heard = String::new();
    let listen = |v: &Value, heard: &mut String| {
        for e in v["entries"].as_array().into_iter().flatten() {
            if e["kind"] == "uart" {
                heard.push_str(e["text"].as_str().unwrap());
                assert_eq!(e["baud"], 115_200, "{e}");
            }
        }
    };
    a.until("the greeting", |v| {
        listen(v, &mut heard);
        heard.contains("botsim console\r\n")
    });
    a.send(json!({"type": "uart", "text": "live\r"}));
    a.until("the echo", |v| {
        listen(v, &mut heard);
        heard.ends_with("live\r")
    });
    assert_eq!(heard, "botsim console\r\nlive\r");
    a.send(json!({"type": "key", "code": "KeyZ", "down": true}));
    a.log_entry("the key pressed", |e| e["kind"] == "input" && e["key"] == "KeyZ");
    a.state("the make code on the LEDs", |s| s["leds"].as_u64() == Some(0x001A));
    a.send(json!({"type": "key", "code": "KeyZ", "down": false}));
    a.state("F0 then the code again", |s| s["leds"].as_u64() == Some(0xF01A));
    a.state("one key on the display", |s| s["text"] == "    0001");
    a.send(json!({"type": "key", "code": "Hyper", "down": true}));
    let e = a.until("the refusal", |v| v["type"] == "error");
    assert!(e["message"].as_str().unwrap().contains("unknown key `Hyper`"), "{e}");
    a.send(json!({"type": "stop"}));
    while let Some(v) = a.next(Duration::from_millis(500)) {
        if v["type"] == "closed" {
            break;
        }
    }
    assert!(live.wait().success());
    let text = std::fs::read_to_string(&record).unwrap();
    assert!(text.contains("uart \"live\\r\"") && text.contains("key KeyZ"), "{text}");
    // Replayed to 20 ms after the last input (a key's release: its time and how long it was
    // held): the same bytes on the UART, the same keys on the LEDs.
    let cycles = |w: Option<&str>| w.and_then(|w| w.strip_suffix('c')?.parse::<u64>().ok());
    let last = text
        .lines()
        .filter_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            let held = if w.get(1) == Some(&"key") { cycles(w.get(3).copied()) } else { Some(0) };
            Some(cycles(w.first().copied())? + held?)
        })
        .max();
    let seconds = format!("{}", last.unwrap() as f64 * 1e-8 + 0.02);
    let uart = dir.path().join("u.bin");
    let o = common::board_in(
        &common::root(),
        &[
            console.to_str().unwrap(),
            "--stimulus",
            record.to_str().unwrap(),
            "--seconds",
            &seconds,
            "--uart",
            uart.to_str().unwrap(),
            "--json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(&uart).unwrap(), b"botsim console\r\nlive\r");
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!((v["leds"].as_u64(), v["display"].as_str()), (Some(0xF01A), Some("    0001")), "{v}");
}

#[test]
fn a_nexys4_ddr_project_gets_a_nexys4_ddr_page() {
    // tests/board_designs/repos/final_project: its .xdc places the pins on a Nexys4 DDR
    // (`CPU_RESETN`, `BTNC`, ...): the page is told that board, with the Nexys4's controls.
    let clone = common::repo::clone_of("final_project");
    let live = Live::start_in(clone.path(), "board", &[".", "--speed", "max"]);
    let mut page = live.client("/");
    let hello = page.next(BUDGET).unwrap();
    let board = &hello["board"];
    assert_eq!(
        (&board["name"], &board["digits"], &board["leds"]),
        (&json!("NEXYS4 DDR"), &json!(8), &json!(16)),
        "{hello}"
    );
    assert_eq!(board["buttons"][0], json!(["btnCpuReset", "CPU RESET"]), "{hello}");
}
