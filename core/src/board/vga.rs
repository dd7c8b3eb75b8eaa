//! VGA frames captured from a design's own pins (spec board.md 1): the changes of the 12-bit
//! colour and the two (active-low) syncs, with their times, become pictures. The mode is
//! found from the syncs: the lines between two vertical syncs say which of the course's modes
//! it is (525: 640 x 480 at 60 Hz; 806: 1024 x 768 at 60 Hz), the time between horizontal
//! syncs gives the pixel period. Pixel `i` of visible row `r` is the colour in the middle of
//! its pixel period, counted from the horizontal sync that precedes its line:
//! `sync + back porch + i` pixels after that sync's falling edge; row `r`'s line follows the
//! `(sync + back porch + r)`-th horizontal sync after the vertical sync's falling edge.
//!
//! ```
//! use botsim_core::board::vga::{Capture, MODE_640};
//! let mut cap = Capture::default();
//! // A synthetic 640 x 480 frame whose every pixel is 0xF80, timed at 40 ns per pixel.
//! let frames = botsim_core::board::vga::tests_support::frames(&MODE_640, 40_000, |_, _| 0xF80, 2);
//! for (t, v) in frames {
//!     cap.pins(t, v);
//! }
//! let f = cap.take().remove(0);
//! assert_eq!((f.width, f.height), (640, 480));
//! assert!(f.pixels.iter().all(|&p| p == 0xF80));
//! ```

/// A display mode's timing, in pixels and lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mode {
    pub width: u32,
    pub h_front: u32,
    pub h_sync: u32,
    pub h_back: u32,
    pub height: u32,
    pub v_front: u32,
    pub v_sync: u32,
    pub v_back: u32,
}

impl Mode {
    pub fn line_pixels(&self) -> u32 {
        self.width + self.h_front + self.h_sync + self.h_back
    }
    pub fn frame_lines(&self) -> u32 {
        self.height + self.v_front + self.v_sync + self.v_back
    }
}

/// 640 x 480 at 60 Hz (25 MHz): 800 x 525.
pub const MODE_640: Mode =
    Mode { width: 640, h_front: 16, h_sync: 96, h_back: 48, height: 480, v_front: 10, v_sync: 2, v_back: 33 };
/// 1024 x 768 at 60 Hz (65 MHz): 1344 x 806.
pub const MODE_1024: Mode =
    Mode { width: 1024, h_front: 24, h_sync: 136, h_back: 160, height: 768, v_front: 3, v_sync: 6, v_back: 29 };

/// One captured frame: 12-bit colours, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// When its vertical sync fell.
    pub time_ps: u64,
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<u16>,
}

impl Frame {
    /// 8-bit RGB, each 4-bit channel scaled by 17 (as the board's resistor DAC maps 0-15).
    pub fn rgb(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|&c| [(c >> 8 & 15) as u8 * 17, (c >> 4 & 15) as u8 * 17, (c & 15) as u8 * 17])
            .collect()
    }
}

impl Frame {
    /// The frame as a PNG.
    pub fn png(&self) -> Vec<u8> {
        crate::picture::encode_rgb(self.width, self.height, &self.rgb())
    }
}

/// Collects pin changes and turns each complete frame (vertical sync to vertical sync) into
/// a [`Frame`].
#[derive(Clone, Debug, Default)]
pub struct Capture {
    /// Pin changes since the last vertical sync fell: (time, colour | hs << 12 | vs << 13).
    changes: Vec<(u64, u16)>,
    last: u16,
    /// The pins just before the last vertical sync fell.
    before: u16,
    frame_start: Option<u64>,
    done: Vec<Frame>,
    /// Frames whose line count matched no mode.
    pub unknown: u64,
}

