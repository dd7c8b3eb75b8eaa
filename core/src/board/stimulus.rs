//! The board's inputs over time: the reset button held at power-up, button presses and
//! switch settings, from the command line (`--press btnC@100+50`, `--switches 00FF`) or a
//! stimulus file. Times are simulated: milliseconds by default, or with a unit: `ms`, `us`,
//! `ns`, `s`, or `c` for cycles of the board's 100 MHz clock.
//!
//! The board's peripherals take part too: keys of the keyboard (named as the browser names
//! them, [`Key`]), text sent to the USB-UART, and the board's tilt (in g, as the
//! accelerometer measures it; flat is `0 0 1`).
//!
//! A stimulus file has one action per line, `#` comments:
//!
//! ```text
//! # time    action
//! 100ms     press btnC 50ms     # press btnC for 50 ms (default 100 ms)
//! 250       switches 00FF       # from 250 ms on
//! 30000000c press btnCpuReset 1ms
//! 300ms     key ArrowUp 200ms   # press a key of the keyboard for 200 ms (default 100 ms)
//! 400ms     uart "hello\r\n"    # send text to the design's UART (\n \r \t \\ \" \xHH)
//! 500ms     tilt 0.5 0 0.87     # the board tilted: x, y, z in g
//! ```
//!
//! ```
//! use botsim_core::board::stimulus::{parse_time, Stimulus};
//! assert_eq!(parse_time("2.5").unwrap(), 2_500_000_000);
//! assert_eq!(parse_time("100c").unwrap(), 1_000_000);
//! let s = Stimulus::parse(std::path::Path::new("s.txt"), "1ms press btnU 2ms\n4ms switches 0F\n").unwrap();
//! assert_eq!(s.inputs_at(2_000_000_000), (false, 0b00010, 0));
//! assert_eq!(s.inputs_at(5_000_000_000), (false, 0, 0x0F));
//! ```

use std::path::Path;

use super::keyboard::{self, Key};
use super::uart::{quoted, unquote};
use crate::frontend::pins::BUTTONS;
use crate::frontend::BoardError;

/// The board's tilt: what the accelerometer measures on x, y and z, in mg.
pub type Tilt = [i32; 3];
/// A board lying flat: +1 g on z.
pub const FLAT: Tilt = [0, 0, 1000];

/// A tilt `X,Y,Z` (or with spaces) in g, as `--tilt` and stimulus files take it, within
/// +-8 g (the accelerometer's widest range).
///
/// ```
/// use botsim_core::board::stimulus::parse_tilt;
/// assert_eq!(parse_tilt("0.5,0,-0.866").unwrap(), [500, 0, -866]);
/// assert!(parse_tilt("1,2").is_err());
/// ```
pub fn parse_tilt(s: &str) -> Result<Tilt, String> {
    let v: Vec<&str> = s.split([',', ' ']).filter(|w| !w.is_empty()).collect();
    let bad = || format!("`{s}`: expected a tilt X,Y,Z in g (e.g. 0,0,1 lying flat; within +-8)");
    if v.len() != 3 {
        return Err(bad());
    }
    let mut t = [0; 3];
    for (k, w) in v.iter().enumerate() {
        let g: f64 = w.parse().map_err(|_| bad())?;
        if !g.is_finite() || g.abs() > 8.0 {
            return Err(bad());
        }
        t[k] = (g * 1000.0).round() as i32;
    }
    Ok(t)
}

/// A tilt as [`parse_tilt`] reads it back.
fn tilt_text(t: Tilt) -> String {
    t.iter().map(|&v| format!("{}", v as f64 / 1000.0)).collect::<Vec<_>>().join(" ")
}

/// One key of the keyboard held from `from` to `to` (ps).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct KeyPress {
    pub key: Key,
    pub from: u64,
    pub to: u64,
}

/// Picoseconds per millisecond.
pub const PS_PER_MS: u64 = 1_000_000_000;
/// The reset button is pressed at power-up and released after this long (1 ms).
pub const POWER_ON_RESET_PS: u64 = PS_PER_MS;
/// A press without a duration lasts this long (100 ms).
pub const DEFAULT_PRESS_PS: u64 = 100 * PS_PER_MS;

