//! Pictures of a run: the world with the bot's path (start, end and heading, blocked moves).
//!
//! ```
//! use botsim_core::render::{path_picture, PathStyle};
//! use botsim_core::world::World;
//! let png = path_picture(&World::builtin(), &[], 15, &PathStyle::default());
//! assert_eq!(&png[1..4], b"PNG");
//! ```

use crate::picture::encode_rgb;
use crate::regs::Snapshot;
use crate::world::{World, SIZE};

/// Colours and scale of a path picture.
#[derive(Clone, Debug)]
pub struct PathStyle {
    /// Pixels per cell (4 gives the course display's 512 x 512).
    pub scale: u32,
    /// The centre of every cell the bot stood on.
    pub path: [u8; 3],
    /// An outline around the start cell.
    pub start: [u8; 3],
    /// The end cell, and a tick from its centre towards the final heading.
    pub end: [u8; 3],
    /// A cross on a cell from which a move was refused by an obstruction.
    pub blocked: [u8; 3],
}

impl Default for PathStyle {
    fn default() -> PathStyle {
        PathStyle { scale: 4, path: [0, 200, 0], start: [0, 90, 255], end: [255, 140, 0], blocked: [255, 0, 255] }
    }
}

/// The cells from which a forward or reverse move was refused ([`Snapshot::move_refused`]).
pub fn blocked_moves(snapshots: &[Snapshot], threshold: u8) -> Vec<(u8, u8)> {
    snapshots.windows(2).filter(|w| w[0].move_refused(&w[1], threshold)).map(|w| w[0].location()).collect()
}

/// An RGB canvas.
struct Canvas {
    w: u32,
    h: u32,
    rgb: Vec<u8>,
}

impl Canvas {
    fn new(w: u32, h: u32) -> Canvas {
        Canvas { w, h, rgb: vec![0; (w * h * 3) as usize] }
    }

    fn put(&mut self, x: i64, y: i64, c: [u8; 3]) {
        if x >= 0 && y >= 0 && (x as u32) < self.w && (y as u32) < self.h {
            let i = ((y as u32 * self.w + x as u32) * 3) as usize;
            self.rgb[i..i + 3].copy_from_slice(&c);
        }
    }

    fn rect(&mut self, x: i64, y: i64, w: i64, h: i64, c: [u8; 3]) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.put(xx, yy, c);
            }
        }
    }
}

/// A PNG of `world` with the path of `snapshots` drawn on it.
pub fn path_picture(world: &World, snapshots: &[Snapshot], threshold: u8, style: &PathStyle) -> Vec<u8> {
    paths_picture(world, &[snapshots], threshold, style)
}

/// The paths of a design's other bots (the second, third, fourth): cyan, yellow, red.
pub const OTHER_PATHS: [[u8; 3]; 3] = [[0, 200, 200], [230, 200, 0], [220, 40, 40]];

/// A PNG of `world` with the paths of several bots drawn on it, the first in `style.path`,
/// the others in [`OTHER_PATHS`]; each bot's start, end and refused moves as `style` says.
pub fn paths_picture(world: &World, trails: &[&[Snapshot]], threshold: u8, style: &PathStyle) -> Vec<u8> {
    let s = style.scale.max(1) as i64;
    let n = SIZE as i64;
    let mut c = Canvas::new((n * s) as u32, (n * s) as u32);
    for y in 0..n {
        for x in 0..n {
            c.rect(x * s, y * s, s, s, world.get(x as u8, y as u8).colour());
        }
    }
    for (k, snapshots) in trails.iter().enumerate() {
        let path = if k == 0 { style.path } else { OTHER_PATHS[(k - 1) % OTHER_PATHS.len()] };
        trail(&mut c, s, snapshots, threshold, &PathStyle { path, ..*style });
    }
    encode_rgb(c.w, c.h, &c.rgb)
}

/// One bot's path on the canvas: the middle of each visited cell (the cell's own colour stays
/// visible around it), its refused moves, its start and its end with its heading.
fn trail(c: &mut Canvas, s: i64, snapshots: &[Snapshot], threshold: u8, style: &PathStyle) {
    let cell = |(x, y): (u8, u8)| ((x as i64 & 127) * s, (y as i64 & 127) * s);
    let inner = (s / 2).max(1);
    let off = (s - inner) / 2;
    for snap in snapshots {
        let (px, py) = cell(snap.location());
        c.rect(px + off, py + off, inner, inner, style.path);
    }
    for b in blocked_moves(snapshots, threshold) {
        let (px, py) = cell(b);
        for i in 0..s {
            c.put(px + i, py + i, style.blocked);
            c.put(px + s - 1 - i, py + i, style.blocked);
        }
    }
    if let (Some(first), Some(last)) = (snapshots.first(), snapshots.last()) {
        let (px, py) = cell(first.location());
        for i in -1..=s {
            for (x, y) in [(px + i, py - 1), (px + i, py + s), (px - 1, py + i), (px + s, py + i)] {
                c.put(x, y, style.start);
            }
        }
        let (px, py) = cell(last.location());
        c.rect(px, py, s, s, style.end);
        let (dx, dy) = last.orientation().step();
        let (cx, cy) = (px + s / 2, py + s / 2);
        for k in 0..=2 * s {
            c.put(cx + dx as i64 * k, cy + dy as i64 * k, style.end);
        }
    }
}

/// The course display: 640 x 480, the world at 4 x 4 pixels per cell (rows 0-119 visible, 512
/// pixels wide; black outside), the bot's 16 x 16 icon centred on its cell, the colour table
/// below (12-bit colours, as on the Nexys4).
pub mod display {
    use super::Canvas;
    use crate::picture::encode_rgb;
    use crate::regs::{Orientation, Snapshot};
    use crate::world::{Cell, World};