impl Capture {
    /// The pins changed at `time_ps` (`value` = r << 8 | g << 4 | b | hsync << 12 | vsync << 13).
    pub fn pins(&mut self, time_ps: u64, value: u16) {
        let vs_fell = self.last >> 13 & 1 == 1 && value >> 13 & 1 == 0;
        if vs_fell {
            if let Some(start) = self.frame_start {
                let changes = std::mem::take(&mut self.changes);
                match decode(start, &changes, self.before) {
                    Some(f) => self.done.push(f),
                    None => self.unknown += 1,
                }
            }
            self.frame_start = Some(time_ps);
            self.before = self.last;
            self.changes.clear();
        }
        if self.frame_start.is_some() {
            self.changes.push((time_ps, value));
        }
        self.last = value;
    }

    /// The frames completed so far (removed from the capture).
    pub fn take(&mut self) -> Vec<Frame> {
        std::mem::take(&mut self.done)
    }
}

/// Decode one frame from its pin changes (the first is the vertical sync's fall; `before`
/// the pins just before it).
///
/// Like a monitor, it takes a mode whose line count is near the frame's (a timing generator
/// that counts to its total inclusively sends a line and a pixel more than the standard, as
/// many teams' do) and places the picture by the syncs it measures: row 0 is the mode's back
/// porch after the vertical sync's end, column 0 the back porch after the horizontal sync's.
fn decode(start: u64, changes: &[(u64, u16)], before: u16) -> Option<Frame> {
    // Horizontal sync falls, in order (one may come with the vertical sync's own change), and
    // how many of them came while the vertical sync was low.
    let mut hs_falls = Vec::new();
    let mut v_sync = None;
    let mut prev = before;
    for &(t, v) in changes {
        if prev >> 12 & 1 == 1 && v >> 12 & 1 == 0 {
            hs_falls.push(t);
        }
        if v_sync.is_none() && v >> 13 & 1 == 1 {
            v_sync = Some(hs_falls.len() as u32);
        }
        prev = v;
    }
    let lines = hs_falls.len() as u32;
    let mode =
        [MODE_640, MODE_1024].into_iter().find(|m| lines.abs_diff(m.frame_lines()) <= m.frame_lines() / LINES_SLACK)?;
    let v_sync = v_sync.filter(|&s| s > 0)?;
    // The lines of the picture, from the first visible row's sync to the sync after the last
    // one's (the front porch follows), must be evenly timed: a frame whose pixel clock was
    // parked for a while (a live board parks it between the frames it shows) is whole when
    // the pause fell in the vertical sync or back porch, and is no frame otherwise.
    let first = (v_sync + mode.v_back) as usize - 1;
    let rows = hs_falls.get(first..=first + mode.height as usize)?;
    let mut spans: Vec<u64> = rows.windows(2).map(|w| w[1] - w[0]).collect();
    spans.sort_unstable();
    let typical = spans[spans.len() / 2];
    if spans[0] < typical - typical / 100 || spans[spans.len() - 1] > typical + typical / 100 {
        return None;
    }
    let line_ps = (rows[rows.len() - 1] - rows[0]) as f64 / mode.height as f64;
    let (pixel_ps, h_sync) = pixel_timing(&mode, changes, rows, line_ps)?;
    let mut pixels = Vec::with_capacity((mode.width * mode.height) as usize);
    for &hs in &rows[..mode.height as usize] {
        for i in 0..mode.width {
            let t = hs as f64 + ((h_sync + mode.h_back + i) as f64 + 0.5) * pixel_ps;
            pixels.push(value_at(changes, t as u64) & 0xFFF);
        }
    }
    Some(Frame { time_ps: start, width: mode.width, height: mode.height, pixels })
}

/// How far a frame's line count may be from its mode's: one part in this many.
const LINES_SLACK: u32 = 50;

