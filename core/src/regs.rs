//! BotSim 2.0's register encodings as types (spec/botsim.md §3): motor control, heading,
//! movement, sensors, and the snapshot published at each upd_sysregs pulse.
//!
//! ```
//! use botsim_core::regs::{MotCtl, Movement, Orientation};
//! assert_eq!(MotCtl::FORWARD.movement(), Movement::Forward);
//! assert_eq!(MotCtl(0x44).movement(), Movement::Stopped); // speed bits 7,6,3,2 are ignored
//! assert_eq!(Orientation::East.turned(Movement::SlowRight), Orientation::SouthEast);
//! assert_eq!("fast-left".parse::<MotCtl>().unwrap(), MotCtl(0x23));
//! ```

use std::fmt;
use std::str::FromStr;

/// `MotCtl_in`: `{LMSpd[2:0], LMDir, RMSpd[2:0], RMDir}`. BotSim 2.0 uses only the speed
/// LSBs (bits 5 and 1) as motor on/off; a direction bit is 1 for forward.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct MotCtl(pub u8);

impl MotCtl {
    pub const STOP: MotCtl = MotCtl(0x00);
    pub const FORWARD: MotCtl = MotCtl(0x33);
    pub const REVERSE: MotCtl = MotCtl(0x22);
    /// Right wheel forward only: 45 degrees counter-clockwise per threshold event.
    pub const SLOW_LEFT: MotCtl = MotCtl(0x03);
    /// Left wheel forward only.
    pub const SLOW_RIGHT: MotCtl = MotCtl(0x30);
    /// Left reverse, right forward: 90 degrees counter-clockwise per event.
    pub const FAST_LEFT: MotCtl = MotCtl(0x23);
    /// Left forward, right reverse.
    pub const FAST_RIGHT: MotCtl = MotCtl(0x32);

    /// The named commands, as accepted in motor scripts.
    pub const NAMED: [(&'static str, MotCtl); 7] = [
        ("stop", MotCtl::STOP),
        ("forward", MotCtl::FORWARD),
        ("reverse", MotCtl::REVERSE),
        ("slow-left", MotCtl::SLOW_LEFT),
        ("slow-right", MotCtl::SLOW_RIGHT),
        ("fast-left", MotCtl::FAST_LEFT),
        ("fast-right", MotCtl::FAST_RIGHT),
    ];

    pub fn left_on(self) -> bool {
        self.0 & 0x20 != 0
    }
    pub fn right_on(self) -> bool {
        self.0 & 0x02 != 0
    }
    pub fn left_forward(self) -> bool {
        self.0 & 0x10 != 0
    }
    pub fn right_forward(self) -> bool {
        self.0 & 0x01 != 0
    }

    /// The movement this motor state makes (spec §4).
    pub fn movement(self) -> Movement {
        match (self.left_on(), self.right_on()) {
            (false, false) => Movement::Stopped,
            (false, true) if self.right_forward() => Movement::SlowLeft,
            (false, true) => Movement::SlowRight,
            (true, false) if self.left_forward() => Movement::SlowRight,
            (true, false) => Movement::SlowLeft,
            (true, true) => match (self.left_forward(), self.right_forward()) {
                (true, true) => Movement::Forward,
                (false, false) => Movement::Reverse,
                (false, true) => Movement::FastLeft,
                (true, false) => Movement::FastRight,
            },
        }
    }
}

/// Parse `33`, `0x33` or a named command (`forward`, `slow-left`, ...).
impl FromStr for MotCtl {
    type Err = String;
    fn from_str(s: &str) -> Result<MotCtl, String> {
        let t = s.trim();
        if let Some((_, m)) = MotCtl::NAMED.iter().find(|(n, _)| n.eq_ignore_ascii_case(t)) {
            return Ok(*m);
        }
        let hex = t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")).unwrap_or(t);
        if hex.len() == 2 {
            if let Ok(v) = u8::from_str_radix(hex, 16) {
                return Ok(MotCtl(v));
            }
        }
        let names: Vec<&str> = MotCtl::NAMED.iter().map(|(n, _)| *n).collect();
        Err(format!("'{t}' is not a MotCtl value (two hex digits, 0xNN, or one of {})", names.join(", ")))
    }
}

impl fmt::Display for MotCtl {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "0x{:02X}", self.0)
    }
}

/// The heading, `BotInfo[2:0]`. Row 0 is the top (North = decreasing Y).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Orientation {
    North = 0,
    NorthEast = 1,
    East = 2,
    SouthEast = 3,
    South = 4,
    SouthWest = 5,
    West = 6,
    NorthWest = 7,
}

