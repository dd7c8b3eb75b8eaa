//! The live board's page in a real browser: Debian's headless Chromium (`/usr/bin/chromium`,
//! installed by scripts/setup.sh; never a downloaded one) loads the page of a live run of the
//! VGA example (its team firmware: LocX and LocY in hex on digits 7-4, the sensors on LED[7:0],
//! the motor byte on switches 7-0), clicks a switch and holds the CPU reset button, and the page
//! shows what the design does: the digits and LEDs as the registers say, the motors the
//! switch asked for, the bot moving on the world and back at its start after the reset, and a
//! VGA frame equal pixel for pixel to botsim's own frame of the bot at that frame's sample (the
//! frame `--frames` writes for that state: tests/boards/board.rs proves the two equal). A screenshot
//! of the page is kept in target/live-page.png.

mod common;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use base64::Engine;
use common::cdp::Page as Tab;
use common::live::{Live, BUDGET};
use serde_json::Value;

fn chromium() -> Option<PathBuf> {
    let p = PathBuf::from("/usr/bin/chromium");
    if p.exists() {
        return Some(p);
    }
    assert!(std::env::var_os("BOTSIM_REQUIRE_TOOLS").is_none(), "chromium is missing: run scripts/setup.sh");
    eprintln!("note: /usr/bin/chromium not found (scripts/setup.sh installs it); skipping");
    None
}

/// Headless Chromium with the page at `url` loaded (the browser ends when dropped).
fn open(chromium: PathBuf, url: &str) -> Tab {
    Tab::open(&chromium, url)
}

/// What the page shows, read in one go.
const PAGE: &str = r#"(() => {
  const on = (id) => { const e = document.getElementById(id); return !!e && e.classList.contains("on"); };
  const text = (id) => document.getElementById(id).textContent;
  const img = document.getElementById("vga");
  return JSON.stringify({
    status: text("status"),
    lit: digits.map((segs) => segs.reduce((a, s, k) => a | (s.classList.contains("on") ? 1 << k : 0), 0)),
    leds: Array.from({ length: 16 }, (_, i) => (on("ld" + i) ? 1 << i : 0)).reduce((a, b) => a | b, 0),
    x: text("r-x"), y: text("r-y"), heading: text("r-heading"), sensors: text("r-sensors"), motctl: text("r-motctl"),
    samples: state ? state.samples : 0, switches: state ? state.switches : 0, buttons: state ? state.buttons : [],
    running: state ? state.running : false, path: path.length, speed: document.getElementById("speed").value,
    placeholder: getComputedStyle(document.getElementById("novga")).display !== "none",
    frame: img.getAttribute("src") ? { sample: img.dataset.sample, from: img.dataset.sampleFrom } : null,
  });
})()"#;

fn page(tab: &Tab) -> Value {
    let v = tab.eval(PAGE, false);
    serde_json::from_str(v.as_str().unwrap()).unwrap()
}