/// A time with an optional unit, in picoseconds.
pub fn parse_time(s: &str) -> Result<u64, String> {
    let s = s.trim();
    let (num, scale) = if let Some(n) = s.strip_suffix("ms") {
        (n, 1e9)
    } else if let Some(n) = s.strip_suffix("us") {
        (n, 1e6)
    } else if let Some(n) = s.strip_suffix("ns") {
        (n, 1e3)
    } else if let Some(n) = s.strip_suffix('s') {
        (n, 1e12)
    } else if let Some(n) = s.strip_suffix('c') {
        (n, crate::PS_PER_CYCLE as f64)
    } else {
        (s, 1e9)
    };
    match num.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 && v * scale < 1.8e19 => Ok((v * scale).round() as u64),
        _ => Err(format!("`{s}` is not a time (e.g. 100, 100ms, 250us, 2s, 5000000c)")),
    }
}

/// One button press: the bit of `btn` (None: the reset button), from, to (ps).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Press {
    pub button: Option<u8>,
    pub from: u64,
    pub to: u64,
}

fn button(name: &str) -> Result<Option<u8>, String> {
    if name.eq_ignore_ascii_case("btnCpuReset") {
        return Ok(None);
    }
    BUTTONS
        .iter()
        .position(|b| b.eq_ignore_ascii_case(name))
        .map(|b| Some(b as u8))
        .ok_or_else(|| format!("unknown button `{name}` (btnC, btnU, btnD, btnL, btnR, btnCpuReset)"))
}

/// The bit of a push button in the board's `btn` (`btnC` 0 ... `btnR` 4), by name in any
/// case; `None` for any other name (the CPU reset button is not one of them).
pub fn button_bit(name: &str) -> Option<u8> {
    BUTTONS.iter().position(|b| b.eq_ignore_ascii_case(name)).map(|b| b as u8)
}

/// The name of the push button with bit `bit` in the board's `btn`.
pub fn button_name(bit: u8) -> &'static str {
    BUTTONS.get(bit as usize).copied().unwrap_or("btn?")
}

/// `NAME@TIME[+DURATION]`, as `--press` takes it.
pub fn parse_press(s: &str) -> Result<Press, String> {
    let bad = |why: String| format!("--press {s}: {why}");
    let (name, when) =
        s.split_once('@').ok_or_else(|| bad("expected NAME@TIME[+DURATION], e.g. btnC@100+50".into()))?;
    let (at, len) = match when.split_once('+') {
        Some((a, l)) => (parse_time(a).map_err(bad)?, parse_time(l).map_err(bad)?),
        None => (parse_time(when).map_err(bad)?, DEFAULT_PRESS_PS),
    };
    if len == 0 {
        return Err(bad("a press lasts longer than 0".into()));
    }
    Ok(Press { button: button(name).map_err(bad)?, from: at, to: at + len })
}

/// The inputs over a run.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Stimulus {
    pub presses: Vec<Press>,
    /// Switch settings from a time on, in time order; before the first, `initial_switches`.
    pub switches: Vec<(u64, u16)>,
    pub initial_switches: u16,
    /// Keys of the keyboard.
    pub keys: Vec<KeyPress>,
    /// Bytes sent to the design's UART, from a time on (one after another).
    pub uart: Vec<(u64, Vec<u8>)>,
    /// The board's tilt from a time on, in time order; before the first, [`FLAT`].
    pub tilts: Vec<(u64, Tilt)>,
}

