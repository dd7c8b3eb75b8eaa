//! The BotSim firmware (`rtl/bot_pgm.psm`) and the assembly-time choices it takes.
//!
//! ```
//! use botsim_core::firmware::{Compat, Firmware, Timing};
//! let fw = Firmware { threshold: 4, timing: Timing::Fast, compat: Compat::BotSim20 };
//! let image = fw.assemble().unwrap();
//! assert_ne!(image, Firmware::default().assemble().unwrap());
//! ```

use std::path::Path;

use kcpsm6::asm::{assemble_source, Options, Program, RomSize};
use kcpsm6::{Diagnostics, Image};

/// The firmware source, built into the library.
pub const SOURCE: &str = include_str!("../../rtl/bot_pgm.psm");
/// Its path in the repository, for messages.
pub const SOURCE_PATH: &str = "rtl/bot_pgm.psm";

/// The sample interval.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Timing {
    /// About 50 ms at 100 MHz, as on the board: 5,313,006 clocks of busy-wait per sample.
    #[default]
    Hw,
    /// The same behaviour with a 1,722-clock wait: about 2,000 clocks per sample.
    Fast,
}

impl Timing {
    /// The delay constants: (delay_50ms, delay_1ms, delay_40us, delay_1us).
    pub fn delay(self) -> [u8; 4] {
        match self {
            Timing::Hw => [50, 25, 40, 24],
            Timing::Fast => [1, 1, 16, 24],
        }
    }

    /// How long a wait for an upd_sysregs pulse may take before it is an error: two sample
    /// periods plus start-up. Every backend's default budget.
    pub fn update_budget(self) -> u64 {
        match self {
            Timing::Hw => 2 * 5_314_000 + 10_000,
            Timing::Fast => 2 * 3_000 + 10_000,
        }
    }

    pub fn parse(s: &str) -> Option<Timing> {
        match s {
            "hw" => Some(Timing::Hw),
            "fast" => Some(Timing::Fast),
            _ => None,
        }
    }
}

/// Which right-front cell the bot reads when facing SW (spec §7.1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Compat {
    /// The symmetric (X-2, Y+1) that the Theory of Operation's figures imply.
    #[default]
    Symmetric,
    /// The 2014 BotSim 2.0 program's (X-1, Y).
    BotSim20,
}

/// The firmware's assembly-time constants.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Firmware {
    /// Samples per cell moved or per 45-degree step (2014 Part 1: 15, Part 2: 4).
    pub threshold: u8,
    pub timing: Timing,
    pub compat: Compat,
}

impl Default for Firmware {
    fn default() -> Firmware {
        Firmware { threshold: 15, timing: Timing::Hw, compat: Compat::Symmetric }
    }
}

impl Firmware {
    /// The `-D` constants for this choice.
    pub fn defines(&self) -> Vec<(String, String)> {
        let d = self.timing.delay();
        vec![
            ("threshold".into(), format!("{}'d", self.threshold)),
            ("compat_botsim20".into(), if self.compat == Compat::BotSim20 { "01" } else { "00" }.into()),
            ("delay_50ms".into(), format!("{}'d", d[0])),
            ("delay_1ms".into(), format!("{}'d", d[1])),
            ("delay_40us".into(), format!("{}'d", d[2])),
            ("delay_1us".into(), format!("{}'d", d[3])),
        ]
    }

    /// Assemble the built-in firmware with these constants (1K ROM).
    pub fn assemble(&self) -> Result<Image, Diagnostics> {
        self.program(0).map(|p| p.image)
    }

    /// The whole assembly (listing, symbols); `timestamp` feeds the predefined date stamps.
    pub fn program(&self, timestamp: u64) -> Result<Program, Diagnostics> {
        let opts = Options { defines: self.defines(), rom_size: Some(RomSize::K1), timestamp, ..Options::default() };
        assemble_source(Path::new(SOURCE_PATH), SOURCE, &opts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `CONSTANT name, value` of the firmware source.
    fn constant(name: &str) -> String {
        let line = SOURCE.lines().find(|l| l.trim_start().starts_with(&format!("CONSTANT {name},"))).unwrap();
        line.split(',').nth(1).unwrap().split(';').next().unwrap().trim().to_string()
    }

    #[test]
    fn default_is_the_psm_source_as_written() {
        // The defines of Firmware::default() change nothing: the same words as the source alone.
        for (name, value) in Firmware::default().defines() {
            let as_written = kcpsm6::asm::literal8(&constant(&name)).unwrap();
            assert_eq!(kcpsm6::asm::literal8(&value).unwrap(), as_written, "{name}");
        }
        let plain = assemble_source(Path::new(SOURCE_PATH), SOURCE, &Options::default()).unwrap();
        assert_eq!(Firmware::default().assemble().unwrap(), plain.image);
    }
}
