//! The board's peripherals (spec board.md §7) end to end at the pins, on clean-room designs
//! under tests/board_designs: the USB-UART and the keyboard (console), the accelerometer and
//! the audio. Each run is checked at the lines between the FPGA and the peripheral (`--lines`,
//! decoded by tests/common/lines.rs from the spec's timing) and by what the design did with
//! what it got (its LEDs, display, UART echo).

use crate::common;

use std::path::{Path, PathBuf};

use common::lines::{self, PS2_CLK, PS2_DATA, RSRX, RSTX};
use common::{board_in, root, stderr};
use serde_json::Value;

fn design(name: &str) -> PathBuf {
    root().join("tests/board_designs").join(name)
}

/// `botsim board DESIGN ARGS --json` in `dir`: the summary.
fn run(dir: &Path, name: &str, args: &[&str]) -> Value {
    let d = design(name);
    let o = board_in(dir, &[&[d.to_str().unwrap(), "--json"], args].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// The LED values of a `--display` log, in order.
fn led_log(text: &str) -> Vec<u16> {
    text.lines()
        .filter_map(|l| l.split_once(" ms  leds    ").map(|(_, v)| u16::from_str_radix(v.trim(), 2).unwrap()))
        .collect()
}

/// The scan codes the console showed: each new code enters LEDs 7-0 (the old one moves to
/// 15-8 first).
fn codes_shown(leds: &[u16]) -> Vec<u8> {
    let mut out: Vec<u8> = Vec::new();
    let leds: Vec<u16> = std::iter::once(0).chain(leds.iter().copied()).collect();
    for w in leds.windows(2) {
        if w[1] >> 8 == w[0] >> 8 && w[1] & 0xFF != w[0] & 0xFF {
            out.push(w[1] as u8);
        }
    }
    out
}

const GREETING: &str = "botsim console\r\n";
/// The scan codes of tests/board_designs/console/typing.txt (A, then the up arrow; it sends
/// "hi!\r" to the UART first).
const CODES: [u8; 8] = [0x1C, 0xF0, 0x1C, 0xE0, 0x75, 0xE0, 0xF0, 0x75];

#[test]
fn the_console_greets_echoes_and_counts_the_keys_at_the_pins() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    let typed = design("console/typing.txt");
    let mut logs = Vec::new();
    for ff in [true, false] {
        let (uart, display, csv) = (p(&format!("{ff}.bin")), p(&format!("{ff}.txt")), p(&format!("{ff}.csv")));
        let mut args = vec!["--seconds", "0.016", "--stimulus", typed.to_str().unwrap()];
        args.extend(["--uart", uart.to_str().unwrap(), "--display", display.to_str().unwrap()]);
        args.extend(["--lines", csv.to_str().unwrap()]);
        if !ff {
            args.push("--no-fast-forward");
        }
        let v = run(dir.path(), "console", &args);
        // What the design sent: its greeting, then the text typed, echoed.
        let sent = std::fs::read(&uart).unwrap();
        assert_eq!(String::from_utf8_lossy(&sent), format!("{GREETING}hi!\r"), "{v}");
        assert_eq!((v["uart"]["baud"].as_u64(), v["uart"]["measured"].as_bool()), (Some(115_200), Some(true)), "{v}");
        assert_eq!(v["uart"]["framing_errors"], 0);
        // What it showed of the keys: every scan code, and two keys pressed.
        let log = std::fs::read_to_string(&display).unwrap();
        assert_eq!(codes_shown(&led_log(&log)), CODES, "{log}");
        assert_eq!(v["display"], "    0002", "{v}");
        // The lines as the spec has them: the UART both ways at 115200, the keyboard's frames.
        let rows = lines::read(&std::fs::read_to_string(&csv).unwrap());
        assert_eq!(lines::uart(&lines::changes(&rows, RSRX), 115_200), b"hi!\r");
        assert_eq!(lines::uart(&lines::changes(&rows, RSTX), 115_200), format!("{GREETING}hi!\r").as_bytes());
        let (clk, data) = (lines::changes(&rows, PS2_CLK), lines::changes(&rows, PS2_DATA));
        assert_eq!(lines::ps2(&clk, &data), CODES);
        // The first key's make code begins after its time.
        assert!(clk.iter().find(|c| !c.1).unwrap().0 > 5_000_000_000);
        logs.push((sent, log, std::fs::read_to_string(&csv).unwrap()));
    }
    // The fast-forward changes nothing, to the line.
    assert!(logs[0] == logs[1], "the fast-forward differs from every edge");
}

#[test]
fn a_keyboard_the_host_inhibits_sends_when_it_lets_go() {
    // Switch 0 holds PS2_CLK low until 12 ms (after the debounce); the key is pressed at 2 ms.
    let dir = tempfile::tempdir().unwrap();
    let (stim, csv, display) = (dir.path().join("s.txt"), dir.path().join("l.csv"), dir.path().join("d.txt"));
    std::fs::write(&stim, "0ms switches 0001\n2ms key Space 2ms\n12ms switches 0000\n").unwrap();
    let args = ["--seconds", "0.02", "--stimulus", stim.to_str().unwrap(), "--lines", csv.to_str().unwrap()];
    run(dir.path(), "console", &[&args[..], &["--display", display.to_str().unwrap()]].concat());
    let rows = lines::read(&std::fs::read_to_string(&csv).unwrap());
    let (clk, data) = (lines::changes(&rows, PS2_CLK), lines::changes(&rows, PS2_DATA));
    // The host's low clock, then the keyboard's frames after it.
    let released = clk.iter().find(|c| c.0 > 1_000_000_000 && c.1).unwrap().0;
    assert!(released > 12_000_000_000, "released at {released} ps");
    let after: Vec<(u64, bool)> = clk.iter().copied().filter(|c| c.0 > released).collect();
    let data_after: Vec<(u64, bool)> = data.iter().copied().filter(|c| c.0 > released).collect();
    assert_eq!(lines::ps2(&after, &data_after), [0x29, 0xF0, 0x29]);
    let shown = codes_shown(&led_log(&std::fs::read_to_string(&display).unwrap()));
    assert_eq!(shown, [0x29, 0xF0, 0x29]);
}

#[test]
fn a_uart_at_another_rate_reads_framing_errors_both_ways() {
    // The host at 9600 baud, the design at 115200: its greeting is not read as sent, and the
    // text sent to it comes back as something else.
    let dir = tempfile::tempdir().unwrap();
    let (stim, uart) = (dir.path().join("s.txt"), dir.path().join("u.bin"));
    std::fs::write(&stim, "3ms uart \"hi!\\r\"\n").unwrap();
    let args = ["--seconds", "0.02", "--uart-baud", "9600", "--stimulus", stim.to_str().unwrap()];
    let v = run(dir.path(), "console", &[&args[..], &["--uart", uart.to_str().unwrap()]].concat());
    assert_eq!((v["uart"]["baud"].as_u64(), v["uart"]["measured"].as_bool()), (Some(9600), Some(false)), "{v}");
    assert!(v["uart"]["framing_errors"].as_u64() > Some(0), "{v}");
    let sent = std::fs::read(&uart).unwrap();
    assert!(!String::from_utf8_lossy(&sent).contains("botsim") && !String::from_utf8_lossy(&sent).contains("hi!"));
    // The summary names the rate the line suggests.
    let d = design("console");
    let o = board_in(dir.path(), &[&[d.to_str().unwrap()], &args[..]].concat());
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("framing errors (the design's rate looks like 11"), "{out}");
}

