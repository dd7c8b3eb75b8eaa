//! World files: the course maps read in place, every format round-trips, bad files give one
//! clear error with a location.

use crate::common;

use std::path::Path;

use botsim::world::{Cell, World, WorldFormat};

/// (file stem, line cells, obstruction cells, floor cells) from the reference README.
const COURSE_MAPS: [(&str, usize, usize, usize); 3] =
    [("world_map_part1", 131, 1166, 15087), ("world_map_lr", 176, 2609, 13599), ("world_map_loop", 197, 2814, 13373)];

#[test]
fn course_maps_load_in_both_formats_and_agree() {
    for (stem, line, wall, floor) in COURSE_MAPS {
        let Some(txt) = common::reference_map(&format!("{stem}.txt")) else { return };
        let coe = common::reference_map(&format!("{stem}.coe")).unwrap();
        let a = World::load(&txt).unwrap_or_else(|e| panic!("{e}"));
        let b = World::load(&coe).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(a, b, "{stem}: .coe equals .txt read row-major");
        assert_eq!(a.counts(), [floor, line, wall, 0], "{stem}");
        assert_eq!(a.get(64, 64), Cell::Line, "{stem}: the start cell");
        assert_eq!(a.get(65, 64), Cell::Line, "{stem}: the line runs East");
    }
}

#[test]
fn part1_tracker_route_is_on_the_line() {
    let Some(txt) = common::reference_map("world_map_part1.txt") else { return };
    let w = World::load(&txt).unwrap();
    let route: Vec<(i32, i32)> = common::PART1_TRACKER.iter().map(|&(x, y)| (x as i32, y as i32)).collect();
    for pair in route.windows(2) {
        let ((x0, y0), (x1, y1)): ((i32, i32), (i32, i32)) = (pair[0], pair[1]);
        let (dx, dy) = ((x1 - x0).signum(), (y1 - y0).signum());
        let (mut x, mut y) = (x0, y0);
        loop {
            assert_eq!(w.get(x as u8, y as u8), Cell::Line, "({x:#x}, {y:#x})");
            if (x, y) == (x1, y1) {
                break;
            }
            x += dx;
            y += dy;
        }
    }
    assert_eq!(w.get(0x3C, 0x3F), Cell::Obstruction, "the end is blocked");
    assert_eq!(w.get(0x3D, 0x3F), Cell::Obstruction);
}

#[test]
fn every_format_round_trips() {
    let mut w = World::builtin();
    w.set(3, 120, Cell::Reserved);
    let dir = tempfile::tempdir().unwrap();
    for ext in ["txt", "coe", "mem", "png"] {
        let p = dir.path().join(format!("w.{ext}"));
        std::fs::write(&p, w.to_format(WorldFormat::of(&p).unwrap())).unwrap();
        assert_eq!(World::load(&p).unwrap(), w, "{ext}");
    }
    // The .coe is written exactly as the course files are: no final newline, a final comma.
    let coe = w.to_coe();
    assert!(coe.starts_with("MEMORY_INITIALIZATION_RADIX=16;\nMEMORY_INITIALIZATION_VECTOR=\n\n"));
    assert!(coe.ends_with("2,") && !coe.ends_with('\n'));
    assert_eq!(coe.lines().count(), 3 + 512);
    let txt = w.to_txt();
    assert_eq!(txt.lines().count(), 135);
    assert!(txt.lines().skip(7).all(|l| l.len() == 132));
}

#[test]
fn builtin_world_is_the_documented_course() {
    let w = World::builtin();
    let [floor, line, wall, reserved] = w.counts();
    assert_eq!(reserved, 0);
    assert!(line > 100 && wall > 500 && floor > 10_000);
    for (x, y) in [(0, 0), (127, 127), (1, 64), (126, 3)] {
        assert_eq!(w.get(x, y), Cell::Obstruction, "border ({x}, {y})");
    }
    // The line's last cell is followed by a wall (the bot ends blocked, like Part 1).
    let &(ex, ey) = botsim::world::COURSE.last().unwrap();
    assert_eq!(w.get(ex, ey), Cell::Line);
    assert_eq!(w.get(ex, ey - 1), Cell::Obstruction);
}

