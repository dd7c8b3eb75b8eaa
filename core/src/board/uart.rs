//! The USB-UART as the PC sees it (board.md §7): the bytes a design sends on `RsTx`, decoded
//! from the line's changes (8N1: a start bit 0, eight data bits least significant first, a
//! stop bit 1), at a rate given or measured from the design's own transmissions.
//!
//! ```
//! use botsim_core::board::uart::{Rate, UartLine};
//! // 'A' (0x41) at 115200 baud: start, 1 0 0 0 0 0 1 0, stop.
//! let bit = 1_000_000_000_000 / 115_200;
//! let mut line = UartLine::new(Rate::Given(115_200));
//! let levels = [0, 1, 0, 0, 0, 0, 0, 1, 0, 1];
//! for (k, l) in levels.iter().enumerate() {
//!     line.level(1_000_000 + k as u64 * bit, *l == 1);
//! }
//! line.flush(1_000_000 + 20 * bit);
//! assert_eq!(line.text(), "A");
//! ```

/// The rates a measured bit time snaps to when it is within `SNAP` of one.
pub const STANDARD_BAUDS: [u32; 15] =
    [300, 600, 1200, 2400, 4800, 9600, 14400, 19200, 28800, 38400, 57600, 115_200, 230_400, 460_800, 921_600];
/// How close a measured rate must be to a standard one to be taken as it (4 %: a design's
/// divider of a 100 MHz clock is within 0.5 %).
const SNAP: f64 = 0.04;
/// The default rate into the FPGA before the design's own has been measured.
pub const DEFAULT_BAUD: u32 = 115_200;
/// Changes of the line that make a measurement (a few bytes of text).
const MEASURE_EDGES: usize = 24;
/// The shortest low pulse that is a bit: the fastest standard rate's, less [`SNAP`]. A
/// shorter one (the line low for a few clocks while the design comes out of reset) is a
/// glitch, neither a byte nor a measure of the rate.
const SHORTEST_BIT_PS: f64 = PS / (921_600.0 * (1.0 + SNAP));

/// Picoseconds per second.
const PS: f64 = 1e12;

/// How the line's rate is known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rate {
    /// `--uart-baud`.
    Given(u32),
    /// From the design's transmissions (the shortest time between two changes, snapped to a
    /// standard rate when it is near one).
    Measured,
}

/// One byte the design sent: when its start bit began, the byte, and whether its stop bit
/// was 1 (a frame that ends in 0 is a framing error: the rates differ).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Received {
    pub time_ps: u64,
    pub byte: u8,
    pub framed: bool,
}

/// The PC's receiver on `RsTx`.
#[derive(Clone, Debug)]
pub struct UartLine {
    rate: Rate,
    /// The bit time in use (ps), once known.
    bit_ps: Option<f64>,
    /// The line's level and the changes not decoded yet (times in ps).
    level: bool,
    edges: Vec<(u64, bool)>,
    /// Every change's interval so far while measuring (the shortest is the bit), and what it
    /// was before the last change (a glitch's changes are taken back).
    shortest: u64,
    shortest_before: u64,
    seen: usize,
    pub received: Vec<Received>,
}

impl UartLine {
    pub fn new(rate: Rate) -> UartLine {
        let bit_ps = match rate {
            Rate::Given(b) => Some(PS / b.max(1) as f64),
            Rate::Measured => None,
        };
        UartLine {
            rate,
            bit_ps,
            level: true,
            edges: Vec::new(),
            shortest: u64::MAX,
            shortest_before: u64::MAX,
            seen: 0,
            received: Vec::new(),
        }
    }

    /// The rate in use (baud), and whether it was measured; `None` before it is known.
    pub fn baud(&self) -> Option<(u32, bool)> {
        self.bit_ps.map(|b| ((PS / b).round() as u32, self.rate == Rate::Measured))
    }

    /// The line is `high` from `time_ps` on.
    pub fn level(&mut self, time_ps: u64, high: bool) {
        if high == self.level {
            return;
        }
        if let Some(&(last, false)) = self.edges.last() {
            if high && ((time_ps - last) as f64) < SHORTEST_BIT_PS {
                // A glitch: as if the line had stayed high.
                self.edges.pop();
                self.level = true;
                self.seen -= 1;
                self.shortest = self.shortest_before;
                return;
            }
        }
        self.shortest_before = self.shortest;
        if let Some(&(last, _)) = self.edges.last() {
            self.shortest = self.shortest.min(time_ps - last);
        }
        self.level = high;
        self.edges.push((time_ps, high));
        self.seen += 1;
        if self.bit_ps.is_none() && self.seen >= MEASURE_EDGES {
            self.measure();
        }
        self.decode(time_ps, false);
    }

