//! `botsim board --check`: the run's board beside the all-RTL board (`--cpu rtl --bot rtl`,
//! every edge under Verilator) over the same time and inputs, every record compared byte for
//! byte: the bot's samples (each bot's), the display, the display's and LEDs' pins, the
//! peripherals' lines, what the design sent on the UART, every 8th VGA frame (or the
//! `--frame-every` asked for), what the design printed. It says the first record that
//! differs (which, when, both values), or that all are equal.
//!
//! The run the user asked for goes first, as without `--check`, with its own outputs; the
//! two compared runs write their records into a temporary folder, removed afterwards. The
//! run's board (by default the ISS CPUs, the bot's model and the fast-forward) costs little
//! beside the all-RTL board, so running it twice does too.

use std::path::Path;

use botsim::board::build::{BotKind, CpuModel};
use botsim_core::frontend::pins::Role;

use super::prepare::{self, Prepared};
use super::{report, session, Args, BotArg, CpuArg};

/// Every `FRAME_EVERY`-th VGA frame is compared when the run saves none.
const FRAME_EVERY: u64 = 8;

/// What the check found.
#[derive(Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every record equal: (record, its size in rows, frames or bytes) for each.
    Equal(Vec<(String, String)>),
    /// The first record that differs.
    Differs(Difference),
}

/// The first difference between the two boards' records.
#[derive(Debug, PartialEq, Eq)]
pub struct Difference {
    /// The record, as its option names it (`--pins`, `--trace-csv (the bot at SYS.hero)`).
    pub record: String,
    /// Where in it: row 37, at 12.5 ms; frame 3, pixel (10, 20).
    pub at: String,
    /// What each board recorded there.
    pub this: String,
    pub rtl: String,
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} differs {}: this board `{}`, the all-RTL board `{}`", self.record, self.at, self.this, self.rtl)
    }
}

/// Check the run `a` (already made, `p` its preparation) against the all-RTL board.
pub fn run(a: &Args, p: &Prepared) -> Result<(), String> {
    if p.cpu == CpuModel::Rtl && p.main_bot == BotKind::Rtl && !p.lockstep {
        a.say("check: this run is the all-RTL board (--cpu rtl --bot rtl): nothing to compare it with".into());
        return Ok(());
    }
    let dir = tempfile::Builder::new()
        .prefix("botsim-check-")
        .tempdir()
        .map_err(|e| format!("error: cannot create a temporary folder for the check: {e}"))?;
    let has = |r: Role| p.plan.pins.iter().any(|(_, x)| *x == r);
    let records = Records {
        bot: p.plan.bot_path.is_some(),
        uart: has(Role::UartTx),
        vga: has(Role::Hsync) && has(Role::Vsync),
        frame_every: if a.frames.is_some() { a.frame_every } else { FRAME_EVERY },
    };
    let span = match (a.seconds, a.samples) {
        (Some(s), _) => format!("{s} s"),
        (None, Some(n)) => format!("{n} samples"),
        (None, None) => "1 s".into(),
    };
    a.say(format!("check: the same run on the all-RTL board (--cpu rtl --bot rtl) over {span}, every record compared"));
    let this = records.args(a, &dir.path().join("this"), None)?;
    let rtl = records.args(a, &dir.path().join("rtl"), Some((CpuArg::Rtl, BotArg::Rtl)))?;
    for args in [&this, &rtl] {
        let p = prepare::prepare(args)?;
        let o = session::simulate(args, &p)?;
        if o.stopped_by == "interrupt" {
            return Err("check: interrupted before the boards were compared".into());
        }
        report::report(args, &p, o)?;
    }
    match compare(&dir.path().join("this"), &dir.path().join("rtl"))? {
        Verdict::Equal(sizes) => {
            let sizes: Vec<String> = sizes.iter().map(|(r, n)| format!("{r} ({n})")).collect();
            a.say(format!("check: equal to the all-RTL board, every record: {}", sizes.join(", ")));
            Ok(())
        }
        Verdict::Differs(d) => Err(format!(
            "check: {d} (the same results are botsim's promise: please report it with the command and the repository)"
        )),
    }
}