/// A tilt in mg as the ADXL362 gives it at +-2 g: (x, y, z) 8-bit, and x, y, z 12-bit as
/// six bytes, low first, sign-extended (board.md §7).
fn accelerometer_bytes(mg: [i32; 3]) -> ([u8; 3], [u8; 6]) {
    let v = mg.map(|a| a.clamp(-2048, 2047) as u16 & 0xFFF);
    let high = |x: u16| if x & 0x800 != 0 { (x >> 8) as u8 | 0xF0 } else { (x >> 8) as u8 };
    (v.map(|x| (x >> 4) as u8), [v[0] as u8, high(v[0]), v[1] as u8, high(v[1]), v[2] as u8, high(v[2])])
}

#[test]
fn the_tilt_reaches_the_design_through_the_accelerometer() {
    // tests/board_designs/tilt reads x and y (8 bits) to the LEDs and x and z (12 bits) to the
    // display at each sample (100 Hz); the board tilts at 30 ms.
    let dir = tempfile::tempdir().unwrap();
    let (stim, csv, display) = (dir.path().join("s.txt"), dir.path().join("l.csv"), dir.path().join("d.txt"));
    std::fs::write(&stim, "30ms tilt -1 0 0\n").unwrap();
    let args = ["--seconds", "0.05", "--tilt", "0.5,-0.25,0.866", "--stimulus", stim.to_str().unwrap()];
    let v = run(
        dir.path(),
        "tilt",
        &[&args[..], &["--lines", csv.to_str().unwrap(), "--display", display.to_str().unwrap()]].concat(),
    );
    let (first, second) = (accelerometer_bytes([500, -250, 866]), accelerometer_bytes([-1000, 0, 0]));
    let log = std::fs::read_to_string(&display).unwrap();
    let leds = led_log(&log);
    // x to LEDs 15-8, then y to 7-0: 1F F0, then C1 00.
    assert_eq!([first.0[0], first.0[1], second.0[0], second.0[1]], [0x1F, 0xF0, 0xC1, 0x00]);
    assert_eq!(leds, [0x1F00, 0x1FF0, 0xC1F0, 0xC100], "{log}");
    assert!(log.contains("display 036201F4"), "{log}");
    assert_eq!(v["display"], "0000FC18");
    // The bus, decoded from the spec: the write that starts measuring, then reads whose data
    // are the registers at the tilt of the time (0 before the first sample).
    let rows = lines::read(&std::fs::read_to_string(&csv).unwrap());
    let spi = lines::spi(&rows);
    assert_eq!(spi[0].1, [0x0A, 0x2D, 0x02]);
    let (mut short, mut burst) = (0, 0);
    let mut seen_second = false;
    for (t, mosi, miso) in &spi[1..] {
        match mosi[..2] {
            [0x0B, 0x0B] => assert_eq!(miso.len(), 3),
            [0x0B, 0x08] => {
                let got = [miso[2], miso[3]];
                seen_second |= got == [second.0[0], second.0[1]];
                let want = if seen_second { [second.0[0], second.0[1]] } else { [first.0[0], first.0[1]] };
                assert_eq!(got, want, "the 8-bit x, y read at {t} ps");
                short += 1;
            }
            [0x0B, 0x0E] => {
                let want = if seen_second { second.1 } else { first.1 };
                assert_eq!(miso[2..], want, "the 12-bit x, y, z read at {t} ps");
                burst += 1;
            }
            _ => panic!("an unexpected transaction at {t} ps: {mosi:02X?}"),
        }
    }
    assert!(short >= 4 && burst == short && seen_second, "{short} reads, {burst} bursts");
}