/// The pixel period and the horizontal sync's width in pixels, measured. A line holds a whole
/// number of pixels near the mode's, and the timing generator's sync edges fall on pixel
/// edges: the count nearest the mode's whose pixels the horizontal sync's width and the
/// vertical sync's end (after its line's sync fell) both fit gives the period (the mode's
/// own when none does).
fn pixel_timing(mode: &Mode, changes: &[(u64, u16)], rows: &[u64], line_ps: f64) -> Option<(f64, u32)> {
    let from = changes.partition_point(|&(t, _)| t < rows[0]);
    let h_rise = changes[from..].iter().find(|&&(_, v)| v >> 12 & 1 == 1).map(|&(t, _)| t)?;
    let mut offsets = vec![(h_rise - rows[0]) as f64];
    // The vertical sync's rise, after the horizontal sync fall before it (none: it rose with
    // the frame's first line).
    if let Some(&(v_rise, _)) = changes.iter().find(|&&(_, v)| v >> 13 & 1 == 1) {
        let k = changes.partition_point(|&(t, _)| t < v_rise);
        let mut prev_hs = None;
        let mut prev = changes[0].1;
        for &(t, v) in &changes[1..k.max(1)] {
            if prev >> 12 & 1 == 1 && v >> 12 & 1 == 0 {
                prev_hs = Some(t);
            }
            prev = v;
        }
        if let Some(h) = prev_hs {
            offsets.push((v_rise - h) as f64);
        }
    }
    let nominal = mode.line_pixels();
    let slack = nominal / LINES_SLACK;
    let fits = |count: u32| {
        let pixel = line_ps / count as f64;
        offsets.iter().all(|o| (o / pixel - (o / pixel).round()).abs() < 0.05)
    };
    let count = (0..=slack).flat_map(|d| [nominal - d, nominal + d]).find(|&n| fits(n)).unwrap_or(nominal);
    let pixel_ps = line_ps / count as f64;
    let h_sync = (offsets[0] / pixel_ps).round() as u32;
    (h_sync > 0).then_some((pixel_ps, h_sync))
}

/// The pin value in effect at time `t`.
fn value_at(changes: &[(u64, u16)], t: u64) -> u16 {
    let k = changes.partition_point(|&(ct, _)| ct <= t);
    changes[k.saturating_sub(1)].1
}

/// Synthetic VGA timing for tests and examples (public so doc tests can use it).
#[doc(hidden)]
pub mod tests_support {
    use super::Mode;