impl Orientation {
    pub const ALL: [Orientation; 8] = [
        Orientation::North,
        Orientation::NorthEast,
        Orientation::East,
        Orientation::SouthEast,
        Orientation::South,
        Orientation::SouthWest,
        Orientation::West,
        Orientation::NorthWest,
    ];

    /// From the low three bits.
    pub fn from_bits(b: u8) -> Orientation {
        Orientation::ALL[(b & 7) as usize]
    }

    pub fn bits(self) -> u8 {
        self as u8
    }

    pub fn degrees(self) -> u16 {
        self as u16 * 45
    }

    pub fn name(self) -> &'static str {
        ["N", "NE", "E", "SE", "S", "SW", "W", "NW"][self as usize]
    }

    /// One cell ahead: (dx, dy).
    pub fn step(self) -> (i8, i8) {
        [(0, -1), (1, -1), (1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1)][self as usize]
    }

    /// Rotated by `eighths` steps of 45 degrees clockwise (negative: counter-clockwise).
    pub fn rotated(self, eighths: i8) -> Orientation {
        Orientation::from_bits((self as i8 + eighths).rem_euclid(8) as u8)
    }

    /// The heading after one threshold event of `m` (spec §5.3).
    pub fn turned(self, m: Movement) -> Orientation {
        self.rotated(match m {
            Movement::SlowLeft => -1,
            Movement::FastLeft => -2,
            Movement::SlowRight => 1,
            Movement::FastRight => 2,
            _ => 0,
        })
    }
}

/// The movement, `BotInfo[7:4]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Movement {
    Stopped,
    Forward,
    Reverse,
    SlowLeft,
    FastLeft,
    SlowRight,
    FastRight,
    /// A code BotSim 2.0 never publishes (a defect if seen).
    Invalid(u8),
}

impl Movement {
    pub fn from_code(c: u8) -> Movement {
        match c & 15 {
            0x0 => Movement::Stopped,
            0x4 => Movement::Forward,
            0x8 => Movement::Reverse,
            0xC => Movement::SlowLeft,
            0xD => Movement::FastLeft,
            0xE => Movement::SlowRight,
            0xF => Movement::FastRight,
            other => Movement::Invalid(other),
        }
    }

    pub fn code(self) -> u8 {
        match self {
            Movement::Stopped => 0x0,
            Movement::Forward => 0x4,
            Movement::Reverse => 0x8,
            Movement::SlowLeft => 0xC,
            Movement::FastLeft => 0xD,
            Movement::SlowRight => 0xE,
            Movement::FastRight => 0xF,
            Movement::Invalid(c) => c & 15,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Movement::Stopped => "stopped",
            Movement::Forward => "forward",
            Movement::Reverse => "reverse",
            Movement::SlowLeft => "slow-left",
            Movement::FastLeft => "fast-left",
            Movement::SlowRight => "slow-right",
            Movement::FastRight => "fast-right",
            Movement::Invalid(_) => "invalid",
        }
    }
}

/// `Sensors_reg`: `{000, ProxL, ProxR, BlkLL, BlkLC, BlkLR}`; the line sensors are active low.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Sensors(pub u8);

impl Sensors {
    pub fn prox_left(self) -> bool {
        self.0 & 0x10 != 0
    }
    pub fn prox_right(self) -> bool {
        self.0 & 0x08 != 0
    }
    /// All three line sensors see black (active low: bits 2:0 = 000).
    pub fn on_line(self) -> bool {
        self.0 & 0x07 == 0
    }
    /// `[BlkLL, BlkLC, BlkLR]` as the register holds them (1 = no line).
    pub fn line_bits(self) -> [bool; 3] {
        [self.0 & 4 != 0, self.0 & 2 != 0, self.0 & 1 != 0]
    }
}

/// The six visible registers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Registers {
    pub loc_x: u8,
    pub loc_y: u8,
    pub sensors: u8,
    pub bot_info: u8,
    pub lm_dist: u8,
    pub rm_dist: u8,
}

impl Registers {
    pub fn orientation(&self) -> Orientation {
        Orientation::from_bits(self.bot_info)
    }
    pub fn movement(&self) -> Movement {
        Movement::from_code(self.bot_info >> 4)
    }
}

/// What the bot publishes at one upd_sysregs pulse.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Snapshot {
    /// 0 for the initial dump after reset, k for main-loop iteration k.
    pub sample: u64,
    /// The first cycle in which upd_sysregs is high.
    pub cycle: u64,
    pub regs: Registers,
}