/// The 16-bit samples of a mono WAV file, and its rate.
fn wav_samples(bytes: &[u8]) -> (u32, Vec<i16>) {
    assert_eq!((&bytes[..4], &bytes[8..16]), (&b"RIFF"[..], &b"WAVEfmt "[..]));
    let u16_at = |i: usize| u16::from_le_bytes([bytes[i], bytes[i + 1]]);
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap());
    assert_eq!((u16_at(20), u16_at(22), u16_at(34)), (1, 1, 16), "PCM, mono, 16 bits");
    assert_eq!(&bytes[36..40], b"data");
    let data = &bytes[44..44 + u32_at(40) as usize];
    (u32_at(24), data.chunks(2).map(|c| i16::from_le_bytes([c[0], c[1]])).collect())
}

/// The strongest frequency of `x` (1 Hz steps from `lo` to `hi`), by each one's DFT power.
fn strongest(x: &[i16], rate: u32, lo: u32, hi: u32) -> u32 {
    (lo..=hi)
        .max_by(|&a, &b| {
            let power = |f: u32| {
                let w = 2.0 * std::f64::consts::PI * f as f64 / rate as f64;
                let (re, im) = x.iter().enumerate().fold((0.0, 0.0), |(re, im), (n, &v)| {
                    (re + v as f64 * (w * n as f64).cos(), im + v as f64 * (w * n as f64).sin())
                });
                re * re + im * im
            };
            power(a).total_cmp(&power(b))
        })
        .unwrap()
}