/// Wait until the page shows what `want` looks for; the page then.
fn until(tab: &Tab, what: &str, mut want: impl FnMut(&Value) -> bool) -> Value {
    let start = Instant::now();
    loop {
        let p = page(tab);
        if want(&p) {
            return p;
        }
        assert!(start.elapsed() < BUDGET, "the page never showed {what}: {p}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// The PNG the page's VGA monitor shows, as the page has it.
fn monitor_png(tab: &Tab) -> Vec<u8> {
    let png = tab.eval(
        r#"fetch(document.getElementById("vga").src).then((r) => r.arrayBuffer()).then((b) => {
                 const u = new Uint8Array(b); let s = "";
                 for (let i = 0; i < u.length; i++) s += String.fromCharCode(u[i]);
                 return btoa(s);
               })"#,
        true,
    );
    base64::engine::general_purpose::STANDARD.decode(png.as_str().unwrap()).unwrap()
}

/// The hex digits the team firmware shows for a byte, as the glyphs read (b and d lower case).
fn hex_glyphs(v: u64) -> String {
    format!("{v:02X}").replace('B', "b").replace('D', "d")
}

#[test]
fn the_page_in_headless_chromium_plays_the_vga_example() {
    let Some(chromium) = chromium() else { return };
    let live = Live::start(&["examples/common", "examples/nexys4_vga", "--param", "SIMULATE=1", "--speed", "max"]);
    let tab = open(chromium, &live.url);
    let p = until(&tab, "the connection", |p| p["status"] == "live" && p["samples"].as_u64() > Some(2));
    assert_eq!(p["speed"], "max", "the speed list shows the run's --speed");

    // The digits as drawn, segment by segment: LocX and LocY in hex, as the registers say.
    let glyphs = |p: &Value| -> String {
        (4..8).rev().map(|d| botsim_core::board::display::glyph(p["lit"][d].as_u64().unwrap() as u8)).collect()
    };
    let reg = |p: &Value, k: &str| p[k].as_str().unwrap().parse::<u64>().unwrap_or(999);
    until(&tab, "LocX and LocY on the digits", |p| {
        p["x"] != "" && glyphs(p) == format!("{}{}", hex_glyphs(reg(p, "x")), hex_glyphs(reg(p, "y")))
    });
    // The LEDs show the sensors.
    until(&tab, "the sensors on LED[7:0]", |p| {
        p["sensors"] != "" && format!("{:08b}", p["leds"].as_u64().unwrap() & 0xFF) == p["sensors"].as_str().unwrap()
    });
    // The bot drives forward with the switches off: it moves on the world.
    let moved = until(&tab, "the bot moving", |p| p["path"].as_u64() > Some(3) && p["x"] != "64");

    // A click on switch 1: the motor byte 02 (the right wheel in reverse: a slow right turn,
    // botsim.md §4) and the bot turning.
    tab.click("#sw1");
    until(&tab, "switch 1 on, its motors", |p| p["switches"] == 2 && p["motctl"] == "02");
    until(&tab, "the bot turning", |p| p["heading"] != moved["heading"]);

    // The CPU reset button held down with the mouse, then let go: the bot back at its start.
    let reset = tab.midpoint("#btn-btnCpuReset");
    tab.mouse(true, reset.0, reset.1);
    until(&tab, "the reset held", |p| p["buttons"].as_array().is_some_and(|b| b.contains(&Value::from("btnCpuReset"))));
    tab.mouse(false, reset.0, reset.1);
    until(&tab, "the reset let go and the bot at its start", |p| {
        p["buttons"] == serde_json::json!([]) && p["x"] == "64" && p["y"] == "64"
    });

    // A frame on the monitor that shows one sample's bot, the run paused so it stays.
    until(&tab, "a frame of one sample", |p| {
        p["frame"]["sample"].is_string() && p["frame"]["sample"] == p["frame"]["from"]
    });
    tab.click("#run");
    let p = until(&tab, "the run paused", |p| p["running"] == false && p["frame"]["sample"] == p["frame"]["from"]);
    assert_eq!(p["placeholder"], false, "a frame hides the placeholder");
    let sample: u64 = p["frame"]["sample"].as_str().unwrap().parse().unwrap();
    let png = monitor_png(&tab);
    // The bot's registers at that sample, from the log every page gets.
    let mut client = live.client("/");
    let entry = client.log_entry("the frame's sample in the log", |e| e["kind"] == "sample" && e["sample"] == sample);
    let byte = |k: &str| entry[k].as_u64().unwrap() as u8;
    let snapshot = botsim::Snapshot {
        sample,
        cycle: 0,
        regs: botsim::Registers {
            loc_x: byte("x"),
            loc_y: byte("y"),
            bot_info: byte("info"),
            sensors: byte("sensors"),
            lm_dist: byte("lmdist"),
            rm_dist: byte("rmdist"),
        },
    };
    let want_png = botsim::render::display::frame(&botsim::World::builtin(), Some(&snapshot));
    let want = common::rgb(&want_png);
    let got = common::rgb(&png);
    assert_eq!((got.0, got.1), (640, 480));
    if got != want {
        // Both pictures kept for a look at what differs.
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target");
        std::fs::write(dir.join("live-frame-page.png"), &png).unwrap();
        std::fs::write(dir.join("live-frame-botsim.png"), &want_png).unwrap();
        panic!("the page's frame of sample {sample} is not botsim's frame of that sample ({entry}): target/live-frame-page.png, target/live-frame-botsim.png");
    }

    // A look at it (kept as an artefact of the test run).
    tab.click("#run");
    until(&tab, "the run again", |p| p["running"] == true);
    std::thread::sleep(Duration::from_millis(800));
    let shot = tab.screenshot();
    let out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/live-page.png");
    std::fs::write(&out, &shot).unwrap();
    assert!(common::rgb(&shot).0 >= 1400);
}

/// `botsim run --live` in the page: the motor panel instead of the board, its wheel buttons
/// setting MotCtl_in, the bot driving on the world (its path drawn). A screenshot in target/live-bot-page.png.
#[test]
fn the_page_drives_the_bot_alone() {
    let Some(chromium) = chromium() else { return };
    let live = Live::start_command("run", &["--timing", "fast", "--speed", "0.02"]);
    let tab = open(chromium, &live.url);
    let shown = r#"JSON.stringify({
        board: getComputedStyle(document.getElementById("board")).display !== "none",
        drive: !document.getElementById("drive").hidden,
        motors: state ? state.motors : null, x: document.getElementById("r-x").textContent,
        y: document.getElementById("r-y").textContent, moved: path.filter(([x, y]) => x !== 64 || y !== 64).length,
        on: Array.from(document.querySelectorAll(".wheel button.on")).map((b) => b.id),
    })"#;
    let look = |tab: &Tab| -> Value { serde_json::from_str(tab.eval(shown, false).as_str().unwrap()).unwrap() };
    let wait = |what: &str, want: &dyn Fn(&Value) -> bool| {
        let start = Instant::now();
        loop {
            let v = look(&tab);
            if want(&v) {
                return v;
            }
            assert!(start.elapsed() < BUDGET, "the page never showed {what}: {v}");
            std::thread::sleep(Duration::from_millis(100));
        }
    };
    let v = wait("the motor panel", &|v| v["drive"] == true && v["motors"] == 0 && v["x"] == "64");
    assert_eq!(v["board"], false, "no board for the bot alone");
    assert_eq!(v["on"], serde_json::json!(["lm-off", "rm-off"]));
    tab.click("#lm-fwd");
    wait("the left wheel forward", &|v| v["motors"] == 0x30);
    tab.click("#rm-fwd");
    wait("both wheels forward", &|v| v["motors"] == 0x33 && v["on"] == serde_json::json!(["lm-fwd", "rm-fwd"]));
    // (The left wheel alone turned it for a while: it drives off wherever it then heads.)
    wait("the bot driving", &|v| v["moved"].as_u64() > Some(30) && (v["x"] != "64" || v["y"] != "64"));
    let shot = tab.screenshot();
    std::fs::write(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/live-bot-page.png"), &shot).unwrap();
}