impl Snapshot {
    /// (LocX, LocY) = (column, row).
    pub fn location(&self) -> (u8, u8) {
        (self.regs.loc_x, self.regs.loc_y)
    }
    pub fn orientation(&self) -> Orientation {
        self.regs.orientation()
    }
    pub fn movement(&self) -> Movement {
        self.regs.movement()
    }
    pub fn sensors(&self) -> Sensors {
        Sensors(self.regs.sensors)
    }
    /// (LMDist, RMDist).
    pub fn distances(&self) -> (u8, u8) {
        (self.regs.lm_dist, self.regs.rm_dist)
    }

    /// A counter reached `threshold` in this iteration: a threshold event (spec §5.3 step 7),
    /// whose turn or move shows in the next snapshot.
    pub fn threshold_event(&self, threshold: u8) -> bool {
        self.regs.lm_dist >= threshold || self.regs.rm_dist >= threshold
    }

    /// This snapshot's threshold event was a forward or reverse move that the world refused:
    /// `next` (the following snapshot) shows the same location (the destination cell is an
    /// obstruction, spec §5.3). The one definition of a blocked move.
    ///
    /// ```
    /// use botsim_core::{Registers, Snapshot};
    /// let at = |sample, loc_x, lm_dist| Snapshot { sample, cycle: 0, regs: Registers { loc_x, loc_y: 64, bot_info: 0x42, lm_dist, rm_dist: lm_dist, ..Registers::default() } };
    /// assert!(at(15, 64, 15).move_refused(&at(16, 64, 1), 15)); // forward, event, still at 64
    /// assert!(!at(15, 64, 15).move_refused(&at(16, 65, 1), 15)); // it moved
    /// assert!(!at(14, 64, 14).move_refused(&at(15, 64, 15), 15)); // no event yet
    /// ```
    pub fn move_refused(&self, next: &Snapshot, threshold: u8) -> bool {
        self.threshold_event(threshold)
            && matches!(self.movement(), Movement::Forward | Movement::Reverse)
            && self.location() == next.location()
    }
}

impl fmt::Display for Snapshot {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = &self.regs;
        write!(
            f,
            "sample {} cycle {}: ({}, {}) {} {} sensors {:02X} dist {}/{}",
            self.sample,
            self.cycle,
            r.loc_x,
            r.loc_y,
            self.orientation().name(),
            self.movement().name(),
            r.sensors,
            r.lm_dist,
            r.rm_dist
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_sixteen_motor_states_follow_the_decision_table() {
        // (lm_on, rm_on, lm_dir, rm_dir) -> movement, spec §4; speed bits 7,6,3,2 ignored.
        for v in 0..=255u8 {
            let m = MotCtl(v);
            let want = match (v >> 5 & 1, v >> 1 & 1, v >> 4 & 1, v & 1) {
                (0, 0, _, _) => Movement::Stopped,
                (0, 1, _, 1) => Movement::SlowLeft,
                (0, 1, _, 0) => Movement::SlowRight,
                (1, 0, 1, _) => Movement::SlowRight,
                (1, 0, 0, _) => Movement::SlowLeft,
                (1, 1, 1, 1) => Movement::Forward,
                (1, 1, 0, 0) => Movement::Reverse,
                (1, 1, 0, 1) => Movement::FastLeft,
                _ => Movement::FastRight,
            };
            assert_eq!(m.movement(), want, "{v:02X}");
        }
    }

    #[test]
    fn parse_motctl() {
        assert_eq!("33".parse::<MotCtl>(), Ok(MotCtl(0x33)));
        assert_eq!("0x2a".parse::<MotCtl>(), Ok(MotCtl(0x2A)));
        assert_eq!("SLOW-RIGHT".parse::<MotCtl>(), Ok(MotCtl(0x30)));
        assert!("3".parse::<MotCtl>().is_err());
        assert!("go".parse::<MotCtl>().unwrap_err().contains("forward"));
    }

    #[test]
    fn orientation_turns_wrap() {
        assert_eq!(Orientation::North.turned(Movement::SlowLeft), Orientation::NorthWest);
        assert_eq!(Orientation::West.turned(Movement::FastRight), Orientation::North);
        assert_eq!(Orientation::NorthEast.turned(Movement::FastLeft), Orientation::NorthWest);
        assert_eq!(Orientation::South.turned(Movement::Forward), Orientation::South);
    }
}