#[test]
fn the_tone_player_sounds_the_note_the_switches_choose() {
    // tests/board_designs/tones: A4 (switches 2-0 = 5), C5 (7) from 100 ms, the amplifier off
    // (switch 15) from 200 ms.
    let dir = tempfile::tempdir().unwrap();
    let (stim, wav) = (dir.path().join("s.txt"), dir.path().join("t.wav"));
    std::fs::write(&stim, "0 switches 8005\n100ms switches 8007\n200ms switches 0007\n").unwrap();
    run(
        dir.path(),
        "tones",
        &["--seconds", "0.3", "--stimulus", stim.to_str().unwrap(), "--audio", wav.to_str().unwrap()],
    );
    let (rate, x) = wav_samples(&std::fs::read(&wav).unwrap());
    assert_eq!((rate, x.len()), (48_000, 14_400));
    let ms = |m: usize| m * 48;
    assert_eq!(strongest(&x[ms(20)..ms(95)], rate, 200, 1000), 440);
    assert_eq!(strongest(&x[ms(120)..ms(195)], rate, 200, 1000), 523);
    // Loud while on, silent (the coupling's decay aside) once off.
    let peak = |s: &[i16]| s.iter().map(|v| v.unsigned_abs()).max().unwrap();
    assert!(peak(&x[ms(20)..ms(95)]) > 8000, "{}", peak(&x[ms(20)..ms(95)]));
    assert!(peak(&x[ms(250)..]) < 800, "{}", peak(&x[ms(250)..]));
}

#[test]
fn peripherals_the_design_lacks_are_one_line_each() {
    let dir = tempfile::tempdir().unwrap();
    let stim = dir.path().join("s.txt");
    let cases: [(&str, &[&str], &str, &str); 4] = [
        ("console", &["--audio", "a.wav"], "", "--audio writes the board's sound, and the design has no ampPWM"),
        (
            "console",
            &["--tilt", "0,0,1"],
            "",
            "the board's tilt is measured by its accelerometer, and the design has no",
        ),
        ("game", &[], "1ms uart \"x\"\n", "the stimulus sends text to the USB-UART, and the design has no RsRx"),
        (
            "game",
            &["--uart", "u.bin"],
            "",
            "--uart writes what the design sends on the USB-UART, and the design has no RsTx",
        ),
    ];
    for (name, extra, stimulus, want) in cases {
        std::fs::write(&stim, stimulus).unwrap();
        let d = if name == "game" { root().join(common::game::GAME) } else { design(name) };
        let o = board_in(dir.path(), &[&[d.to_str().unwrap(), "--stimulus", stim.to_str().unwrap()], extra].concat());
        let e = stderr(&o);
        assert!(!o.status.success() && e.lines().last().unwrap_or("").contains(want), "{name} {extra:?}: {e}");
    }
}