    /// Decode everything that has ended by `now_ps` (the end of a run, a page's update).
    pub fn flush(&mut self, now_ps: u64) {
        if self.bit_ps.is_none() && self.seen >= 2 {
            // The line idle for long after a few changes: what there is measures it.
            let idle = self.edges.last().map_or(0, |&(t, _)| now_ps.saturating_sub(t));
            if idle > 20 * self.shortest {
                self.measure();
            }
        }
        self.decode(now_ps, true);
    }

    fn measure(&mut self) {
        if self.shortest == u64::MAX || self.shortest == 0 {
            return;
        }
        let baud = PS / self.shortest as f64;
        let snapped = STANDARD_BAUDS.iter().map(|&b| b as f64).find(|b| (baud / b - 1.0).abs() <= SNAP);
        self.bit_ps = Some(PS / snapped.unwrap_or(baud));
    }

    /// Decode the frames that have ended by `now` (with `idle`, the line's last level holds
    /// up to `now`; otherwise only frames ended before the last change).
    fn decode(&mut self, now: u64, idle: bool) {
        let Some(bit) = self.bit_ps else { return };
        loop {
            // A frame starts at a falling edge.
            let Some(start) = self.edges.iter().position(|&(_, h)| !h) else {
                self.edges.retain(|_| false);
                return;
            };
            self.edges.drain(..start);
            let t0 = self.edges[0].0;
            let end = t0 + (9.5 * bit) as u64;
            let last = self.edges.last().map_or(t0, |e| e.0);
            if !(end < last || (idle && end <= now)) {
                return;
            }
            // The level at the middle of bit k.
            let at = |k: u32| {
                let t = t0 + ((k as f64 + 0.5) * bit) as u64;
                self.edges.iter().take_while(|e| e.0 <= t).last().map_or(true, |e| e.1)
            };
            let byte = (0..8).fold(0u8, |b, k| b | (at(k + 1) as u8) << k);
            let framed = at(9) && !at(0);
            self.received.push(Received { time_ps: t0, byte, framed });
            // The next frame starts at a falling edge after this one's stop bit began.
            let stop = t0 + (9.0 * bit) as u64;
            let keep = self.edges.iter().position(|e| e.0 > stop).unwrap_or(self.edges.len());
            let level_then = self.edges[..keep].last().map_or(true, |e| e.1);
            self.edges.drain(..keep);
            if !level_then {
                // Still low at the stop bit (a break, or another rate): the next frame
                // starts at the next falling edge after the line rises.
                let rise = self.edges.iter().position(|e| e.1).map_or(self.edges.len(), |p| p + 1);
                self.edges.drain(..rise);
            }
        }
    }

    /// The bytes received as text (bytes that are not printable ASCII, tab, CR or LF as
    /// `\xHH`).
    pub fn text(&self) -> String {
        text(self.received.iter().map(|r| r.byte))
    }

    /// How many frames ended in a 0 stop bit.
    pub fn framing_errors(&self) -> usize {
        self.received.iter().filter(|r| !r.framed).count()
    }

    /// The rate the line's changes suggest (the shortest interval seen), in baud, once any.
    pub fn suggested_baud(&self) -> Option<u32> {
        (self.shortest != u64::MAX && self.shortest > 0).then(|| (PS / self.shortest as f64).round() as u32)
    }
}

/// Bytes as text: printable ASCII, tab, CR and LF as they are, others as `\xHH`.
pub fn text(bytes: impl Iterator<Item = u8>) -> String {
    let mut s = String::new();
    for b in bytes {
        match b {
            b'\t' | b'\n' | b'\r' | 0x20..=0x7E => s.push(b as char),
            _ => s.push_str(&format!("\\x{b:02X}")),
        }
    }
    s
}

/// The bytes of a quoted text as a stimulus file writes it: `\n`, `\r`, `\t`, `\\`, `\"`
/// and `\xHH` escapes.
///
/// ```
/// use botsim_core::board::uart::{quoted, unquote};
/// assert_eq!(unquote("hi\\r\\n\\x07").unwrap(), b"hi\r\n\x07");
/// assert_eq!(quoted(b"a\"b\n\x01"), "\"a\\\"b\\n\\x01\"");
/// ```
pub fn unquote(s: &str) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            let mut b = [0u8; 4];
            out.extend_from_slice(c.encode_utf8(&mut b).as_bytes());
            continue;
        }
        match chars.next() {
            Some('n') => out.push(b'\n'),
            Some('r') => out.push(b'\r'),
            Some('t') => out.push(b'\t'),
            Some('\\') => out.push(b'\\'),
            Some('"') => out.push(b'"'),
            Some('x') => {
                let h: String = chars.by_ref().take(2).collect();
                out.push(u8::from_str_radix(&h, 16).map_err(|_| format!("`\\x{h}`: expected two hexadecimal digits"))?);
            }
            Some(c) => return Err(format!("`\\{c}`: unknown escape (\\n \\r \\t \\\\ \\\" \\xHH)")),
            None => return Err("a `\\` at the end".into()),
        }
    }
    Ok(out)
}

