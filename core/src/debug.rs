//! Debugging a KCPSM6 program, the one implementation `botsim board` and `botsim run` share:
//! breakpoints as the command line gives them (`--break`), checked against every instruction
//! the ISS retires and every sample of the bot; where a program counter is in the source; and
//! the signal groups of a waveform's GTKWave save file.
//!
//! ```
//! use botsim_core::debug::{Break, BreakSpec, Breaks};
//! let spec = BreakSpec::parse("port=09:22").unwrap();
//! assert_eq!(spec.kind, Break::Port(0x09, Some(0x22)));
//! let mut breaks = Breaks::default();
//! assert!(breaks.add(&spec, None).unwrap());
//! assert_eq!(breaks.port_writes, [(0x09, Some(0x22), "port=09:22".to_string())]);
//! assert!(BreakSpec::parse("pc=1000").is_err());
//! ```

use kcpsm6::iss::{PortKind, RetireKind, Retired};
use kcpsm6::source::SourceMap;

use crate::board::gtkw::{Format, Signal};
use crate::regs::Snapshot;

/// A breakpoint as given: its text and what it stops at.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BreakSpec {
    pub text: String,
    pub kind: Break,
}

/// What a breakpoint stops at.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Break {
    /// An instruction at this address (`pc=03A`).
    Pc(u16),
    /// An instruction at this label (`label=NAME`), in the program whose source has it.
    Label(String),
    /// An instruction of this source line (`line=FILE.psm:N`).
    Line(String, usize),
    /// An OUTPUT (or OUTPUTK) to this port, of this value or any (`port=0A`, `port=0A:18`).
    Port(u8, Option<u8>),
    /// A condition on the bot's samples (`bot=...`).
    Bot(BotCondition),
}

/// A condition on the bot's samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BotCondition {
    /// The world refused the move of the sample before (`bot=blocked`).
    Blocked,
    /// No line sensor sees the line (`bot=off-line`).
    OffLine,
    /// The sensors read this byte (`bot=sensors:XX`).
    Sensors(u8),
}

impl BotCondition {
    /// Whether sample `s` (after `before`) shows the condition; `threshold`: the firmware's
    /// proximity threshold (what a refused move needs).
    pub fn hit(&self, before: Option<&Snapshot>, s: &Snapshot, threshold: u8) -> bool {
        match self {
            BotCondition::Blocked => before.is_some_and(|b| b.move_refused(s, threshold)),
            BotCondition::OffLine => s.sensors().line_bits() == [true; 3],
            BotCondition::Sensors(v) => s.regs.sensors == *v,
        }
    }
}

impl BreakSpec {
    /// Parse `pc=03A`, `label=NAME`, `line=FILE.psm:N`, `port=0A`, `port=0A:18`,
    /// `bot=blocked`, `bot=off-line` or `bot=sensors:XX`; the error is one line.
    pub fn parse(spec: &str) -> Result<BreakSpec, String> {
        let hex =
            |v: &str| u8::from_str_radix(v, 16).map_err(|_| format!("--break {spec}: `{v}` is not a hexadecimal byte"));
        let (kind, value) = spec
            .split_once('=')
            .ok_or_else(|| format!("--break {spec}: expected pc=, label=, line=, port= or bot="))?;
        let kind = match kind {
            "pc" => Break::Pc(
                u16::from_str_radix(value, 16)
                    .ok()
                    .filter(|&p| p < 0x1000)
                    .ok_or_else(|| format!("--break {spec}: expected a 3-digit hexadecimal address"))?,
            ),
            "label" if !value.is_empty() => Break::Label(value.to_string()),
            "line" => {
                let (file, line) = value
                    .rsplit_once(':')
                    .and_then(|(f, l)| Some((f, l.parse().ok()?)))
                    .ok_or_else(|| format!("--break {spec}: expected line=FILE:LINE"))?;
                Break::Line(file.to_string(), line)
            }
            "port" => match value.split_once(':') {
                Some((p, v)) => Break::Port(hex(p)?, Some(hex(v)?)),
                None => Break::Port(hex(value)?, None),
            },
            "bot" => Break::Bot(match value {
                "blocked" => BotCondition::Blocked,
                "off-line" => BotCondition::OffLine,
                v if v.starts_with("sensors:") => BotCondition::Sensors(hex(&v[8..])?),
                _ => return Err(format!("--break {spec}: expected bot=blocked, bot=off-line or bot=sensors:XX")),
            }),
            _ => return Err(format!("--break {spec}: expected pc=, label=, line=, port= or bot=")),
        };
        Ok(BreakSpec { text: spec.to_string(), kind })
    }

    /// The bot condition, when this is one.
    pub fn bot(&self) -> Option<BotCondition> {
        match self.kind {
            Break::Bot(c) => Some(c),
            _ => None,
        }
    }

    /// Whether this is a bot condition that sample `s` (after `before`) shows.
    pub fn hit(&self, before: Option<&Snapshot>, s: &Snapshot, threshold: u8) -> bool {
        self.bot().is_some_and(|c| c.hit(before, s, threshold))
    }
}

/// Where the bot is at sample `s`, for the line that says a run stopped there:
/// `sample 12, the bot at (64, 70) facing E, forward, sensors 05`.
pub fn sample_state(s: &Snapshot) -> String {
    format!(
        "sample {}, the bot at ({}, {}) facing {}, {}, sensors {:02X}",
        s.sample,
        s.regs.loc_x,
        s.regs.loc_y,
        s.orientation().name(),
        s.movement().name(),
        s.regs.sensors
    )
}

