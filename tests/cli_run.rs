//! `botsim run` as a user runs it: the contract of the system issue.

mod common;

use std::path::Path;

use common::{botsim, stderr};

fn rows(csv: &str) -> Vec<Vec<u64>> {
    csv.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect()
}

#[test]
fn csv_trace_has_the_contract_columns_and_one_row_per_pulse() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("m.txt"), "# drive\nforward 16\n\n0x00 2   # stop\n").unwrap();
    let o = botsim(&["run", "--timing", "fast", "--motors", "m.txt", "--trace-csv", "t.csv"], d.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(d.path().join("t.csv")).unwrap();
    assert_eq!(csv.lines().next(), Some("sample,cycle,loc_x,loc_y,bot_info,sensors,lm_dist,rm_dist"));
    let r = rows(&csv);
    assert_eq!(r.len(), 19, "sample 0 and iterations 1-18");
    assert_eq!(r[0][..1], [0]);
    assert_eq!(r[0][2..], [64, 64, 2, 0, 0, 0]);
    // Iterations 1-16 see forward: counters 1..15, the move shows in sample 16.
    assert_eq!(r[15][2..], [64, 64, 0x42, 0, 15, 15]);
    assert_eq!(r[16][2..], [65, 64, 0x42, 0, 1, 1]);
    // Iteration 17 sees 00: stopped, counters held.
    assert_eq!(r[17][2..], [65, 64, 0x02, 0, 1, 1]);
    assert!(r.windows(2).all(|w| w[1][1] > w[0][1]), "cycles increase");
    assert!(String::from_utf8_lossy(&o.stdout).contains("final        (65, 64) facing E stopped"));
}

#[test]
fn samples_overrides_the_script_and_holds_the_last_value() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("m.txt"), "33 1\n").unwrap();
    let o = botsim(
        &["run", "--timing", "fast", "--threshold", "1", "--motors", "m.txt", "--samples", "5", "--trace-csv", "t.csv"],
        d.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let r = rows(&std::fs::read_to_string(d.path().join("t.csv")).unwrap());
    let x: Vec<u64> = r.iter().map(|r| r[2]).collect();
    assert_eq!(x, [64, 64, 65, 66, 67, 68]);
}

#[test]
fn compat_threshold_and_program_options() {
    let d = tempfile::tempdir().unwrap();
    let root = env!("CARGO_MANIFEST_DIR");
    // Our firmware assembled to .hex, run with the course's part-2 threshold given to the
    // assembler: a .psm program takes --threshold.
    let psm = format!("{root}/rtl/bot_pgm.psm");
    std::fs::write(d.path().join("m.txt"), "forward 5\n").unwrap();
    let o = botsim(
        &[
            "run",
            "--program",
            &psm,
            "--threshold",
            "4",
            "--timing",
            "fast",
            "--compat",
            "botsim20",
            "--motors",
            "m.txt",
            "--trace-csv",
            "t.csv",
        ],
        d.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let r = rows(&std::fs::read_to_string(d.path().join("t.csv")).unwrap());
    assert_eq!((r[4][6], r[5][2]), (4, 65), "threshold 4: counters reach 4, the move shows in sample 5");
    let o = botsim(&["run", "--compat", "2015"], d.path());
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn vcd_opens_with_a_vcd_reader_and_has_the_top_ports() {
    let d = tempfile::tempdir().unwrap();
    let o = botsim(&["run", "--timing", "fast", "--samples", "2", "--vcd", "w.vcd"], d.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let f = std::fs::File::open(d.path().join("w.vcd")).unwrap();
    let mut parser = vcd::Parser::new(std::io::BufReader::new(f));
    let header = parser.parse_header().unwrap();
    for port in ["MotCtl_in", "LocX_reg", "LocY_reg", "Sensors_reg", "BotInfo_reg", "upd_sysregs", "clk", "reset"] {
        assert!(header.find_var(&["TOP", port]).is_some(), "TOP.{port}");
    }
    assert!(header.find_var(&["TOP", "bot", "BOTSIMCPU", "address"]).is_some(), "the RTL hierarchy");
    let upd = header.find_var(&["TOP", "upd_sysregs"]).unwrap().code;
    let clk = header.find_var(&["TOP", "clk"]).unwrap().code;
    let (mut rises, mut last) = (0, false);
    let (mut stamps, mut clk_changes, mut clk_last) = (0u64, 0u64, None);
    for cmd in parser {
        match cmd.unwrap() {
            vcd::Command::Timestamp(_) => stamps += 1,
            vcd::Command::ChangeScalar(c, v) if c == upd => {
                let now = v == vcd::Value::V1;
                rises += (now && !last) as u32;
                last = now;
            }
            vcd::Command::ChangeScalar(c, v) if c == clk => {
                assert_ne!(clk_last, Some(v), "the clock must alternate");
                clk_last = Some(v);
                clk_changes += 1;
            }
            _ => {}
        }
    }
    assert_eq!(rises, 3, "samples 0, 1, 2");
    // Both clock edges are in the file: the clock changes at every time stamp.
    assert!(clk_changes >= stamps, "{clk_changes} clock changes in {stamps} time stamps");
    assert!(!d.path().join(".w.vcd.part").exists());
}

#[test]
fn bad_inputs_are_one_line_with_a_location() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("bad.txt"), "forward 3\nsideways 2\n").unwrap();
    let o = botsim(&["run", "--motors", "bad.txt"], d.path());
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.starts_with("bad.txt:2:1: error: 'sideways' is not a MotCtl value"), "{e}");
    assert_eq!(e.lines().count(), 1);
    std::fs::write(d.path().join("bad2.txt"), "33 x\n").unwrap();
    assert_eq!(
        stderr(&botsim(&["run", "--motors", "bad2.txt"], d.path())),
        "bad2.txt:1:4: error: 'x' is not a count (a decimal number of iterations)\n"
    );
    std::fs::write(d.path().join("bad3.txt"), "33\n").unwrap();
    assert!(stderr(&botsim(&["run", "--motors", "bad3.txt"], d.path()))
        .starts_with("bad3.txt:1:1: error: expected '<MOTCTL> <COUNT>'"));
    let o = botsim(&["run", "--map", "nope.coe"], d.path());
    assert_eq!(stderr(&o), "nope.coe: error: cannot read file: no such file or directory\n");
    let o = botsim(&["run", "--timing", "fast", "--samples", "1", "--trace-csv", "no/dir/t.csv"], d.path());
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).starts_with("no/dir/t.csv: error: cannot write file"), "{}", stderr(&o));
}