/// `bytes` quoted as [`unquote`] reads it back.
pub fn quoted(bytes: &[u8]) -> String {
    let mut s = String::from("\"");
    for &b in bytes {
        match b {
            b'\n' => s.push_str("\\n"),
            b'\r' => s.push_str("\\r"),
            b'\t' => s.push_str("\\t"),
            b'\\' => s.push_str("\\\\"),
            b'"' => s.push_str("\\\""),
            0x20..=0x7E => s.push(b as char),
            _ => s.push_str(&format!("\\x{b:02X}")),
        }
    }
    s.push('"');
    s
}

/// The clocks of the 100 MHz oscillator per bit at `baud` (rounded).
pub fn clocks_per_bit(baud: u32) -> u32 {
    ((100_000_000.0 / baud.max(1) as f64).round() as u32).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The line's changes for `bytes` sent at `baud` from `t0`, with `gap` idle bits between.
    fn send(line: &mut UartLine, t0: u64, baud: f64, bytes: &[u8], gap: u32) -> u64 {
        let bit = PS / baud;
        let mut k = 0u64;
        for &b in bytes {
            let bits: Vec<bool> =
                std::iter::once(false).chain((0..8).map(|i| b >> i & 1 == 1)).chain(std::iter::once(true)).collect();
            for v in bits {
                line.level(t0 + (k as f64 * bit) as u64, v);
                k += 1;
            }
            k += gap as u64;
        }
        t0 + (k as f64 * bit) as u64
    }

    #[test]
    fn bytes_at_a_given_rate_and_a_measured_one() {
        for (rate, baud) in [(Rate::Given(9600), 9600.0), (Rate::Measured, 115_200.0), (Rate::Measured, 9615.4)] {
            let mut line = UartLine::new(rate);
            let end = send(&mut line, 5_000_000, baud, b"Hello, botsim!\r\n\x00\xFF", 0);
            line.flush(end + 1_000_000_000);
            assert_eq!(line.text(), "Hello, botsim!\r\n\\x00\\xFF", "{rate:?} {baud}");
            assert_eq!(line.framing_errors(), 0);
            let (b, measured) = line.baud().unwrap();
            assert_eq!(measured, rate == Rate::Measured);
            assert_eq!(b, if baud > 100_000.0 { 115_200 } else { 9600 });
        }
    }

    #[test]
    fn a_glitch_at_reset_is_no_byte_and_no_rate() {
        // The line low for 15 clocks of 100 MHz as the design comes out of reset: alone,
        // nothing was sent; before a transmission, the rate is the transmission's.
        let mut line = UartLine::new(Rate::Measured);
        line.level(1_000_000, false);
        line.level(1_150_000, true);
        line.flush(1_000_000_000);
        assert_eq!((line.text(), line.baud()), (String::new(), None));
        let end = send(&mut line, 2_000_000_000, 115_200.0, b"OK", 1);
        line.flush(end + 1_000_000_000);
        assert_eq!((line.text(), line.baud()), ("OK".to_string(), Some((115_200, true))));
        // A given rate too.
        let mut line = UartLine::new(Rate::Given(115_200));
        line.level(0, false);
        line.level(150_000, true);
        line.flush(1_000_000_000);
        assert!(line.received.is_empty(), "{:?}", line.received);
    }

    #[test]
    fn a_wrong_rate_reads_wrong_bytes_and_framing_errors() {
        let mut line = UartLine::new(Rate::Given(115_200));
        let end = send(&mut line, 0, 9600.0, b"UUUU", 3);
        line.flush(end + 1_000_000_000);
        assert_ne!(line.text(), "UUUU");
        assert!(line.framing_errors() > 0 || line.received.len() != 4, "{:?}", line.received);
        assert_eq!(line.suggested_baud().map(|b| (b as f64 / 9600.0 - 1.0).abs() < 0.01), Some(true));
    }

    #[test]
    fn quoting_round_trips() {
        let all: Vec<u8> = (0..=255).collect();
        assert_eq!(unquote(&quoted(&all)[1..quoted(&all).len() - 1]).unwrap(), all);
        assert!(unquote("\\q").unwrap_err().contains("unknown escape"));
        assert_eq!(clocks_per_bit(115_200), 868);
    }
}