    /// `count` frames of `mode` at `pixel_ps` per pixel, colour `f(row, col)`, as pin changes
    /// in the output-aligned timing of a DTG whose syncs change at the column where they begin.
    pub fn frames(mode: &Mode, pixel_ps: u64, f: impl Fn(u32, u32) -> u16, count: u32) -> Vec<(u64, u16)> {
        let mut out = Vec::new();
        let mut last = None;
        let mut t = 0;
        for _ in 0..count + 1 {
            for line in 0..mode.frame_lines() {
                for col in 0..mode.line_pixels() {
                    let visible = line < mode.height && col < mode.width;
                    let hs = !(mode.width + mode.h_front..mode.width + mode.h_front + mode.h_sync).contains(&col);
                    let vs = !(mode.height + mode.v_front..mode.height + mode.v_front + mode.v_sync).contains(&line);
                    let c = if visible { f(line, col) & 0xFFF } else { 0 };
                    let v = c | (hs as u16) << 12 | (vs as u16) << 13;
                    if last != Some(v) {
                        out.push((t, v));
                        last = Some(v);
                    }
                    t += pixel_ps;
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::tests_support::frames;
    use super::*;

    fn capture(changes: &[(u64, u16)]) -> Capture {
        let mut c = Capture::default();
        for &(t, v) in changes {
            c.pins(t, v);
        }
        c
    }

    #[test]
    fn every_pixel_lands_where_it_was_drawn() {
        let pattern = |r: u32, c: u32| ((r * 7 + c * 3) % 4096) as u16;
        let mut cap = capture(&frames(&MODE_640, 40_000, pattern, 2));
        let f = cap.take();
        assert_eq!(f.len(), 2);
        for (k, &p) in f[0].pixels.iter().enumerate() {
            let (r, c) = (k as u32 / 640, k as u32 % 640);
            assert_eq!(p, pattern(r, c), "row {r} col {c}");
        }
    }

    #[test]
    fn a_non_integer_pixel_period_and_the_1024_mode() {
        // 65 MHz: 15,384.6 ps; the synthetic source rounds to 15,385.
        let pattern = |r: u32, c: u32| if (r / 8 + c / 8) % 2 == 0 { 0xFFF } else { 0x000 };
        let mut cap = capture(&frames(&MODE_1024, 15_385, pattern, 1));
        let f = cap.take().remove(0);
        assert_eq!((f.width, f.height), (1024, 768));
        assert!(f.pixels.iter().enumerate().all(|(k, &p)| p == pattern(k as u32 / 1024, k as u32 % 1024)));
    }

    /// A pixel clock parked for a while and taken back (a live board between two frames it
    /// shows): the frame is whole when the pause fell in the vertical sync or back porch, and
    /// no frame when it fell in the picture.
    #[test]
    fn a_pause_before_the_picture_keeps_the_frame_and_one_inside_it_loses_it() {
        let pattern = |r: u32, c: u32| ((r * 5 + c) % 4096) as u16;
        let pixel = 40_000;
        let line = MODE_640.line_pixels() as u64 * pixel;
        let source = frames(&MODE_640, pixel, pattern, 1);
        // The first frame's vertical sync falls at the start of line 490 (480 + 10 front).
        let vs = (MODE_640.height + MODE_640.v_front) as u64 * line;
        let paused = |at: u64| -> Capture {
            let gap = 123_456_789_000;
            capture(&source.iter().map(|&(t, v)| (if t >= at { t + gap } else { t }, v)).collect::<Vec<_>>())
        };
        // Ten lines after the vertical sync: in the back porch.
        let mut cap = paused(vs + 10 * line + 300 * pixel);
        let f = cap.take();
        assert_eq!(f.len(), 1);
        assert!(f[0].pixels.iter().enumerate().all(|(k, &p)| p == pattern(k as u32 / 640, k as u32 % 640)));
        // In row 100 of the picture.
        let mut cap = paused(vs + (35 + 100) as u64 * line + 300 * pixel);
        assert!(cap.take().is_empty());
        assert_eq!(cap.unknown, 1);
    }

    /// A timing generator that counts to its totals inclusively (`== 1344` wraps after 1345
    /// pixels, `>= 806` after 807 lines) and tests its syncs inclusively too (a pixel and a
    /// line longer): a monitor shows it, and so does the capture, every pixel in its place.
    #[test]
    fn a_generator_counting_one_more_pixel_and_line_is_shown_as_its_mode() {
        let pattern = |r: u32, c: u32| ((r * 7 + c * 3) % 4096) as u16;
        for (mode, pixel) in [
            (Mode { h_sync: 137, v_sync: 7, ..MODE_1024 }, 15_385),
            (Mode { h_sync: 97, v_sync: 3, ..MODE_640 }, 40_000),
            // One more line and pixel in the front porches.
            (Mode { h_front: 17, v_front: 11, ..MODE_640 }, 40_000),
        ] {
            let mut cap = capture(&frames(&mode, pixel, pattern, 2));
            let f = cap.take();
            assert_eq!((f.len(), cap.unknown), (2, 0), "{mode:?}");
            let (w, h) = (mode.width, mode.height);
            assert_eq!((f[1].width, f[1].height), (w, h));
            for (k, &p) in f[1].pixels.iter().enumerate() {
                let (r, c) = (k as u32 / w, k as u32 % w);
                assert_eq!(p, pattern(r, c), "{mode:?}: row {r} col {c}");
            }
        }
    }

    #[test]
    fn an_unknown_line_count_is_no_frame() {
        let mode = Mode { height: 400, ..MODE_640 };
        let mut cap = capture(&frames(&mode, 40_000, |_, _| 0, 2));
        assert!(cap.take().is_empty());
        assert_eq!(cap.unknown, 2);
    }
}