impl Stimulus {
    /// Parse a stimulus file; errors carry its file:line:col.
    pub fn parse(path: &Path, text: &str) -> Result<Stimulus, BoardError> {
        let mut s = Stimulus::default();
        for (n, raw) in text.lines().enumerate() {
            // A comment starts at a `#` outside quotes.
            let mut quoted_now = false;
            let mut escaped = false;
            let end = raw
                .char_indices()
                .find(|&(_, c)| {
                    let hash = c == '#' && !quoted_now;
                    if c == '"' && !escaped {
                        quoted_now = !quoted_now;
                    }
                    escaped = c == '\\' && !escaped;
                    hash
                })
                .map_or(raw.len(), |(i, _)| i);
            let line = &raw[..end];
            let words: Vec<(usize, &str)> =
                line.split_whitespace().map(|w| (w.as_ptr() as usize - raw.as_ptr() as usize + 1, w)).collect();
            let Some(&(c0, t)) = words.first() else { continue };
            let at = |col: usize, m: String| BoardError::at(path, n as u32 + 1, col as u32, m);
            let time = parse_time(t).map_err(|m| at(c0, m))?;
            match words.get(1).map(|w| (w.0, w.1.to_ascii_lowercase())) {
                Some((_, ref a)) if a == "press" => {
                    let &(cb, name) =
                        words.get(2).ok_or_else(|| at(c0, "press what? (e.g. `100ms press btnC 50ms`)".into()))?;
                    let len = match words.get(3) {
                        Some(&(cl, l)) => parse_time(l).map_err(|m| at(cl, m))?,
                        None => DEFAULT_PRESS_PS,
                    };
                    s.presses.push(Press { button: button(name).map_err(|m| at(cb, m))?, from: time, to: time + len });
                }
                Some((_, ref a)) if a == "switches" => {
                    let &(cv, v) =
                        words.get(2).ok_or_else(|| at(c0, "switches to what? (e.g. `250ms switches 00FF`)".into()))?;
                    let v = u16::from_str_radix(v.trim_start_matches("0x"), 16)
                        .map_err(|_| at(cv, format!("`{v}`: expected up to four hexadecimal digits")))?;
                    s.switches.push((time, v));
                }
                Some((_, ref a)) if a == "key" => {
                    let &(ck, name) =
                        words.get(2).ok_or_else(|| at(c0, "key what? (e.g. `100ms key KeyA 50ms`)".into()))?;
                    let key = Key::named(name).ok_or_else(|| at(ck, keyboard::unknown(name)))?;
                    let len = match words.get(3) {
                        Some(&(cl, l)) => parse_time(l).map_err(|m| at(cl, m))?,
                        None => DEFAULT_PRESS_PS,
                    };
                    if len == 0 {
                        return Err(at(ck, "a key is held longer than 0".into()));
                    }
                    s.keys.push(KeyPress { key, from: time, to: time + len });
                }
                Some((ca, ref a)) if a == "uart" => {
                    let rest = line[ca - 1 + 4..].trim();
                    let col = ca + 4 + line[ca - 1 + 4..].len() - line[ca - 1 + 4..].trim_start().len();
                    let text = rest
                        .strip_prefix('"')
                        .and_then(|r| r.strip_suffix('"'))
                        .ok_or_else(|| at(col, "uart takes a quoted text (e.g. `400ms uart \"hi\\r\\n\"`)".into()))?;
                    let bytes = unquote(text).map_err(|m| at(col, m))?;
                    s.uart.push((time, bytes));
                }
                Some((ca, ref a)) if a == "tilt" => {
                    let rest = line[ca - 1 + 4..].trim();
                    let t = parse_tilt(rest).map_err(|m| at(ca, m))?;
                    s.tilts.push((time, t));
                }
                Some((ca, ref a)) => {
                    return Err(at(ca, format!("unknown action `{a}` (press, switches, key, uart, tilt)")))
                }
                None => return Err(at(c0, "a time needs an action (press, switches, key, uart, tilt)".into())),
            }
        }
        s.switches.sort_by_key(|&(t, _)| t);
        s.tilts.sort_by_key(|&(t, _)| t);
        s.uart.sort_by_key(|&(t, _)| t);
        Ok(s)
    }