/// The records a design has, and how they are asked for.
struct Records {
    bot: bool,
    uart: bool,
    vga: bool,
    frame_every: u64,
}

impl Records {
    /// `a` as a run that writes every record into `dir` and nothing else, on the board `on`
    /// (`None`: the run's own).
    fn args(&self, a: &Args, dir: &Path, on: Option<(CpuArg, BotArg)>) -> Result<Args, String> {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: error: cannot create the folder: {e}", dir.display()))?;
        let file = |f: &str| Some(dir.join(f));
        let mut r = a.clone();
        r.check = false;
        r.quiet = true;
        r.json = false;
        (r.vcd, r.cpu_trace, r.png, r.trace_json, r.audio) = (None, None, None, None, None);
        (r.trace_from, r.trace_to, r.vcd_max, r.cpu_trace_from, r.cpu_trace_to) = (None, None, None, None, None);
        r.trace_csv = if self.bot { file(TRACE) } else { None };
        r.display = file(DISPLAY);
        r.pins = file(PINS);
        r.lines = file(LINES);
        r.design_log = file(LOG);
        r.uart = if self.uart { file(UART) } else { None };
        r.frames = if self.vga { file(FRAMES) } else { None };
        r.frame_every = self.frame_every;
        if let Some((cpu, bot)) = on {
            // A design without a bot takes no --bot.
            (r.cpu, r.bot, r.no_fast_forward) = (Some(cpu), self.bot.then_some(bot), false);
        }
        Ok(r)
    }
}

// The records' files in each run's folder.
const TRACE: &str = "trace.csv";
const DISPLAY: &str = "display.txt";
const PINS: &str = "pins.csv";
const LINES: &str = "lines.csv";
const LOG: &str = "design.log";
const UART: &str = "uart.bin";
const FRAMES: &str = "frames";

/// A record's option for a file of the run's folder (another bot's trace is
/// `trace.<path>.csv`).
fn record_of(file: &str) -> String {
    match file {
        TRACE => "--trace-csv".into(),
        DISPLAY => "--display".into(),
        PINS => "--pins".into(),
        LINES => "--lines".into(),
        LOG => "--design-log".into(),
        UART => "--uart".into(),
        f => match f.strip_prefix("trace.").and_then(|f| f.strip_suffix(".csv")) {
            Some(bot) => format!("--trace-csv (the bot at {bot})"),
            None => f.to_string(),
        },
    }
}

/// Compare the records of two runs' folders: the same files, each byte for byte.
pub fn compare(this: &Path, rtl: &Path) -> Result<Verdict, String> {
    let mut sizes = Vec::new();
    let (mine, theirs) = (listing(this)?, listing(rtl)?);
    for name in mine.iter().chain(&theirs) {
        if !(mine.contains(name) && theirs.contains(name)) {
            let (t, r) = if mine.contains(name) { ("written", "none") } else { ("none", "written") };
            return Ok(Verdict::Differs(Difference {
                record: record_of(name),
                at: "in whether it was written".into(),
                this: t.into(),
                rtl: r.into(),
            }));
        }
    }
    for name in &mine {
        if name == FRAMES {
            let frames = (listing(&this.join(FRAMES))?, listing(&rtl.join(FRAMES))?);
            if frames.0 != frames.1 {
                let n = |v: &Vec<String>| count(v.len(), "frame");
                return Ok(Verdict::Differs(Difference {
                    record: "--frames".into(),
                    at: "in the frames written".into(),
                    this: n(&frames.0),
                    rtl: n(&frames.1),
                }));
            }
            for f in &frames.0 {
                let (a, b) = (read(&this.join(FRAMES).join(f))?, read(&rtl.join(FRAMES).join(f))?);
                if a != b {
                    return Ok(Verdict::Differs(frame_difference(f, &a, &b)));
                }
            }
            sizes.push(("--frames".into(), count(frames.0.len(), "frame")));
            continue;
        }
        let (a, b) = (read(&this.join(name))?, read(&rtl.join(name))?);
        let record = record_of(name);
        if name == UART {
            if let Some(i) = (0..a.len().max(b.len())).find(|&i| a.get(i) != b.get(i)) {
                let byte = |v: &[u8]| v.get(i).map_or("(the end)".into(), |x| format!("{x:02X}"));
                let at = format!("at byte {i}");
                return Ok(Verdict::Differs(Difference { record, at, this: byte(&a), rtl: byte(&b) }));
            }
            sizes.push((record, count(a.len(), "byte")));
            continue;
        }
        let (a, b) = (String::from_utf8_lossy(&a), String::from_utf8_lossy(&b));
        if let Some(d) = text_difference(&record, name, &a, &b) {
            return Ok(Verdict::Differs(d));
        }
        sizes.push((record, count(a.lines().count(), "row")));
    }
    Ok(Verdict::Equal(sizes))
}