/// A Rojobot design whose team program steers the bot by the board's tilt
/// (tests/board_designs/tilt_bot, with the course's nexys4_bot_if and the SPI master of
/// tests/board_designs/tilt): tilted forward it drives forward, tilted right it turns, flat
/// it stops; each sample's MotCtl and movement say so.
#[test]
fn the_board_tilted_steers_the_bot() {
    let dir = tempfile::tempdir().unwrap();
    let (stim, trace) = (dir.path().join("s.txt"), dir.path().join("t.json"));
    std::fs::write(&stim, "0 tilt 0 0.5 0.87\n1s tilt 0.5 0 0.87\n1.5s tilt 0 0 1\n").unwrap();
    let sources = [design("tilt_bot"), design("tilt/spi_master.v"), root().join("examples/common/nexys4_bot_if.v")];
    let mut args: Vec<&str> = sources.iter().map(|p| p.to_str().unwrap()).collect();
    args.extend([
        "--seconds",
        "2",
        "--stimulus",
        stim.to_str().unwrap(),
        "--trace-json",
        trace.to_str().unwrap(),
        "-q",
    ]);
    let o = board_in(dir.path(), &args);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows: Vec<Value> =
        std::fs::read_to_string(&trace).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    let mut phases: Vec<(u64, String)> = Vec::new();
    for r in &rows {
        let p = (r["next_motctl"].as_u64().unwrap(), r["movement"].as_str().unwrap().to_string());
        if phases.last() != Some(&p) {
            phases.push(p);
        }
    }
    // Each MotCtl written at a sample moves the bot from the next: the movement follows.
    let motctl: Vec<u64> = phases.iter().map(|p| p.0).collect();
    let mut distinct = motctl.clone();
    distinct.dedup();
    assert_eq!(distinct, [0x00, 0x33, 0x32, 0x00], "{phases:?}");
    let moves: Vec<&str> = rows.iter().map(|r| r["movement"].as_str().unwrap()).collect();
    let mut m = moves.clone();
    m.dedup();
    assert_eq!(m, ["stopped", "forward", "fast-right", "stopped"], "{phases:?}");
    let x = |i: usize| rows[i]["loc_x"].as_u64().unwrap();
    let turned = moves.iter().position(|m| *m == "fast-right").unwrap();
    assert!(x(turned) > x(0), "the bot went forward (east): x {} -> {}", x(0), x(turned));
}

/// `text` with every whole identifier `from` written `to` (but an instance's port name,
/// `.from(`).
fn rename_word(text: &str, from: &str, to: &str) -> String {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '$' || c == '.';
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find(from) {
        let before = rest[..at].chars().next_back();
        let after = rest[at + from.len()..].chars().next();
        out.push_str(&rest[..at]);
        out.push_str(if before.is_some_and(ident) || after.is_some_and(ident) { from } else { to });
        rest = &rest[at + from.len()..];
    }
    out.push_str(rest);
    out
}

/// The package pin of the Nexys4 that is `f`.
fn nexys4_pin(f: botsim_core::frontend::constraints::Function) -> &'static str {
    use botsim_core::frontend::constraints::Board;
    Board::Nexys4.pins().find(|(_, g)| *g == f).map(|(p, _)| p).unwrap_or_else(|| panic!("{f:?}"))
}