    /// The stimulus as a file that [`Stimulus::parse`] reads back as it is: `# header` first,
    /// times in cycles of the 100 MHz clock (in ns off a cycle boundary); a press still held
    /// (`to` = `u64::MAX`) lasts to `held_until_ps`, one cycle at the least.
    ///
    /// ```
    /// use botsim_core::board::stimulus::{Press, Stimulus};
    /// let s = Stimulus { presses: vec![Press { button: Some(0), from: 20_000, to: u64::MAX }], ..Default::default() };
    /// assert_eq!(s.text(50_000, "a session"), "# a session\n2c press btnC 3c\n");
    /// ```
    pub fn text(&self, held_until_ps: u64, header: &str) -> String {
        let time = |ps: u64| match ps % crate::PS_PER_CYCLE {
            0 => format!("{}c", ps / crate::PS_PER_CYCLE),
            _ => format!("{}.{:03}ns", ps / 1000, ps % 1000),
        };
        let mut lines: Vec<(u64, String)> = Vec::new();
        if self.initial_switches != 0 {
            lines.push((0, format!("0c switches {:04X}", self.initial_switches)));
        }
        for p in &self.presses {
            let name = p.button.map_or("btnCpuReset", button_name);
            let to = if p.to == u64::MAX { held_until_ps.max(p.from + crate::PS_PER_CYCLE) } else { p.to };
            lines.push((p.from, format!("{} press {name} {}", time(p.from), time(to - p.from))));
        }
        for &(t, v) in &self.switches {
            lines.push((t, format!("{} switches {v:04X}", time(t))));
        }
        for k in &self.keys {
            let to = if k.to == u64::MAX { held_until_ps.max(k.from + crate::PS_PER_CYCLE) } else { k.to };
            lines.push((k.from, format!("{} key {} {}", time(k.from), k.key.name, time(to - k.from))));
        }
        for (t, bytes) in &self.uart {
            lines.push((*t, format!("{} uart {}", time(*t), quoted(bytes))));
        }
        for &(t, v) in &self.tilts {
            lines.push((t, format!("{} tilt {}", time(t), tilt_text(v))));
        }
        lines.sort_by_key(|(t, _)| *t);
        let mut out = format!("# {header}\n");
        for (_, l) in lines {
            out.push_str(&l);
            out.push('\n');
        }
        out
    }

    /// Every time at which an input changes (after 0), with the power-on reset's release.
    pub fn change_times(&self) -> Vec<u64> {
        let mut t: Vec<u64> = std::iter::once(POWER_ON_RESET_PS)
            .chain(self.presses.iter().flat_map(|p| [p.from, p.to]))
            .chain(self.switches.iter().map(|&(t, _)| t))
            .chain(self.keys.iter().flat_map(|k| [k.from, k.to]))
            .chain(self.uart.iter().map(|(t, _)| *t))
            .chain(self.tilts.iter().map(|&(t, _)| t))
            .filter(|&t| t > 0 && t != u64::MAX)
            .collect();
        t.sort_unstable();
        t.dedup();
        t
    }

    /// (reset pressed, buttons, switches) at time `t`.
    pub fn inputs_at(&self, t: u64) -> (bool, u8, u16) {
        let mut reset = t < POWER_ON_RESET_PS;
        let mut buttons = 0;
        for p in self.presses.iter().filter(|p| (p.from..p.to).contains(&t)) {
            match p.button {
                Some(b) => buttons |= 1 << b,
                None => reset = true,
            }
        }
        let switches = self.switches.iter().rev().find(|&&(at, _)| at <= t).map_or(self.initial_switches, |&(_, v)| v);
        (reset, buttons, switches)
    }

    /// The scan codes the keyboard sends at `t`: the keys released then, then those pressed.
    pub fn keyboard_at(&self, t: u64) -> Vec<u8> {
        let up = self.keys.iter().filter(|k| k.to == t).flat_map(|k| keyboard::codes(k.key, false));
        let down = self.keys.iter().filter(|k| k.from == t).flat_map(|k| keyboard::codes(k.key, true));
        up.chain(down).collect()
    }

    /// The bytes sent to the UART at `t`.
    pub fn uart_at(&self, t: u64) -> Vec<u8> {
        self.uart.iter().filter(|(at, _)| *at == t).flat_map(|(_, b)| b.iter().copied()).collect()
    }