/// The first line at which two text records differ, with its time where the record has one.
fn text_difference(record: &str, name: &str, a: &str, b: &str) -> Option<Difference> {
    let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    let i = (0..la.len().max(lb.len())).find(|&i| la.get(i) != lb.get(i))?;
    let line = |v: &[&str]| v.get(i).map_or("(the end)".to_string(), |l| l.to_string());
    let first = la.get(i).or(lb.get(i)).copied().unwrap_or_default();
    let when = match name {
        PINS | LINES => first.split(',').next().and_then(|t| t.parse::<u64>().ok()).map(time),
        DISPLAY => first.split("display").next().map(|t| t.trim().to_string()).filter(|t| !t.is_empty()),
        _ if name.starts_with("trace.") => {
            first.split(',').nth(1).and_then(|c| c.parse::<u64>().ok()).map(|c| time(c * botsim::PS_PER_CYCLE))
        }
        _ => None,
    };
    let at = match when {
        Some(t) => format!("at row {} ({t})", i + 1),
        None => format!("at line {}", i + 1),
    };
    Some(Difference { record: record.into(), at, this: line(&la), rtl: line(&lb) })
}

/// `1 row`, `2 rows`.
fn count(n: usize, what: &str) -> String {
    format!("{n} {what}{}", if n == 1 { "" } else { "s" })
}

/// A time in picoseconds as the run's account says it.
fn time(ps: u64) -> String {
    format!("{:.6} ms", ps as f64 / 1e9)
}

/// Where two PNG frames of the same name differ: the first pixel, row by row.
fn frame_difference(name: &str, a: &[u8], b: &[u8]) -> Difference {
    let pixels = |bytes: &[u8]| -> Option<(u32, Vec<u8>)> {
        let mut r = png::Decoder::new(std::io::Cursor::new(bytes)).read_info().ok()?;
        let mut buf = vec![0; r.output_buffer_size()?];
        let info = r.next_frame(&mut buf).ok()?;
        let bpp = info.line_size / info.width as usize;
        buf.truncate(info.buffer_size());
        Some((info.width, buf.chunks(bpp).flat_map(|p| p[..3.min(bpp)].to_vec()).collect()))
    };
    let record = "--frames".to_string();
    match (pixels(a), pixels(b)) {
        (Some((w, pa)), Some((_, pb))) => {
            let k = (0..pa.len().max(pb.len()) / 3).find(|&k| pa.get(3 * k..3 * k + 3) != pb.get(3 * k..3 * k + 3));
            let k = k.unwrap_or(0);
            let rgb = |p: &[u8]| {
                p.get(3 * k..3 * k + 3).map_or("(none)".into(), |c| format!("#{:02X}{:02X}{:02X}", c[0], c[1], c[2]))
            };
            Difference {
                record,
                at: format!("in {name}, at pixel ({}, {})", k as u32 % w, k as u32 / w),
                this: rgb(&pa),
                rtl: rgb(&pb),
            }
        }
        _ => Difference {
            record,
            at: format!("in {name}"),
            this: format!("{} bytes", a.len()),
            rtl: format!("{} bytes", b.len()),
        },
    }
}

fn listing(dir: &Path) -> Result<Vec<String>, String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: error: cannot read the folder: {e}", dir.display()))?
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .collect();
    v.sort();
    Ok(v)
}