#[test]
fn the_console_with_every_pin_renamed_and_placed_by_its_xdc_runs_as_the_original() {
    // The package pins, not the names, say what a port is: every port of the console's top
    // is renamed (`RsRx` becomes `pin_9`) and an .xdc places each bit where the original's
    // name puts it. Greeting, echo, keys and display are the original's, to the line.
    use botsim_core::frontend::constraints::Function as F;
    use botsim_core::frontend::pins::{role, Role};
    let dir = tempfile::tempdir().unwrap();
    let renamed = dir.path().join("renamed");
    std::fs::create_dir(&renamed).unwrap();
    for e in std::fs::read_dir(design("console")).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), renamed.join(e.file_name())).unwrap();
    }
    let top_file = renamed.join("nexys4fpga.v");
    let mut top = std::fs::read_to_string(&top_file).unwrap();
    let module = botsim_core::frontend::scan::scan(&top).into_iter().find(|m| m.name == "nexys4fpga").unwrap();
    let mut xdc = String::new();
    for (k, port) in module.ports.iter().enumerate() {
        let r = role(&port.name).unwrap_or_else(|| panic!("{}", port.name));
        let new = format!("pin_{k}");
        let scalar = match r {
            Role::Clock => Some(F::Clock),
            Role::Reset { active_low } => Some(F::Reset { active_low }),
            Role::Button(n) => Some(F::Button(n)),
            Role::DecimalPoint => Some(F::DecimalPoint),
            Role::UartRx => Some(F::UartRx),
            Role::UartTx => Some(F::UartTx),
            Role::Ps2Clock => Some(F::Ps2Clock),
            Role::Ps2Data => Some(F::Ps2Data),
            _ => None,
        };
        match scalar {
            Some(f) => xdc.push_str(&format!("set_property PACKAGE_PIN {} [get_ports {new}]\n", nexys4_pin(f))),
            None => {
                for bit in 0..port.width {
                    let f = match r {
                        Role::Switches => F::Switch(bit as u8),
                        Role::Leds => F::Led(bit as u8),
                        Role::Anodes => F::Anode(bit as u8),
                        Role::Segments => F::Segment(bit as u8),
                        other => panic!("{other:?}"),
                    };
                    xdc.push_str(&format!(
                        "set_property -dict {{ PACKAGE_PIN {} IOSTANDARD LVCMOS33 }} [get_ports {{ {new}[{bit}] }}]\n",
                        nexys4_pin(f)
                    ));
                }
            }
        }
        top = rename_word(&top, &port.name, &new);
    }
    assert!(!top.contains("RsRx") && top.contains("pin_0"), "{top}");
    std::fs::write(&top_file, top).unwrap();
    std::fs::write(renamed.join("nexys4.xdc"), xdc).unwrap();
    let typed = design("console/typing.txt");
    let outputs = |source: &Path, tag: &str| {
        let (uart, display) = (dir.path().join(format!("{tag}.bin")), dir.path().join(format!("{tag}.txt")));
        let args = [
            source.to_str().unwrap(),
            "--seconds",
            "0.016",
            "--stimulus",
            typed.to_str().unwrap(),
            "--uart",
            uart.to_str().unwrap(),
            "--display",
            display.to_str().unwrap(),
        ];
        let o = board_in(dir.path(), &args);
        assert!(o.status.success(), "{}", stderr(&o));
        (std::fs::read(&uart).unwrap(), std::fs::read_to_string(&display).unwrap(), stderr(&o))
    };
    let (sent, shown, said) = outputs(&renamed, "renamed");
    assert!(said.contains("nexys4.xdc places them on the Nexys4 (11 of its ports)"), "{said}");
    assert!(!said.contains("ports with no board pin"), "{said}");
    assert_eq!(String::from_utf8_lossy(&sent), format!("{GREETING}hi!\r"));
    let (sent0, shown0, _) = outputs(&design("console"), "original");
    assert_eq!((sent, shown), (sent0, shown0));
}

#[test]
fn a_board_pin_declared_with_the_wrong_direction_runs_as_the_board_would_with_one_warning() {
    // `output aclMISO` (the accelerometer's data into the FPGA): Vivado builds it with a
    // warning; the design then reads its own undriven output, 0, as the board would give
    // it. One warning at the port's line, with and without the controller stubbed.
    let dir = tempfile::tempdir().unwrap();
    let tilt = dir.path().join("tilt");
    std::fs::create_dir(&tilt).unwrap();
    for e in std::fs::read_dir(design("tilt")).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), tilt.join(e.file_name())).unwrap();
    }
    let top = tilt.join("nexys4fpga.v");
    let text = std::fs::read_to_string(&top).unwrap();
    let wrong = text.replacen("    input  wire        aclMISO,", "    output wire        aclMISO,", 1);
    assert_ne!(wrong, text);
    std::fs::write(&top, wrong).unwrap();
    for stub in [false, true] {
        let mut args = vec!["tilt", "--seconds", "0.01", "--tilt", "0.5,0,0.8"];
        if stub {
            args.extend(["--stub", "spi_master"]);
        }
        let o = board_in(dir.path(), &args);
        let said = stderr(&o);
        assert!(o.status.success(), "{said}");
        let warnings: Vec<&str> = said.lines().filter(|l| l.contains("aclMISO") && l.starts_with("warning:")).collect();
        assert_eq!(warnings.len(), 1, "{said}");
        assert!(
            warnings[0].starts_with("warning: tilt/nexys4fpga.v:16:24: port `aclMISO` is the board's accelerometer pin, an input, but `nexys4fpga` declares it an output")
                && warnings[0].contains("reads `aclMISO` as what it drives itself"),
            "{}",
            warnings[0]
        );
    }
}