    pub const WIDTH: u32 = 640;
    pub const HEIGHT: u32 = 480;
    /// The display timing generator's active width and the visible map rows (spec §12).
    pub const ACTIVE_WIDTH: u32 = 512;
    pub const VISIBLE_ROWS: u32 = 120;

    /// 12-bit colours: floor, line, obstruction, reserved; icon colours 1, 2, 3.
    pub const COLOURS: [u16; 7] = [0xFFF, 0x000, 0xC22, 0x29F, 0xF80, 0x04C, 0xFF0];

    fn rgb(c12: u16) -> [u8; 3] {
        [((c12 >> 8 & 15) * 17) as u8, ((c12 >> 4 & 15) * 17) as u8, ((c12 & 15) * 17) as u8]
    }

    /// The colour of a world cell.
    pub fn cell_colour(c: Cell) -> [u8; 3] {
        rgb(COLOURS[c as usize])
    }

    /// Icon colour 1-3.
    pub fn icon_colour(i: u8) -> [u8; 3] {
        rgb(COLOURS[3 + i.clamp(1, 3) as usize])
    }

    /// The bot heading North: 0 transparent, 1 outline, 2 body, 3 eyes.
    const ICON_N: [&str; 16] = [
        "................",
        ".......11.......",
        "......1221......",
        "......1221......",
        ".....122221.....",
        ".....122221.....",
        "....12222221....",
        "....13222231....",
        "...1233223321...",
        "...1222222221...",
        "..122222222221..",
        "..122222222221..",
        ".12222222222221.",
        ".11111111111111.",
        "................",
        "................",
    ];

    type Icon = [[u8; 16]; 16];

    fn parse(rows: &[&str; 16]) -> Icon {
        let mut icon = [[0; 16]; 16];
        for (y, r) in rows.iter().enumerate() {
            for (x, ch) in r.bytes().enumerate().take(16) {
                icon[y][x] = if ch == b'.' { 0 } else { ch - b'0' };
            }
        }
        icon
    }

    /// Rotated clockwise by `eighths` x 45 degrees (nearest neighbour about the centre).
    fn rotated(icon: &Icon, eighths: u8) -> Icon {
        let t = std::f64::consts::FRAC_PI_4 * eighths as f64;
        let (sin, cos) = t.sin_cos();
        let mut out = [[0; 16]; 16];
        for (y, row) in out.iter_mut().enumerate() {
            for (x, px) in row.iter_mut().enumerate() {
                let (dx, dy) = (x as f64 - 7.5, y as f64 - 7.5);
                let sx = (7.5 + dx * cos + dy * sin).round();
                let sy = (7.5 - dx * sin + dy * cos).round();
                if (0.0..16.0).contains(&sx) && (0.0..16.0).contains(&sy) {
                    *px = icon[sy as usize][sx as usize];
                }
            }
        }
        out
    }

    /// The icon for a heading: the North bitmap, turned.
    pub fn icon(h: Orientation) -> [[u8; 16]; 16] {
        rotated(&parse(&ICON_N), h as u8)
    }

    /// One display frame as PNG: `world` as read through the video port, the bot of `s`.
    pub fn frame(world: &World, s: Option<&Snapshot>) -> Vec<u8> {
        let mut c = Canvas::new(WIDTH, HEIGHT);
        for y in 0..VISIBLE_ROWS as i64 {
            for x in 0..(ACTIVE_WIDTH / 4) as i64 {
                c.rect(x * 4, y * 4, 4, 4, cell_colour(world.get(x as u8, y as u8)));
            }
        }
        if let Some(s) = s {
            let icon = icon(s.orientation());
            let (cx, cy) = ((s.regs.loc_x & 127) as i64 * 4 + 2, (s.regs.loc_y & 127) as i64 * 4 + 2);
            for (y, row) in icon.iter().enumerate() {
                for (x, &v) in row.iter().enumerate() {
                    let (px, py) = (cx - 8 + x as i64, cy - 8 + y as i64);
                    // The colorizer shows the icon only where the display is active.
                    if v != 0 && px < ACTIVE_WIDTH as i64 && py < (VISIBLE_ROWS * 4) as i64 {
                        c.put(px, py, icon_colour(v));
                    }
                }
            }
        }
        encode_rgb(c.w, c.h, &c.rgb)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::regs::Registers;

    fn colours(png_bytes: &[u8]) -> std::collections::BTreeSet<[u8; 3]> {
        let mut r = png::Decoder::new(std::io::Cursor::new(png_bytes)).read_info().unwrap();
        let mut buf = vec![0; r.output_buffer_size().unwrap()];
        let info = r.next_frame(&mut buf).unwrap();
        buf[..info.buffer_size()].chunks(3).map(|p| [p[0], p[1], p[2]]).collect()
    }

    #[test]
    fn each_bot_has_its_own_path_colour() {
        let at = |sample, loc_x, loc_y| Snapshot {
            sample,
            cycle: 0,
            regs: Registers { loc_x, loc_y, bot_info: 0x42, ..Registers::default() },
        };
        let hero: Vec<Snapshot> = (0..6).map(|k| at(k, 10 + k as u8, 20)).collect();
        let monster: Vec<Snapshot> = (0..6).map(|k| at(k, 40, 50 + k as u8)).collect();
        let style = PathStyle::default();
        let both = colours(&paths_picture(&World::empty(), &[&hero, &monster], 15, &style));
        assert!(both.contains(&style.path) && both.contains(&OTHER_PATHS[0]), "{both:?}");
        let one = colours(&path_picture(&World::empty(), &hero, 15, &style));
        assert!(one.contains(&style.path) && !one.contains(&OTHER_PATHS[0]), "{one:?}");
    }
}