/// One CPU's breakpoints: addresses and port writes, each with its text.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Breaks {
    pub pcs: Vec<(u16, String)>,
    pub port_writes: Vec<(u8, Option<u8>, String)>,
}

impl Breaks {
    /// Add `spec` for a CPU whose program's source is `map` (if known); whether it applies to
    /// that CPU (a label or line its source does not have does not; a bot condition never).
    pub fn add(&mut self, spec: &BreakSpec, map: Option<&SourceMap>) -> Result<bool, String> {
        let at = match &spec.kind {
            Break::Pc(pc) => Some(*pc),
            Break::Label(name) => map.and_then(|m| m.label_address(name)),
            Break::Line(file, line) => map.and_then(|m| m.line_address(file, *line)),
            Break::Port(port, value) => {
                self.port_writes.push((*port, *value, spec.text.clone()));
                return Ok(true);
            }
            Break::Bot(_) => return Ok(false),
        };
        match at {
            Some(pc) => {
                self.pcs.push((pc, spec.text.clone()));
                Ok(true)
            }
            None => Ok(false),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.pcs.is_empty() && self.port_writes.is_empty()
    }

    /// The breakpoint an instruction `r` hits, if any: its address, or its port write.
    pub fn hit(&self, r: &Retired) -> Option<&str> {
        if r.kind != RetireKind::Executed {
            return None;
        }
        if let Some((_, w)) = self.pcs.iter().find(|(pc, _)| *pc == r.pc) {
            return Some(w);
        }
        let p = r.port.filter(|p| p.kind != PortKind::Read)?;
        self.port_writes
            .iter()
            .find(|(port, value, _)| *port == p.port && value.map_or(true, |v| v == p.value))
            .map(|(_, _, w)| w.as_str())
    }
}

/// `pc 00B wait (linefollow.psm:89)`: an address with its label and source line, when known.
pub fn describe_pc(map: Option<&SourceMap>, pc: u16) -> String {
    match map {
        Some(m) => {
            let line = m.line(pc).map_or(String::new(), |l| {
                format!(" ({}:{})", l.file.file_name().map(|n| n.to_string_lossy()).unwrap_or_default(), l.line)
            });
            format!("pc {pc:03X} {}{line}", m.describe(pc))
        }
        None => format!("pc {pc:03X}"),
    }
}

/// The save-file group of one KCPSM6 whose ports are under `at` (`TOP.bot.BOTSIMCPU`) and
/// whose debug signals (Xilinx's names: the instruction's text, the status, the active bank's
/// registers) are under `debug_at`; its address through the `labels` translate filter.
pub fn cpu_signals(at: &str, debug_at: &str, labels: Option<usize>) -> Vec<Signal> {
    let mut v = vec![
        (format!("{at}.address[11:0]"), Format::Hex, labels),
        (format!("{debug_at}.kcpsm6_opcode[1:160]"), Format::Ascii, None),
        (format!("{debug_at}.kcpsm6_status[1:128]"), Format::Ascii, None),
        (format!("{at}.instruction[17:0]"), Format::Hex, None),
    ];
    for r in 0..16 {
        v.push((format!("{debug_at}.sim_s{r:X}[7:0]"), Format::Hex, None));
    }
    for p in ["port_id[7:0]", "out_port[7:0]", "in_port[7:0]"] {
        v.push((format!("{at}.{p}"), Format::Hex, None));
    }
    for p in ["write_strobe", "k_write_strobe", "read_strobe", "interrupt", "interrupt_ack", "sleep", "reset"] {
        v.push((format!("{at}.{p}"), Format::Binary, None));
    }
    v
}

/// The translate filters of the bot's registers: BotInfo as heading and movement, MotCtl as
/// movement (lines of [`crate::board::gtkw::filter_text`]).
pub fn register_filters() -> (String, String) {
    use crate::board::gtkw::filter_text;
    use crate::regs::{MotCtl, Registers};
    let info = filter_text(
        (0..256u32).map(|v| {
            let r = Registers { bot_info: v as u8, ..Registers::default() };
            (v, format!("{}_{}", r.orientation().name(), r.movement().name()))
        }),
        2,
    );
    let motctl = filter_text((0..256u32).map(|v| (v, MotCtl(v as u8).movement().name().to_string())), 2);
    (info, motctl)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_parses_and_bad_ones_say_what_is_expected() {
        let k = |s: &str| BreakSpec::parse(s).map(|b| b.kind);
        assert_eq!(k("pc=03A"), Ok(Break::Pc(0x3A)));
        assert_eq!(k("label=wait"), Ok(Break::Label("wait".into())));
        assert_eq!(k("line=bot_pgm.psm:57"), Ok(Break::Line("bot_pgm.psm".into(), 57)));
        assert_eq!(k("port=0A"), Ok(Break::Port(0x0A, None)));
        assert_eq!(k("bot=sensors:05"), Ok(Break::Bot(BotCondition::Sensors(5))));
        assert_eq!(k("bot=off-line"), Ok(Break::Bot(BotCondition::OffLine)));
        assert_eq!(k("pc=fff"), Ok(Break::Pc(0xFFF)));
        assert_eq!(k("nope"), Err("--break nope: expected pc=, label=, line=, port= or bot=".into()));
        assert_eq!(k("line=x.psm"), Err("--break line=x.psm: expected line=FILE:LINE".into()));
        assert_eq!(k("port=0G"), Err("--break port=0G: `0G` is not a hexadecimal byte".into()));
    }
}
