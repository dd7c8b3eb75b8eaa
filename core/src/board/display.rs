//! The seven-segment display as a person sees it (spec board.md 1): the design multiplexes
//! eight common-anode digits (`an[i]` low drives digit i; a segment is lit while its `seg`
//! bit is low; `seg[0]` is segment a). Per digit, what is seen is the pattern it showed for
//! the longest time while its anode was low, in its last on-window; a digit not driven for
//! [`FADE_PS`] is dark. The decoder reports a line whenever what is seen changes, from the
//! moment every digit has been refreshed once (or [`FADE_PS`] after the first).
//!
//! ```
//! use botsim_core::board::display::{Display, glyph};
//! assert_eq!(glyph(0b011_1111), '0');
//! let mut d = Display::default();
//! // Digit 0 shows "1" (segments b, c lit) for 1 ms of every 8 ms; the others stay dark.
//! const MS: u64 = 1_000_000_000;
//! for k in 0..5 {
//!     d.pins(k * 8 * MS, 0xFE, !0b000_0110 & 0x7F, true);
//!     d.pins(k * 8 * MS + MS, 0xFF, 0x7F, true);
//! }
//! d.settle(41 * MS);
//! assert_eq!(d.lines().last().unwrap().text, "       1");
//! ```

/// A digit that is not refreshed for this long (20 ms) is dark.
pub const FADE_PS: u64 = 20_000_000_000;

/// The character for a set of lit segments (bit 0 = a ... bit 6 = g): the hexadecimal
/// glyphs, blank, `-`; `?` for any other pattern.
pub fn glyph(lit: u8) -> char {
    const GLYPHS: [(u8, char); 18] = [
        (0b011_1111, '0'),
        (0b000_0110, '1'),
        (0b101_1011, '2'),
        (0b100_1111, '3'),
        (0b110_0110, '4'),
        (0b110_1101, '5'),
        (0b111_1101, '6'),
        (0b000_0111, '7'),
        (0b111_1111, '8'),
        (0b110_1111, '9'),
        (0b111_0111, 'A'),
        (0b111_1100, 'b'),
        (0b011_1001, 'C'),
        (0b101_1110, 'd'),
        (0b111_1001, 'E'),
        (0b111_0001, 'F'),
        (0b000_0000, ' '),
        (0b100_0000, '-'),
    ];
    GLYPHS.iter().find(|(p, _)| *p == lit & 0x7F).map_or('?', |(_, c)| *c)
}

/// What the display showed from `time_ps` on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Line {
    pub time_ps: u64,
    /// Digit 7 (leftmost) to digit 0, each followed by `.` when its decimal point is lit.
    pub text: String,
    /// Lit segments per digit (index = digit), bit 7 the decimal point.
    pub lit: [u8; 8],
}

/// The decoder: feed it every change of the pins.
#[derive(Clone, Debug)]
pub struct Display {
    last_time: u64,
    an: u8,
    seg: u8,
    dp: bool,
    /// Per digit: time shown per pattern in the current on-window.
    window: [Vec<(u8, u64)>; 8],
    seen: [u8; 8],
    refreshed: [Option<u64>; 8],
    first: Option<u64>,
    lines: Vec<Line>,
}

impl Default for Display {
    fn default() -> Display {
        Display {
            last_time: 0,
            an: 0xFF,
            seg: 0x7F,
            dp: true,
            window: Default::default(),
            seen: [0; 8],
            refreshed: [None; 8],
            first: None,
            lines: Vec::new(),
        }
    }
}

impl Display {
    /// The pins changed at `time_ps` to `an`, `seg` (g..a), `dp` (all active low).
    pub fn pins(&mut self, time_ps: u64, an: u8, seg: u8, dp: bool) {
        let held = time_ps.saturating_sub(self.last_time);
        let lit = (!self.seg & 0x7F) | if self.dp { 0 } else { 0x80 };
        for i in 0..8 {
            if self.an >> i & 1 == 0 && held > 0 {
                let w = &mut self.window[i];
                match w.iter_mut().find(|(p, _)| *p == lit) {
                    Some((_, t)) => *t += held,
                    None => w.push((lit, held)),
                }
            }
        }
        let mut ended = false;
        for i in 0..8 {
            let was_on = self.an >> i & 1 == 0;
            let now_on = an >> i & 1 == 0;
            if was_on && !now_on {
                if let Some(&(p, _)) = self.window[i].iter().max_by_key(|(_, t)| *t) {
                    self.seen[i] = p;
                }
                self.window[i].clear();
                self.refreshed[i] = Some(time_ps);
                self.first.get_or_insert(time_ps);
                ended = true;
            }
        }
        self.last_time = time_ps;
        self.an = an;
        self.seg = seg & 0x7F;
        self.dp = dp;
        if ended || self.first.is_some_and(|f| time_ps >= f + FADE_PS) {
            self.report(time_ps);
        }
    }