/// A final project without a bot in the page: no world and no bot registers, the game's
/// frames on the monitor with the box where game.psm puts it, and the left arrow key held
/// (the left button) holding the box at the left edge, where by itself it only passes. A
/// screenshot in target/live-game-page.png.
#[test]
fn the_page_plays_a_game_without_a_bot() {
    use common::game::{box_place, GAME};
    let Some(chromium) = chromium() else { return };
    let live = Live::start(&[GAME, "--param", "SIMULATE=1", "--speed", "max"]);
    let tab = open(chromium, &live.url);
    let shown = |tab: &Tab| -> Value {
        let v = tab.eval(
            r#"JSON.stringify({
                     world: !document.getElementById("worldbox").hidden,
                     regs: !document.getElementById("regs").hidden,
                     samples: document.getElementById("samples").textContent,
                     fps: document.getElementById("fps").textContent,
                     frame_ps: document.getElementById("vga").dataset.timePs || null })"#,
            false,
        );
        serde_json::from_str(v.as_str().unwrap()).unwrap()
    };
    until(&tab, "the connection and a frame", |p| p["status"] == "live" && p["frame"].is_object());
    let s = shown(&tab);
    assert_eq!((&s["world"], &s["regs"], &s["samples"]), (&Value::from(false), &Value::from(false), &Value::from("")));
    // The frame on the monitor: the game's picture.
    let frame = |tab: &Tab| -> ((u8, u8), u64) {
        let png = monitor_png(tab);
        let at = shown(tab)["frame_ps"].as_str().and_then(|t| t.parse().ok()).unwrap_or(0);
        (box_place(&png).unwrap(), at)
    };
    // The left arrow held: the box goes to the left edge and stays there, bouncing between x
    // 0 and 1 (by itself it passes the edge in three frames and goes on).
    tab.key("ArrowLeft", 37, true);
    until(&tab, "the left button held", |p| p["buttons"].as_array().is_some_and(|b| b.contains(&Value::from("btnL"))));
    let start = Instant::now();
    let mut at_edge: Vec<u64> = Vec::new();
    while at_edge.len() < 4 || at_edge[at_edge.len() - 1] - at_edge[0] < 200_000_000_000 {
        assert!(start.elapsed() < BUDGET, "the box did not stay at the left edge: {at_edge:?}");
        let ((x, _), at) = frame(&tab);
        if x > 1 {
            at_edge.clear();
        } else if at_edge.last() != Some(&at) {
            at_edge.push(at);
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    tab.key("ArrowLeft", 37, false);
    until(&tab, "the left button let go", |p| p["buttons"] == serde_json::json!([]));
    until(&tab, "a frame rate", |_| shown(&tab)["fps"].as_str().is_some_and(|f| f.ends_with("frames/s")));
    let shot = tab.screenshot();
    std::fs::write(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/live-game-page.png"), &shot).unwrap();
}

/// The peripherals' panels of the page as it shows them.
fn devices(tab: &Tab) -> Value {
    let v = tab.eval(
        r#"JSON.stringify({
                 panels: ["kbd", "uart", "tilt", "sound"].filter((id) => !document.getElementById(id).hidden),
                 console: document.getElementById("console-out").textContent,
                 baud: document.getElementById("baud").textContent,
                 tilt: document.getElementById("tilt-now").textContent,
                 sound: { samples: window.botsimSound.samples, peak: window.botsimSound.peak },
                 focused: document.activeElement === document.getElementById("board") })"#,
        false,
    );
    serde_json::from_str(v.as_str().unwrap()).unwrap()
}