fn read(f: &Path) -> Result<Vec<u8>, String> {
    std::fs::read(f).map_err(|e| format!("{}: error: cannot read: {e}", f.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn folders(files: &[(&str, &str, &str)]) -> (tempfile::TempDir, PathBuf, PathBuf) {
        let t = tempfile::tempdir().unwrap();
        let (a, b) = (t.path().join("this"), t.path().join("rtl"));
        for (name, x, y) in files {
            for (d, text) in [(&a, x), (&b, y)] {
                std::fs::create_dir_all(d).unwrap();
                if !text.is_empty() {
                    std::fs::write(d.join(name), text).unwrap();
                }
            }
        }
        (t, a, b)
    }

    #[test]
    fn equal_records_are_equal_with_their_sizes() {
        let (_t, a, b) = folders(&[(PINS, "time_ps,an\n10000,FE\n", "time_ps,an\n10000,FE\n"), (UART, "hi", "hi")]);
        let v = compare(&a, &b).unwrap();
        assert_eq!(v, Verdict::Equal(vec![("--pins".into(), "2 rows".into()), ("--uart".into(), "2 bytes".into())]));
    }

    #[test]
    fn the_first_difference_says_its_record_row_time_and_both_values() {
        let (_t, a, b) = folders(&[
            (PINS, "time_ps,an\n10000,FE\n2500000000,FD\n", "time_ps,an\n10000,FE\n2500000000,FB\n"),
            ("trace.SYS.hero.csv", "sample,cycle\n0,100\n1,300\n", "sample,cycle\n0,100\n1,301\n"),
        ]);
        let Verdict::Differs(d) = compare(&a, &b).unwrap() else { panic!() };
        assert_eq!(
            d.to_string(),
            "--pins differs at row 3 (2.500000 ms): this board `2500000000,FD`, the all-RTL board `2500000000,FB`"
        );
        std::fs::remove_file(a.join(PINS)).unwrap();
        std::fs::remove_file(b.join(PINS)).unwrap();
        let Verdict::Differs(d) = compare(&a, &b).unwrap() else { panic!() };
        assert_eq!(d.record, "--trace-csv (the bot at SYS.hero)");
        assert_eq!(d.at, "at row 3 (0.003000 ms)");
        // A record one board lacks, a shorter one, and bytes of the UART.
        let (_t, a, b) = folders(&[(DISPLAY, "  1.000 ms  display 8.\n", "")]);
        let Verdict::Differs(d) = compare(&a, &b).unwrap() else { panic!() };
        assert_eq!((d.this.as_str(), d.rtl.as_str()), ("written", "none"));
        let (_t, a, b) =
            folders(&[(DISPLAY, "  1.000 ms  display 8.\n", "  1.000 ms  display 8.\n  2.000 ms  display 0.\n")]);
        let Verdict::Differs(d) = compare(&a, &b).unwrap() else { panic!() };
        assert_eq!((d.at.as_str(), d.this.as_str()), ("at row 2 (2.000 ms)", "(the end)"));
        let (_t, a, b) = folders(&[(UART, "abc", "abd")]);
        let Verdict::Differs(d) = compare(&a, &b).unwrap() else { panic!() };
        assert_eq!((d.at.as_str(), d.this.as_str(), d.rtl.as_str()), ("at byte 2", "63", "64"));
    }

    #[test]
    fn frames_differ_at_their_first_pixel() {
        let png = |px: [u8; 3]| {
            let mut out = Vec::new();
            let mut e = png::Encoder::new(&mut out, 4, 2);
            e.set_color(png::ColorType::Rgb);
            let mut w = e.write_header().unwrap();
            let mut data = vec![0u8; 4 * 2 * 3];
            data[3 * 6..3 * 7].copy_from_slice(&px);
            w.write_image_data(&data).unwrap();
            drop(w);
            out
        };
        let d = frame_difference("frame_00008.png", &png([0, 0, 0]), &png([0xFF, 0, 0x10]));
        assert_eq!(
            d.to_string(),
            "--frames differs in frame_00008.png, at pixel (2, 1): this board `#000000`, the all-RTL board `#FF0010`"
        );
    }
}