fn error(name: &str, content: &[u8]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join(name);
    std::fs::write(&p, content).unwrap();
    let e = World::load(&p).unwrap_err().to_string();
    e.replace(&format!("{}/", dir.path().display()), "")
}

#[test]
fn bad_world_files_give_one_located_error() {
    let good = World::builtin().to_txt();
    assert_eq!(
        error("w.txt", good.replacen("|22", "|29", 1).as_bytes()),
        "w.txt:8:6: error: '9' is not a cell value 0-3"
    );
    assert_eq!(
        error("w.txt", good.replacen("\n001|", "\n000|", 1).as_bytes()),
        "w.txt:9:1: error: row 000 again (first at line 8)"
    );
    let short: String = good.lines().take(100).map(|l| format!("{l}\n")).collect();
    assert_eq!(error("w.txt", short.as_bytes()), "w.txt: error: row 05D is missing (35 of 128 rows missing)");
    let long_row = good.replacen("|2222", "|22222", 1);
    assert_eq!(error("w.txt", long_row.as_bytes()), "w.txt:8:5: error: row 000 has 129 cells; a row has 128");
    let coe = World::builtin().to_coe();
    assert_eq!(error("w.coe", coe.replacen("2,", "4,", 1).as_bytes()), "w.coe:4:1: error: '4' is not a cell value 0-3");
    assert_eq!(error("w.coe", &coe.as_bytes()[..coe.len() - 2]), "w.coe: error: has 16383 values; a world has 16384");
    assert_eq!(error("w.coe", b"hello"), "w.coe:1:1: error: missing MEMORY_INITIALIZATION_RADIX");
    assert_eq!(error("w.mem", b"0\n1\n7\n"), "w.mem:3:1: error: '7' is not a cell value 0-3");
    assert_eq!(error("w.mem", b""), "w.mem: error: no cell values found");
    assert_eq!(
        error("w.png", b"not a png"),
        "w.png: error: not a readable PNG: Format error at byte 0: wrong signature"
            .replace("Format error at byte 0: wrong signature", &png_error())
    );
    assert_eq!(error("w.bmp", b""), "w.bmp: error: unknown world format (expected .txt, .coe, .mem or .png)");
    assert!(World::load(Path::new("/no/such/w.txt"))
        .unwrap_err()
        .to_string()
        .ends_with("cannot read file: no such file or directory"));
    // A Xilinx COE with a final ';', blanks and upper-case keywords reads too.
    let xilinx = format!(
        "; comment\nMEMORY_INITIALIZATION_RADIX = 16;\nMEMORY_INITIALIZATION_VECTOR =\n{};\n",
        vec!["0"; 16384].join(", ")
    );
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.coe");
    std::fs::write(&p, xilinx).unwrap();
    assert_eq!(World::load(&p).unwrap(), World::empty());
}

/// The png crate's own wording for a bad signature.
fn png_error() -> String {
    let d = png::Decoder::new(std::io::Cursor::new(b"not a png".to_vec()));
    d.read_info().err().map(|e| e.to_string()).unwrap_or_default()
}

#[test]
fn png_with_a_foreign_colour_names_the_pixel() {
    let mut rgb = vec![255u8; 128 * 128 * 3];
    rgb[(5 * 128 + 7) * 3] = 12;
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, 128, 128);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header().unwrap().write_image_data(&rgb).unwrap();
    }
    let e = error("w.png", &out);
    assert!(e.starts_with("w.png: error: pixel (7, 5) has colour #0CFFFF;"), "{e}");
    let mut small = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut small, 64, 64);
        enc.set_color(png::ColorType::Grayscale);
        enc.write_header().unwrap().write_image_data(&vec![255u8; 64 * 64]).unwrap();
    }
    assert_eq!(error("w.png", &small), "w.png: error: image is 64 x 64 pixels; a world is 128 x 128");
}