#[test]
fn line_follow_driver_with_json_summary_png_and_json_lines() {
    let d = tempfile::tempdir().unwrap();
    let o = botsim(
        &[
            "run",
            "--timing",
            "fast",
            "--driver",
            "line-follow",
            "--json",
            "--png",
            "p.png",
            "--trace-json",
            "t.jsonl",
            "--trace-csv",
            "t.csv",
        ],
        d.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["driver"], "reached the end of the line");
    let &(ex, ey) = botsim::world::COURSE.last().unwrap();
    assert_eq!(
        (summary["final"]["loc_x"].as_u64(), summary["final"]["loc_y"].as_u64()),
        (Some(ex as u64), Some(ey as u64))
    );
    assert_eq!(summary["final"]["orientation"], "N");
    assert!(summary["cycles"].as_u64().unwrap() > 1_000_000);
    assert_eq!(summary["files"].as_array().unwrap().len(), 3);
    assert!(stderr(&o).is_empty(), "no progress bar when stderr is not a terminal: {}", stderr(&o));

    // JSON lines: one per pulse, decoded fields present, same rows as the CSV.
    let jsonl = std::fs::read_to_string(d.path().join("t.jsonl")).unwrap();
    let csv = std::fs::read_to_string(d.path().join("t.csv")).unwrap();
    let rows: Vec<serde_json::Value> = jsonl.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(rows.len(), csv.lines().count() - 1);
    assert_eq!(rows[0]["orientation"], "E");
    assert_eq!(rows[0]["on_line"], true);
    assert_eq!(rows[1]["movement"], "forward");
    let last = rows.last().unwrap();
    assert_eq!((last["prox_left"].as_bool(), last["prox_right"].as_bool()), (Some(true), Some(true)));

    // The PNG: 512 x 512, and the centre of every visited cell in the path colour.
    let (width, height, buf) = common::decode_png(&d.path().join("p.png"));
    assert_eq!((width, height), (512, 512));
    let px = |x: u32, y: u32| {
        let i = (y * width + x) as usize * 3;
        [buf[i], buf[i + 1], buf[i + 2]]
    };
    let style = botsim::render::PathStyle::default();
    let mut checked = 0;
    for r in rows.iter().take(rows.len() - 1) {
        let (x, y) = (r["loc_x"].as_u64().unwrap() as u32, r["loc_y"].as_u64().unwrap() as u32);
        if (x, y) == (64, 64) {
            continue; // the start cell is outlined
        }
        assert_eq!(px(4 * x + 2, 4 * y + 2), style.path, "path at ({x}, {y})");
        checked += 1;
    }
    assert!(checked > 1000);
    assert_eq!(px(4 * ex as u32 + 1, 4 * ey as u32 + 1), style.end, "the end cell");
    assert_eq!(px(4 * 64 - 1, 4 * 64 + 1), style.start, "the start outline");
    assert_eq!(px(0, 0), botsim::Cell::Obstruction.colour(), "the border wall");
}