/// Wait until the peripherals' panels show what `want` looks for.
fn devices_until(tab: &Tab, what: &str, mut want: impl FnMut(&Value) -> bool) -> Value {
    let start = Instant::now();
    loop {
        let d = devices(tab);
        if want(&d) {
            return d;
        }
        assert!(start.elapsed() < BUDGET, "the page never showed {what}: {d}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// A final project's console in the page (tests/board_designs/console): the greeting in the
/// console with its measured rate, a line typed into it echoed, and keys typed on the board
/// (it has the focus) reaching the design's keyboard: its LEDs show the scan codes.
#[test]
fn the_page_types_on_the_console_and_the_keyboard() {
    let Some(chromium) = chromium() else { return };
    let live = Live::start(&["tests/board_designs/console", "--speed", "max"]);
    let tab = open(chromium, &live.url);
    until(&tab, "the connection", |p| p["status"] == "live");
    let d = devices_until(&tab, "the greeting", |d| d["console"] == "botsim console\n");
    assert_eq!(d["panels"], serde_json::json!(["kbd", "uart"]));
    assert_eq!(d["baud"], "USB-UART, 115200 baud");
    tab.click("#console-in");
    tab.type_line("echo me");
    devices_until(&tab, "the echo", |d| d["console"] == "botsim console\necho me\n");
    // The board focused (a click on it), then keys: A, then the up arrow (E0 75).
    tab.click("#board");
    devices_until(&tab, "the board focused", |d| d["focused"] == true);
    tab.key("KeyA", 65, true);
    until(&tab, "A's make code", |p| p["leds"] == 0x1C);
    tab.key("KeyA", 65, false);
    until(&tab, "A's break code", |p| p["leds"] == 0xF01C);
    tab.key("ArrowUp", 38, true);
    until(&tab, "the up arrow's make code", |p| p["leds"] == 0xE075);
    tab.key("ArrowUp", 38, false);
    until(&tab, "two keys counted", |p| p["leds"] == 0xF075 && p["lit"][0] == 0x5B);
    tab.eval("window.scrollTo(0, 0)", false);
    let shot = tab.screenshot();
    std::fs::write(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/live-console-page.png"), &shot).unwrap();
}

/// The tilt pad tilts the board (tests/board_designs/tilt shows the accelerometer's x and y on
/// its LEDs), and the tone player's sound arrives as samples the page plays (sound on).
#[test]
fn the_page_tilts_the_board_and_plays_its_sound() {
    let Some(chromium) = chromium() else { return };
    let live = Live::start(&["tests/board_designs/tilt", "--speed", "1"]);
    let tab = open(chromium.clone(), &live.url);
    until(&tab, "flat: x and y 0", |p| p["status"] == "live");
    assert_eq!(devices(&tab)["panels"], serde_json::json!(["tilt"]));
    // Drag to the pad's right edge, half way up: x 1 g (LEDs 15-8 3E), y 0.
    let (x, y, w, h) = tab.rect("#tilt-pad");
    let (cx, cy, r) = (x + w / 2.0, y + h / 2.0, w / 2.0 - 10.0);
    tab.mouse(true, cx + r, cy);
    tab.mouse(false, cx + r, cy);
    devices_until(&tab, "x 1 g", |d| d["tilt"] == "x 1.00 g, y 0.00 g, z 0.00 g");
    until(&tab, "x 1 g on the LEDs", |p| p["leds"] == 0x3E00);
    let shot = tab.screenshot();
    std::fs::write(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/live-tilt-page.png"), &shot).unwrap();
    drop(tab);
    drop(live);

    let live = Live::start(&["tests/board_designs/tones", "--speed", "1", "--switches", "8005"]);
    let tab = open(chromium, &live.url);
    until(&tab, "the connection", |p| p["status"] == "live");
    assert_eq!(devices(&tab)["panels"], serde_json::json!(["sound"]));
    tab.click("#mute");
    let d = devices_until(&tab, "a second of sound", |d| d["sound"]["samples"].as_u64() > Some(48_000));
    assert!(d["sound"]["peak"].as_f64() > Some(0.2), "{d}");
}

#[test]
fn the_page_draws_every_bot_of_a_game() {
    // The two-bot game (tests/board_designs/repos/two_bots: the course's bot and a team's
    // BotSim 3.1 `bot31`, unnamed): the page draws the second in its own colour over the
    // first and says where it is.
    let Some(chromium) = chromium() else { return };
    let game = common::repo::clone_of("two_bots");
    let live = Live::start_in(game.path(), "board", &[".", "--param", "SIMULATE=1", "--speed", "max"]);
    let tab = open(chromium, &live.url);
    let shown = |tab: &Tab| -> Value {
        let v = tab
            .eval(
                r##"(() => {
                     const c = document.getElementById("world").getContext("2d");
                     const px = c.getImageData(0, 0, 512, 512).data;
                     let cyan = 0;
                     for (let i = 0; i < px.length; i += 4) cyan += px[i] === 0 && px[i + 1] === 200 && px[i + 2] === 200;
                     const text = (id) => document.getElementById(id).textContent;
                     const first = "(" + text("r-x") + ", " + text("r-y") + ") " + text("r-heading");
                     return JSON.stringify({ legend: text("others"), cyan, first });
                   })()"##,
                false,
            )
            ;
        serde_json::from_str(v.as_str().unwrap()).unwrap()
    };
    until(&tab, "a few samples", |p| p["status"] == "live" && p["samples"].as_u64().is_some_and(|n| n >= 3));
    // The second bot stands where the first does (the same motors): its place in the legend,
    // and its arrow on the world.
    let start = Instant::now();
    loop {
        let s = shown(&tab);
        let (legend, first) = (s["legend"].as_str().unwrap(), s["first"].as_str().unwrap());
        if legend.contains(&format!("nexys4fpga.SYS.bot31_72 {first}")) && s["cyan"].as_u64().unwrap() > 10 {
            break;
        }
        assert!(start.elapsed() < BUDGET, "the page never drew the second bot where the first is: {s}");
        std::thread::sleep(Duration::from_millis(100));
    }
    let shot = tab.screenshot();
    std::fs::write(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/live-two-bots-page.png"), &shot).unwrap();
}

/// The board the page drew: its name, its controls' counts, its button labels, the digits'
/// lit segments and the switches and digits of the state it last drew.
fn drawn_board(tab: &Tab) -> Value {
    let v = tab.eval(
        r##"JSON.stringify({
                 status: document.getElementById("status").textContent,
                 title: document.querySelector("#board .silk.big").textContent,
                 digits: digits.length, leds: leds.length, knobs: knobs.length,
                 labels: Array.from(document.querySelectorAll("#board text.silk")).map((t) => t.textContent)
                   .filter((t) => t.startsWith("BTN") || t === "CPU RESET"),
                 lit: digits.map((segs) => segs.reduce((a, s, k) => a | (s.classList.contains("on") ? 1 << k : 0), 0)),
                 state: state ? { digits: state.digits, switches: state.switches } : null })"##,
        false,
    );
    serde_json::from_str(v.as_str().unwrap()).unwrap()
}

/// Wait until the page is live and shows some digit lit; what it drew then.
fn board_with_digits(tab: &Tab) -> Value {
    let start = Instant::now();
    loop {
        let d = drawn_board(tab);
        if d["status"] == "live"
            && d["state"].is_object()
            && d["lit"].as_array().is_some_and(|l| l.iter().any(|x| x != 0))
        {
            return d;
        }
        assert!(start.elapsed() < BUDGET, "the page never showed the design's digits: {d}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn the_page_draws_a_nexys3_for_a_nexys3_design() {
    // tests/board_designs/nexys3_dcm: four digits, eight LEDs and switches, its reset the
    // centre button BTNS. The page draws that board, and its switches and digits work.
    let Some(chromium) = chromium() else { return };
    let live = Live::start(&["tests/board_designs/nexys3_dcm", "--param", "SIMULATE=1", "--speed", "max"]);
    let tab = open(chromium, &live.url);
    let d = board_with_digits(&tab);
    assert_eq!(d["title"], "NEXYS3", "{d}");
    assert_eq!((d["digits"].as_u64(), d["leds"].as_u64(), d["knobs"].as_u64()), (Some(4), Some(8), Some(8)), "{d}");
    let labels: Vec<&str> = d["labels"].as_array().unwrap().iter().filter_map(Value::as_str).collect();
    assert_eq!(labels, ["BTNS", "BTNU", "BTNL", "BTNR", "BTND"], "{d}");
    // The switch the page shows as SW3 is the design's sw[3].
    tab.eval("document.getElementById('sw3').dispatchEvent(new MouseEvent('click'))", false);
    until(&tab, "switch 3 on", |p| p["switches"] == 8);
    let shot = tab.screenshot();
    std::fs::write(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/live-nexys3-page.png"), &shot).unwrap();
}

#[test]
fn the_page_draws_a_nexys4_ddr_for_a_nexys4_ddr_project() {
    // tests/board_designs/repos/final_project: a Vivado project whose .xdc places its pins
    // (`CPU_RESETN`, `BTNC`, `SW`, `LED`, ...) on a Nexys4 DDR, its console and tilt games'
    // PicoBlazes, as a team commits it. The page draws that board with eight digits, sixteen
    // LEDs and switches, and the design sees its switches.
    let Some(chromium) = chromium() else { return };
    let clone = common::repo::clone_of("final_project");
    let live = Live::start_in(clone.path(), "board", &[".", "--speed", "max"]);
    let tab = open(chromium, &live.url);
    let d = board_with_digits(&tab);
    assert_eq!(d["title"], "NEXYS4 DDR", "{d}");
    assert_eq!((d["digits"].as_u64(), d["leds"].as_u64(), d["knobs"].as_u64()), (Some(8), Some(16), Some(16)), "{d}");
    let labels: Vec<&str> = d["labels"].as_array().unwrap().iter().filter_map(Value::as_str).collect();
    assert_eq!(labels, ["CPU RESET", "BTNU", "BTNL", "BTNC", "BTNR", "BTND"], "{d}");
    tab.eval("document.getElementById('sw12').dispatchEvent(new MouseEvent('click'))", false);
    until(&tab, "switch 12 on", |p| p["switches"] == 1 << 12);
    let shot = tab.screenshot();
    std::fs::write(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/live-nexys4ddr-page.png"), &shot).unwrap();
}