    /// The board's tilt at `t`.
    pub fn tilt_at(&self, t: u64) -> Tilt {
        self.tilts.iter().rev().find(|&&(at, _)| at <= t).map_or(FLAT, |&(_, v)| v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What `text` writes, `parse` reads back as it was (a held press ended where asked).
    #[test]
    fn a_stimulus_written_reads_back_the_same() {
        let s = Stimulus {
            presses: vec![
                Press { button: None, from: 30_000_000, to: 90_000_000 },
                Press { button: Some(2), from: 1_234_567, to: 2_000_000 },
                Press { button: Some(0), from: 5_000_000_000, to: u64::MAX },
            ],
            switches: vec![(10_000, 0x0030), (7_000_000_010, 0xFF01)],
            initial_switches: 0x8001,
            ..Default::default()
        };
        let back = Stimulus::parse(Path::new("s.txt"), &s.text(6_000_000_000, "round trip")).unwrap();
        let mut want = s.clone();
        want.presses[2].to = 6_000_000_000;
        want.switches.insert(0, (0, 0x8001));
        want.initial_switches = 0;
        assert_eq!(back.inputs_at(0), want.inputs_at(0));
        let (mut a, mut b) = (back.presses.clone(), want.presses.clone());
        a.sort_by_key(|p| p.from);
        b.sort_by_key(|p| p.from);
        assert_eq!((a, &back.switches), (b, &want.switches));
    }

    #[test]
    fn times_presses_and_file_errors_with_their_column() {
        assert_eq!(parse_time("250us").unwrap(), 250_000_000);
        assert_eq!(parse_time("1s").unwrap(), 1_000_000_000_000);
        assert!(parse_time("-1").is_err() && parse_time("soon").is_err());
        assert_eq!(
            parse_press("btnC@100+50").unwrap(),
            Press { button: Some(0), from: 100 * PS_PER_MS, to: 150 * PS_PER_MS }
        );
        assert_eq!(parse_press("btnCpuReset@5000c").unwrap().button, None);
        assert!(parse_press("btnX@1").unwrap_err().contains("unknown button `btnX`"));
        let p = Path::new("stim.txt");
        let e = Stimulus::parse(p, "# start\n10ms press btnQ\n").unwrap_err().to_string();
        assert_eq!(e, "stim.txt:2:12: unknown button `btnQ` (btnC, btnU, btnD, btnL, btnR, btnCpuReset)");
        let e = Stimulus::parse(p, "  10ms  jump\n").unwrap_err().to_string();
        assert_eq!(e, "stim.txt:1:9: unknown action `jump` (press, switches, key, uart, tilt)");
        let e = Stimulus::parse(p, "10ms switches zz\n").unwrap_err().to_string();
        assert_eq!(e, "stim.txt:1:15: `zz`: expected up to four hexadecimal digits");
    }

    #[test]
    fn keys_uart_text_and_tilts_read_back_as_written() {
        let p = Path::new("s.txt");
        let text =
            "1ms key ArrowUp 2ms\n2ms uart \"hi # there\\r\\n\" # a comment\n3ms tilt 0.5, 0, 0.866\n5ms key KeyA\n";
        let s = Stimulus::parse(p, text).unwrap();
        assert_eq!(s.keyboard_at(PS_PER_MS), [0xE0, 0x75]);
        assert_eq!(s.keyboard_at(3 * PS_PER_MS), [0xE0, 0xF0, 0x75]);
        assert_eq!(s.uart_at(2 * PS_PER_MS), b"hi # there\r\n");
        assert_eq!((s.tilt_at(0), s.tilt_at(4 * PS_PER_MS)), (FLAT, [500, 0, 866]));
        assert_eq!(s.change_times(), [1.0, 2.0, 3.0, 5.0, 105.0].map(|ms: f64| (ms * PS_PER_MS as f64) as u64));
        let back = Stimulus::parse(p, &s.text(0, "again")).unwrap();
        assert_eq!((back.keys, back.uart, back.tilts), (s.keys, s.uart, s.tilts));
        for (bad, col, what) in [
            ("1ms key Hyper\n", 9, "unknown key `Hyper`"),
            ("1ms uart hello\n", 10, "uart takes a quoted text"),
            ("1ms uart \"\\q\"\n", 10, "unknown escape"),
            ("1ms tilt 9 0 0\n", 5, "expected a tilt X,Y,Z in g"),
        ] {
            let e = Stimulus::parse(p, bad).unwrap_err().to_string();
            assert!(e.starts_with(&format!("s.txt:1:{col}: ")) && e.contains(what), "{bad}: {e}");
        }
    }

    #[test]
    fn the_reset_is_held_at_power_up_and_inputs_follow_their_times() {
        let s = Stimulus::parse(Path::new("s"), "3ms press btnCpuReset 1ms\n2ms switches 1\n1.5ms press btnR 1ms\n")
            .unwrap();
        assert_eq!(s.inputs_at(0), (true, 0, 0));
        assert_eq!(s.inputs_at(PS_PER_MS), (false, 0, 0));
        assert_eq!(s.inputs_at(2 * PS_PER_MS), (false, 0b10000, 1));
        assert_eq!(s.inputs_at(3 * PS_PER_MS), (true, 0, 1));
        assert_eq!(s.change_times(), [1.0, 1.5, 2.0, 2.5, 3.0, 4.0].map(|ms: f64| (ms * PS_PER_MS as f64) as u64));
    }
}