#[test]
fn vcd_windows_in_samples_and_cycles() {
    let d = tempfile::tempdir().unwrap();
    // Samples 3..=5: the file covers exactly those three pulses.
    let o = botsim(
        &[
            "run",
            "--timing",
            "fast",
            "--samples",
            "8",
            "--vcd",
            "s.vcd",
            "--trace-from",
            "3",
            "--trace-to",
            "5",
            "--trace-csv",
            "t.csv",
        ],
        d.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(d.path().join("t.csv")).unwrap();
    let cycles: Vec<u64> = csv.lines().skip(1).map(|l| l.split(',').nth(1).unwrap().parse().unwrap()).collect();
    let (rises, first, last) = scan_vcd(&d.path().join("s.vcd"));
    assert_eq!(rises, 3);
    // Time is in ps, 10,000 ps per cycle; the window starts right after sample 2's pulse.
    assert!(first > cycles[2] * 10_000 && first < cycles[3] * 10_000, "{first}");
    assert!(last >= cycles[5] * 10_000 && last < cycles[6] * 10_000, "{last}");
    // Cycles 2000..=3000: the file's time stamps stay inside.
    let o = botsim(
        &[
            "run",
            "--timing",
            "fast",
            "--samples",
            "3",
            "--vcd",
            "c.vcd",
            "--trace-from",
            "2000c",
            "--trace-to",
            "3000c",
        ],
        d.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let (_, first, last) = scan_vcd(&d.path().join("c.vcd"));
    assert_eq!(first, 2000 * 10_000);
    assert!(last <= 3000 * 10_000 && last > 2990 * 10_000, "{last}");
    let o = botsim(&["run", "--trace-from", "3"], d.path());
    assert_eq!(o.status.code(), Some(1), "a window needs --vcd");
}

/// (upd_sysregs rises, first time stamp, last time stamp) of a VCD file.
fn scan_vcd(path: &Path) -> (u32, u64, u64) {
    let f = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut p = vcd::Parser::new(f);
    let h = p.parse_header().unwrap();
    let upd = h.find_var(&["TOP", "upd_sysregs"]).unwrap().code;
    let (mut rises, mut last_v, mut first, mut last) = (0, false, None, 0);
    for c in p {
        match c.unwrap() {
            vcd::Command::Timestamp(t) => {
                first.get_or_insert(t);
                last = t;
            }
            vcd::Command::ChangeScalar(code, v) if code == upd => {
                let now = v == vcd::Value::V1;
                rises += (now && !last_v) as u32;
                last_v = now;
            }
            _ => {}
        }
    }
    (rises, first.unwrap(), last)
}

#[test]
fn every_backend_gives_the_same_trace() {
    let d = tempfile::tempdir().unwrap();
    std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/drive.txt"), d.path().join("drive.txt"))
        .unwrap();
    let mut traces = vec![];
    for backend in ["rtl", "iss", "lockstep"] {
        let csv = format!("{backend}.csv");
        let o = botsim(
            &["run", "--backend", backend, "--timing", "fast", "--motors", "drive.txt", "--trace-csv", &csv, "--quiet"],
            d.path(),
        );
        assert_eq!(o.status.code(), Some(0), "{backend}: {}", stderr(&o));
        traces.push(std::fs::read_to_string(d.path().join(csv)).unwrap());
    }
    assert!(rows(&traces[0]).len() > 40);
    assert_eq!(traces[0], traces[1], "rtl and iss");
    assert_eq!(traces[0], traces[2], "rtl and lockstep");
    // A picture of the end works on any backend (the video port is read from an RTL model).
    let o =
        botsim(&["frame", "--backend", "iss", "--timing", "fast", "--motors", "drive.txt", "-o", "f.png"], d.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(d.path().join("f.png").exists());
}
