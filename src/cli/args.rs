//! Arguments shared by several subcommands, as clap types.

use botsim::{Compat, Firmware, Timing};

/// The firmware's assembly-time constants (`botsim run`, `botsim frame`, `botsim firmware`).
/// Unset options take [`Firmware::default`]'s values.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct FirmwareArgs {
    /// Samples per move or 45-degree turn [default: 15]
    #[arg(long, value_name = "T")]
    pub threshold: Option<u8>,
    /// Sample interval: hw (~50 ms at 100 MHz, as on the board) or fast (~2,000 clocks)
    #[arg(long, value_enum, value_name = "hw|fast")]
    pub timing: Option<TimingArg>,
    /// Behave as the 2014 BotSim 2.0 program (its facing-SW right-front cell)
    #[arg(long, value_enum, value_name = "botsim20")]
    pub compat: Option<CompatArg>,
}

impl FirmwareArgs {
    pub fn firmware(&self) -> Firmware {
        let d = Firmware::default();
        Firmware {
            threshold: self.threshold.unwrap_or(d.threshold),
            timing: self.timing.map_or(d.timing, Timing::from),
            compat: self.compat.map_or(d.compat, Compat::from),
        }
    }

    /// Whether any was given (they only apply to a program assembled from source).
    pub fn any(&self) -> bool {
        self.threshold.is_some() || self.timing.is_some() || self.compat.is_some()
    }
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimingArg {
    Hw,
    Fast,
}

impl From<TimingArg> for Timing {
    fn from(t: TimingArg) -> Timing {
        match t {
            TimingArg::Hw => Timing::Hw,
            TimingArg::Fast => Timing::Fast,
        }
    }
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum CompatArg {
    /// The 2014 BotSim 2.0 program's behaviour.
    Botsim20,
}

impl From<CompatArg> for Compat {
    fn from(_: CompatArg) -> Compat {
        Compat::BotSim20
    }
}

/// What simulates the bot.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BackendKind {
    /// The RTL under Verilator (can write a waveform).
    #[default]
    Rtl,
    /// The instruction-set simulator with cycle-timed models of world_if and map.
    Iss,
    /// Both, every snapshot and port access compared.
    Lockstep,
}

/// A closed-loop driver.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum DriverKind {
    /// The course's black-line follower.
    LineFollow,
}
