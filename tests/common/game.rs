//! examples/nexys4_game, a final project without a bot: its program's rules (game.psm's
//! header) and its picture.

/// The design's folder, from the repository's root.
pub const GAME: &str = "examples/nexys4_game";

/// game.psm as its header states it: places in 4-pixel steps, x 0-156 and y 0-116, one step
/// a frame in each; a step toward an edge the box is at turns it around first and counts a
/// bounce; a held button sets the direction before the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Game {
    pub x: u8,
    pub y: u8,
    pub dx: i8,
    pub dy: i8,
    pub bounces: u32,
}

impl Game {
    const MAX_X: u8 = 156;
    const MAX_Y: u8 = 116;

    pub fn start() -> Game {
        Game { x: 10, y: 20, dx: 1, dy: 1, bounces: 0 }
    }

    /// One frame, with the left button held or not.
    pub fn frame(&mut self, left: bool) {
        if left {
            self.dx = -1;
        }
        let mut step = |p: &mut u8, d: &mut i8, max: u8| {
            if (*d == 1 && *p == max) || (*d == -1 && *p == 0) {
                *d = -*d;
                self.bounces += 1;
            }
            *p = p.wrapping_add_signed(*d);
        };
        let (mut x, mut dx, mut y, mut dy) = (self.x, self.dx, self.y, self.dy);
        step(&mut x, &mut dx, Self::MAX_X);
        step(&mut y, &mut dy, Self::MAX_Y);
        (self.x, self.dx, self.y, self.dy) = (x, dx, y, dy);
    }

    pub fn leds(&self) -> u16 {
        (self.y as u16) << 8 | self.x as u16
    }
}

impl Game {
    /// The box's places over `frames` frames from the start, no button held.
    pub fn track(frames: usize) -> Vec<(u8, u8)> {
        let mut g = Game::start();
        let mut track = vec![(g.x, g.y)];
        for _ in 0..frames {
            g.frame(false);
            track.push((g.x, g.y));
        }
        track
    }
}

/// Where a frame (PNG) of the game shows the box, in its 4-pixel steps, after checking the
/// picture: 640 x 480, a grey frame 2 pixels wide, one white 16 x 16 box, the rest dark blue.
pub fn box_place(png: &[u8]) -> Result<(u8, u8), String> {
    let (w, h, rgb) = super::rgb(png);
    if (w, h) != (640, 480) {
        return Err(format!("{w} x {h}"));
    }
    let px = |c: u32, r: u32| &rgb[3 * (r * w + c) as usize..][..3];
    let white: Vec<(u32, u32)> =
        (0..h).flat_map(|r| (0..w).map(move |c| (c, r))).filter(|&(c, r)| px(c, r) == [255; 3]).collect();
    let Some(&(c, r)) = white.first() else { return Err("no box".into()) };
    let in_box = |&(cc, rr): &(u32, u32)| (c..c + 16).contains(&cc) && (r..r + 16).contains(&rr);
    if white.len() != 256 || !white.iter().all(in_box) || c % 4 != 0 || r % 4 != 0 {
        return Err(format!("not one 16 x 16 box on the 4-pixel grid: {} white pixels from ({c}, {r})", white.len()));
    }
    let background = (0..h).flat_map(|r| (0..w).map(move |c| (c, r))).filter(|p| !in_box(p)).all(|(c, r)| {
        let edge = !(2..638).contains(&c) || !(2..478).contains(&r);
        px(c, r) == if edge { [0x88; 3] } else { [0x00, 0x11, 0x44] }
    });
    if !background {
        return Err("the background is not the grey frame on dark blue".into());
    }
    Ok(((c / 4) as u8, (r / 4) as u8))
}
