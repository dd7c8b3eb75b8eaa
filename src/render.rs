//! Pictures of a run: the world with the bot's path (start, end and heading, blocked moves).
//!
//! ```
//! use botsim::render::{path_picture, PathStyle};
//! use botsim::world::World;
//! let png = path_picture(&World::builtin(), &[], 15, &PathStyle::default());
//! assert_eq!(&png[1..4], b"PNG");
//! ```

use crate::picture::encode_rgb;
use crate::regs::{Movement, Snapshot};
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

/// The cells from which a forward or reverse move was refused: a threshold event (a counter
/// at `threshold`) while moving, and the same location in the next snapshot.
pub fn blocked_moves(snapshots: &[Snapshot], threshold: u8) -> Vec<(u8, u8)> {
    snapshots
        .windows(2)
        .filter(|w| {
            let (a, b) = (&w[0], &w[1]);
            let event = a.regs.lm_dist >= threshold || a.regs.rm_dist >= threshold;
            event && matches!(a.movement(), Movement::Forward | Movement::Reverse) && a.location() == b.location()
        })
        .map(|w| w[0].location())
        .collect()
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
    let s = style.scale.max(1) as i64;
    let n = SIZE as i64;
    let mut c = Canvas::new((n * s) as u32, (n * s) as u32);
    for y in 0..n {
        for x in 0..n {
            c.rect(x * s, y * s, s, s, world.get(x as u8, y as u8).colour());
        }
    }
    let cell = |(x, y): (u8, u8)| ((x as i64 & 127) * s, (y as i64 & 127) * s);
    // The path: the middle of each visited cell (the cell's own colour stays visible around it).
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
    encode_rgb(c.w, c.h, &c.rgb)
}
