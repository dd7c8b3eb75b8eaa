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

/// The decoder's state but its lines ([`Display::repeat`]).
struct State {
    last_time: u64,
    pins: (u8, u8, bool),
    window: [Vec<(u8, u64)>; 8],
    seen: [u8; 8],
    refreshed: [Option<u64>; 8],
    first: Option<u64>,
}

impl State {
    /// This state is `before`'s, `period_ps` later: the same pins, windows and patterns,
    /// every digit refreshed a period later or not at all since.
    fn repeats(&self, before: &State, period_ps: u64) -> bool {
        self.last_time == before.last_time + period_ps
            && self.pins == before.pins
            && self.window == before.window
            && self.seen == before.seen
            && self.first == before.first
            && self.refreshed.iter().zip(&before.refreshed).all(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => *a == *b || *a == b + period_ps,
                (None, None) => true,
                _ => false,
            })
    }
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

    /// The changes `pins` (`(time_ps, an, seg, dp)`: one period of them, `period_ps` long,
    /// already given to [`Display::pins`]) happen `count` more times, each a period after the
    /// last. The same as giving every copy, but without the cost: once a copy changes nothing
    /// a person sees (no line, every digit refreshed as in the copy before, a period later),
    /// the next ones change nothing either, up to the moment a digit no copy refreshes fades
    /// or the first line is due, so the decoder moves on to there at once.
    ///
    /// ```
    /// use botsim_core::board::display::Display;
    /// // Digit 0 shows "1" for 1 ms of every 8 ms, then 100,000 periods more.
    /// const MS: u64 = 1_000_000_000;
    /// let period = [(0, 0xFE, !0b000_0110 & 0x7F, true), (MS, 0xFF, 0x7F, true)];
    /// let (mut fast, mut slow) = (Display::default(), Display::default());
    /// for d in [&mut fast, &mut slow] {
    ///     for &(t, an, seg, dp) in &period {
    ///         d.pins(t, an, seg, dp);
    ///     }
    /// }
    /// fast.repeat(&period, 8 * MS, 100_000);
    /// for j in 1..=100_000 {
    ///     for &(t, an, seg, dp) in &period {
    ///         slow.pins(t + j * 8 * MS, an, seg, dp);
    ///     }
    /// }
    /// fast.settle(800_005 * MS);
    /// slow.settle(800_005 * MS);
    /// assert_eq!(fast.lines(), slow.lines());
    /// assert_eq!(fast.lines().last().unwrap().text, "       1");
    /// ```
    pub fn repeat(&mut self, pins: &[(u64, u8, u8, bool)], period_ps: u64, count: u64) {
        let mut j = 0;
        while j < count {
            let (before, lines) = (self.state(), self.lines.len());
            j += 1;
            for &(t, an, seg, dp) in pins {
                self.pins(t + j * period_ps, an, seg, dp);
            }
            let after = self.state();
            if self.lines.len() != lines || !after.repeats(&before, period_ps) {
                continue;
            }
            // The next copies change nothing until a moment an absolute time decides: a
            // digit no copy refreshes fades, or the first line becomes due.
            let mut critical = u64::MAX;
            for (i, r) in after.refreshed.iter().enumerate() {
                if let Some(r) = *r {
                    if before.refreshed[i] == Some(r) {
                        critical = critical.min(r.saturating_add(FADE_PS));
                    }
                }
            }
            if let Some(f) = self.first {
                if f.saturating_add(FADE_PS) > self.last_time {
                    critical = critical.min(f + FADE_PS);
                }
            }
            // Copies whose changes all come before it (the last change of a copy is its latest).
            let room = critical.saturating_sub(self.last_time).saturating_sub(1) / period_ps.max(1);
            let m = room.min(count - j);
            let by = m * period_ps;
            self.last_time += by;
            for (i, r) in self.refreshed.iter_mut().enumerate() {
                if let Some(r) = r {
                    if before.refreshed[i] != Some(*r) {
                        *r += by;
                    }
                }
            }
            j += m;
        }
    }

    /// Everything but the lines, to compare one copy of a period with the last.
    fn state(&self) -> State {
        State {
            last_time: self.last_time,
            pins: (self.an, self.seg, self.dp),
            window: self.window.clone(),
            seen: self.seen,
            refreshed: self.refreshed,
            first: self.first,
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
    fn a_repeated_period_reads_as_every_copy_given() {
        // Random periods of pin changes (some digits never lit, some lit once; short and
        // long periods, starting before and after the first line is due), repeated whole
        // and given copy by copy: the same lines, to the picosecond.
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = move |n: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % n
        };
        for case in 0..300 {
            let period = 1 + next(30) * MS / 4 + next(1000);
            let changes = 1 + next(12) as usize;
            let mut times: Vec<u64> = (0..changes).map(|_| next(period)).collect();
            times.sort_unstable();
            times.dedup();
            let digits = 1 + next(8) as u32;
            // Half the cases walk the anodes over the digits in turn (each refreshed once a
            // period, as a driver does), the others drive them at random.
            let walk = case % 2 == 0;
            let pins: Vec<(u64, u8, u8, bool)> = times
                .iter()
                .enumerate()
                .map(|(k, &t)| {
                    let an = match (walk, next(4)) {
                        (true, _) => !(1u8 << (k as u32 % digits)),
                        (false, 0) => 0xFF,
                        _ => !(1u8 << next(digits as u64)),
                    };
                    (t, an, next(128) as u8, next(2) == 0)
                })
                .collect();
            let start = next(3) * 9 * MS;
            let count = next(2000);
            let (mut fast, mut slow) = (Display::default(), Display::default());
            for d in [&mut fast, &mut slow] {
                for &(t, an, seg, dp) in &pins {
                    d.pins(start + t, an, seg, dp);
                }
            }
            let shifted: Vec<_> = pins.iter().map(|&(t, a, s, d)| (start + t, a, s, d)).collect();
            fast.repeat(&shifted, period, count);
            for j in 1..=count {
                for &(t, an, seg, dp) in &shifted {
                    slow.pins(t + j * period, an, seg, dp);
                }
            }
            // The board goes on as before after the skip.
            for j in count + 1..count + 4 {
                for d in [&mut fast, &mut slow] {
                    for &(t, an, seg, dp) in &shifted {
                        d.pins(t + j * period, an, seg, dp);
                    }
                }
            }
            let end = start + (count + 5) * period + 25 * MS;
            fast.settle(end);
            slow.settle(end);
            assert_eq!(fast.lines(), slow.lines(), "case {case}: period {period}, {count} copies of {pins:?}");
        }
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
