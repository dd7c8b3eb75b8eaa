//! `botsim frame`, `run --frames` and `botsim map` as a user runs them.

use crate::common;

use std::path::Path;

use common::botsim;

use botsim::render::display;
use botsim::world::World;

#[test]
fn frame_shows_the_world_through_the_video_port_and_the_bot() {
    let d = tempfile::tempdir().unwrap();
    let o = botsim(&["frame", "--timing", "fast", "--samples", "0", "-o", "f.png", "--quiet"], d.path());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (w, h, px) = common::decode_png(&d.path().join("f.png"));
    assert_eq!((w, h), (640, 480));
    let at = |x: u32, y: u32| {
        let i = ((y * w + x) * 3) as usize;
        [px[i], px[i + 1], px[i + 2]]
    };
    let world = World::builtin();
    // Every visible cell away from the icon has its colour from the colour table.
    for y in (0..120u32).step_by(3) {
        for x in (0..128u32).step_by(3) {
            if (x as i32 - 64).abs() <= 3 && (y as i32 - 64).abs() <= 3 {
                continue;
            }
            assert_eq!(at(4 * x + 1, 4 * y + 1), display::cell_colour(world.get(x as u8, y as u8)), "cell ({x}, {y})");
        }
    }
    assert_eq!(at(600, 100), [0, 0, 0], "right of the 512-pixel active area");
    // The icon: North bitmap turned East, centred on (64, 64) = pixel (258, 258).
    let icon = display::icon(botsim::Orientation::East);
    for (iy, row) in icon.iter().enumerate() {
        for (ix, &v) in row.iter().enumerate() {
            if v != 0 {
                assert_eq!(at(250 + ix as u32, 250 + iy as u32), display::icon_colour(v));
            }
        }
    }
}

#[test]
fn run_saves_frames_every_n_samples() {
    let d = tempfile::tempdir().unwrap();
    let o = botsim(
        &[
            "run",
            "--timing",
            "fast",
            "--samples",
            "40",
            "--motors",
            "m.txt",
            "--frames",
            "fr",
            "--frame-every",
            "15",
            "--quiet",
        ],
        d.path(),
    );
    assert_eq!(o.status.code(), Some(1), "the motor file is missing");
    std::fs::write(d.path().join("m.txt"), "forward 40\n").unwrap();
    let o = botsim(
        &["run", "--timing", "fast", "--motors", "m.txt", "--frames", "fr", "--frame-every", "15", "--quiet"],
        d.path(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut names: Vec<String> = std::fs::read_dir(d.path().join("fr"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["frame_000000.png", "frame_000015.png", "frame_000030.png", "frame_000040.png"]);
    // The bot moved two cells East between the first and the last frame.
    let (w, _, first) = common::decode_png(&d.path().join("fr/frame_000000.png"));
    let (_, _, last) = common::decode_png(&d.path().join("fr/frame_000040.png"));
    let body = display::icon_colour(2);
    let body_x =
        |px: &[u8]| -> Vec<u32> { (0..w).filter(|&x| px[((258 * w + x) * 3) as usize..][..3] == body).collect() };
    let (a, b) = (body_x(&first), body_x(&last));
    assert_eq!(b[0] - a[0], 8, "two cells at 4 pixels each");
}

#[test]
fn map_show_and_convert() {
    let d = tempfile::tempdir().unwrap();
    let o = botsim(&["map", "show", "builtin"], d.path());
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    let row64: &str = text.lines().nth(1 + 64).unwrap();
    assert!(row64.starts_with(" 64 ##"));
    assert_eq!(&row64[4 + 64..4 + 65], ".", "the start cell is a line cell");
    assert!(text.trim_end().ends_with(&format!("reserved {}", 0)));
    for (from, to) in [("builtin", "w.txt"), ("w.txt", "w.coe"), ("w.coe", "w.png"), ("w.png", "w.mem")] {
        let o = botsim(&["map", "convert", from, to], d.path());
        assert!(o.status.success(), "{from} -> {to}: {}", String::from_utf8_lossy(&o.stderr));
    }
    assert_eq!(World::load(&d.path().join("w.mem")).unwrap(), World::builtin());
    let o = botsim(&["map", "convert", "w.txt", "w.bmp"], d.path());
    assert_eq!(
        String::from_utf8_lossy(&o.stderr),
        "w.bmp: error: unknown world format (expected .txt, .coe, .mem or .png)\n"
    );
    std::fs::write(d.path().join("bad.txt"), "000|0\n").unwrap();
    let o = botsim(&["map", "show", "bad.txt"], d.path());
    assert_eq!(
        (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned()),
        (Some(1), "bad.txt:1:5: error: row 000 has 1 cells; a row has 128\n".into())
    );
}

#[test]
fn every_subcommand_help_has_an_example() {
    for args in [
        &["run", "--help"][..],
        &["frame", "--help"],
        &["map", "--help"],
        &["map", "show", "--help"],
        &["map", "convert", "--help"],
        &["asm", "--help"],
        &["disasm", "--help"],
        &["firmware", "--help"],
        &["bench", "--help"],
    ] {
        let o = botsim(args, Path::new("."));
        assert!(o.status.success(), "{args:?}");
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains("Example"), "{args:?}: {text}");
    }
}

#[test]
fn bench_reports_each_backend_as_json() {
    let o = botsim(&["bench", "--quick", "--json"], Path::new("."));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for key in ["rtl_mcycles_per_s", "rtl_vcd_mcycles_per_s", "iss_mcycles_per_s"] {
        assert!(v[key].as_f64().is_some_and(|x| x > 0.0), "{key}: {v}");
    }
    // The ISS backend is far faster than the RTL, which is faster than with a VCD.
    assert!(v["iss_mcycles_per_s"].as_f64() > v["rtl_mcycles_per_s"].as_f64());
    assert!(v["rtl_mcycles_per_s"].as_f64() > v["rtl_vcd_mcycles_per_s"].as_f64());
}