    /// Call at the end of a run (or any time) to let dark digits fade.
    pub fn settle(&mut self, time_ps: u64) {
        self.pins(time_ps, self.an, self.seg, self.dp);
    }

    fn report(&mut self, time_ps: u64) {
        let Some(first) = self.first else { return };
        let all = self.refreshed.iter().all(Option::is_some);
        if !all && time_ps < first + FADE_PS {
            return;
        }
        let mut lit = [0u8; 8];
        for (i, l) in lit.iter_mut().enumerate() {
            if self.refreshed[i].is_some_and(|t| time_ps < t + FADE_PS) {
                *l = self.seen[i];
            }
        }
        if self.lines.last().is_some_and(|l| l.lit == lit) {
            return;
        }
        let mut text = String::new();
        for i in (0..8).rev() {
            text.push(glyph(lit[i]));
            if lit[i] & 0x80 != 0 {
                text.push('.');
            }
        }
        self.lines.push(Line { time_ps, text, lit });
    }

    /// Every change of what is seen, in order.
    pub fn lines(&self) -> &[Line] {
        &self.lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: u64 = 1_000_000_000;

    /// Drive `text` (8 glyph masks, digit 7 first) for `refreshes` rounds of 1 ms per digit.
    fn drive(d: &mut Display, t: &mut u64, digits: [u8; 8], refreshes: usize) {
        for _ in 0..refreshes {
            for i in 0..8 {
                d.pins(*t, !(1u8 << i), !digits[7 - i] & 0x7F, true);
                *t += MS;
            }
        }
    }

    #[test]
    fn a_multiplexed_display_reads_as_eight_characters_once_refreshed() {
        let mut d = Display::default();
        let mut t = 0;
        let twelve34 = [0, 0, 0, 0, 0b000_0110, 0b101_1011, 0b100_1111, 0b110_0110];
        drive(&mut d, &mut t, twelve34, 3);
        assert_eq!(d.lines().len(), 1, "{:?}", d.lines());
        assert_eq!(d.lines()[0].text, "    1234");
        assert_eq!(d.lines()[0].time_ps, 8 * MS, "the first line once every digit was refreshed");
        let mut next = twelve34;
        next[7] = 0b011_1111;
        drive(&mut d, &mut t, next, 2);
        assert_eq!(d.lines().last().unwrap().text, "    1230");
    }

    #[test]
    fn a_glitch_at_the_anode_edge_is_not_what_is_seen() {
        let mut d = Display::default();
        // Digit 0 shows 8 for 1 ms, but the next digit's pattern appears 10 ns before the anode
        // switches (a driver that updates seg first).
        for k in 0..30u64 {
            let t = k * 2 * MS;
            d.pins(t, 0xFE, 0x00, true);
            d.pins(t + MS - 10_000, 0xFE, !0b000_0110 & 0x7F, true);
            d.pins(t + MS, 0xFD, !0b000_0110 & 0x7F, true);
        }
        d.settle(70 * MS);
        assert_eq!(d.lines().last().unwrap().text, "      18");
    }

    #[test]
    fn decimal_points_and_unknown_patterns() {
        let mut d = Display::default();
        for k in 0..5 {
            d.pins(k * 8 * MS, 0xFE, !0b100_0000 & 0x7F, false);
            d.pins(k * 8 * MS + MS, 0xFF, 0x7F, true);
        }
        d.settle(41 * MS);
        assert_eq!(d.lines().last().unwrap().text, "       -.");
        assert_eq!(glyph(0b100_1001), '?');
    }
}
