//! The board's pins: which port of a user's top module is the clock, the reset button, the
//! buttons, switches, LEDs, the seven-segment display and VGA (spec board.md 1), and the
//! peripherals of final projects: the USB-UART, the keyboard (PS/2), the accelerometer and the
//! audio output (board.md §7), by the names the course's constraint files use (Nexys4 2014 and
//! 2016, Nexys3, Nexys4 DDR / A7).

use super::constraints::Placed;
pub use super::role::{Peripheral, Role};
use super::scan::{Dir, Module};

/// The peripherals the pins reach, each with its pins' names, in the order of [`Peripheral`].
///
/// ```
/// use botsim_core::frontend::pins::{peripherals, role, Peripheral};
/// let pins: Vec<(String, _)> = ["RsTx", "clk", "PS2_CLK"].iter().map(|n| (n.to_string(), role(n).unwrap())).collect();
/// let p = peripherals(&pins);
/// assert_eq!(p, [(Peripheral::Uart, vec!["RsTx".to_string()]), (Peripheral::Keyboard, vec!["PS2_CLK".to_string()])]);
/// ```
pub fn peripherals(pins: &[(String, Role)]) -> Vec<(Peripheral, Vec<String>)> {
    let mut out: std::collections::BTreeMap<Peripheral, Vec<String>> = Default::default();
    for (name, r) in pins {
        if let Some(p) = r.peripheral() {
            out.entry(p).or_default().push(name.clone());
        }
    }
    out.into_iter().collect()
}

/// The role of a port named `name`, if it is one of the board's pins (in any case: `CLK`,
/// `Led` and `BTNC` are the same pins as `clk`, `led` and `btnC`).
pub fn role(name: &str) -> Option<Role> {
    Some(match name.to_ascii_lowercase().as_str() {
        "clk" | "clk100" | "clk100mhz" | "clk_100mhz" | "sysclk" => Role::Clock,
        "btncpureset" | "cpu_resetn" | "btncpureset_n" => Role::Reset { active_low: true },
        "btns" | "btncpureset_p" => Role::Reset { active_low: false },
        "btnc" => Role::Button(0),
        "btnu" => Role::Button(1),
        "btnd" => Role::Button(2),
        "btnl" => Role::Button(3),
        "btnr" => Role::Button(4),
        "sw" | "switches" => Role::Switches,
        "led" | "leds" => Role::Leds,
        "seg" => Role::Segments,
        "ca" => Role::Segment(0),
        "cb" => Role::Segment(1),
        "cc" => Role::Segment(2),
        "cd" => Role::Segment(3),
        "ce" => Role::Segment(4),
        "cf" => Role::Segment(5),
        "cg" => Role::Segment(6),
        "dp" => Role::DecimalPoint,
        "an" => Role::Anodes,
        "vgared" | "vga_red" | "vga_r" => Role::VgaRed,
        "vgagreen" | "vga_green" | "vga_g" => Role::VgaGreen,
        "vgablue" | "vga_blue" | "vga_b" => Role::VgaBlue,
        "hsync" | "vga_hsync" | "vga_hs" => Role::Hsync,
        "vsync" | "vga_vsync" | "vga_vs" => Role::Vsync,
        "rsrx" | "uart_txd_in" => Role::UartRx,
        "rstx" | "uart_rxd_out" => Role::UartTx,
        "ps2_clk" | "ps2clk" => Role::Ps2Clock,
        "ps2_data" | "ps2data" => Role::Ps2Data,
        "aclsck" | "acl_sclk" => Role::AclSck,
        "aclmosi" | "acl_mosi" => Role::AclMosi,
        "aclmiso" | "acl_miso" => Role::AclMiso,
        "aclss" | "acl_csn" => Role::AclSs,
        "aclint1" => Role::AclInt(1),
        "aclint2" => Role::AclInt(2),
        "acl_int" => Role::AclInt(0),
        "amppwm" | "aud_pwm" => Role::AudioPwm,
        "ampsd" | "aud_sd" => Role::AudioOn,
        _ => return None,
    })
}

/// A pin mapping problem: the port, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PinError {
    pub port: String,
    pub reason: String,
}

/// The direction each role needs.
fn expected_dir(r: Role) -> Dir {
    match r {
        Role::Clock
        | Role::Reset { .. }
        | Role::Button(_)
        | Role::Switches
        | Role::UartRx
        | Role::Ps2Clock
        | Role::Ps2Data
        | Role::AclMiso
        | Role::AclInt(_) => Dir::Input,
        _ => Dir::Output,
    }
}

/// Whether a port of role `r` may be declared `dir`: as the role needs, or an inout for the
/// open-collector PS/2 lines and the audio line (driven low or left floating).
fn dir_fits(r: Role, dir: Dir) -> bool {
    dir == expected_dir(r) || (dir == Dir::Inout && matches!(r, Role::Ps2Clock | Role::Ps2Data | Role::AudioPwm))
}

/// The roles of a top's ports, the ports with none, and the board pins it declares with the
/// wrong direction.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PinMap {
    pub roles: Vec<(String, Role)>,
    pub unknown: Vec<String>,
    pub misdirected: Vec<Misdirected>,
}

/// A port on a board pin, declared with the other direction (`output aclMISO`): Vivado
/// builds it with a warning, and so does botsim: the port is on no pin (an input reads 0, an
/// output reaches nothing), as on the board.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Misdirected {
    pub port: String,
    pub role: Role,
    pub declared: Dir,
    pub line: u32,
    pub col: u32,
}

impl Misdirected {
    /// What happens, said for the top `top`.
    pub fn message(&self, top: &str) -> String {
        let pin = describe(self.role);
        let consequence = match self.declared {
            Dir::Output => format!(
                "the {pin} line reaches nothing in the design, and the design reads `{}` as what it drives itself (0 where nothing drives it)",
                self.port
            ),
            _ => format!("the design drives nothing to the {pin} pin, and reads `{}` as 0", self.port),
        };
        format!(
            "port `{}` is the board's {pin} pin, an {}, but `{top}` declares it an {} (Vivado builds it with a warning): run as the board would, {consequence}",
            self.port,
            dir_word(expected_dir(self.role)),
            dir_word(self.declared)
        )
    }
}

/// Map every port of `top` to a role: by where the constraint file places it (`placed`),
/// else by its name; ports with no role are reported in `unknown` (inputs are tied low,
/// outputs left open), and so are those declared with the wrong direction (in
/// `misdirected` too). A top with no clock is an error.
pub fn map(top: &Module, placed: Option<&Placed>) -> Result<PinMap, PinError> {
    let mut out = PinMap::default();
    for p in &top.ports {
        let lsb = p.range.map_or(0, |(m, l)| m.min(l).max(0) as u32);
        let by_pin = placed.and_then(|pl| pl.role(&p.name, lsb, p.width));
        match by_pin.unwrap_or_else(|| role(&p.name)) {
            Some(r) if dir_fits(r, p.dir) => out.roles.push((p.name.clone(), r)),
            Some(r) if r != Role::Clock => {
                out.misdirected.push(Misdirected {
                    port: p.name.clone(),
                    role: r,
                    declared: p.dir,
                    line: p.line,
                    col: p.col,
                });
                out.unknown.push(p.name.clone());
            }
            Some(r) => {
                return Err(PinError {
                    port: p.name.clone(),
                    reason: format!(
                        "is the board's {} pin, an {}, but `{}` declares it an {}",
                        describe(r),
                        dir_word(expected_dir(r)),
                        top.name,
                        dir_word(p.dir)
                    ),
                })
            }
            None => out.unknown.push(p.name.clone()),
        }
    }
    if !out.roles.iter().any(|(_, r)| *r == Role::Clock) {
        return Err(PinError {
            port: top.name.clone(),
            reason: "has no clock input (expected one of clk, clk100, CLK100MHZ)".into(),
        });
    }
    Ok(out)
}

fn dir_word(d: Dir) -> &'static str {
    match d {
        Dir::Input => "input",
        Dir::Output => "output",
        Dir::Inout => "inout",
    }
}

fn describe(r: Role) -> &'static str {
    match r {
        Role::Clock => "clock",
        Role::Reset { .. } => "reset button",
        Role::Button(_) => "push button",
        Role::Switches => "switch",
        Role::Leds => "LED",
        Role::Segments | Role::Segment(_) => "seven-segment",
        Role::DecimalPoint => "decimal point",
        Role::Anodes => "anode",
        Role::VgaRed | Role::VgaGreen | Role::VgaBlue | Role::Hsync | Role::Vsync => "VGA",
        Role::UartRx | Role::UartTx => "USB-UART",
        Role::Ps2Clock | Role::Ps2Data => "keyboard (PS/2)",
        Role::AclSck | Role::AclMosi | Role::AclMiso | Role::AclSs | Role::AclInt(_) => "accelerometer",
        Role::AudioPwm | Role::AudioOn => "audio",
    }
}

/// The button names accepted by `--press`, in the order of [`Role::Button`].
pub const BUTTONS: [&str; 5] = ["btnC", "btnU", "btnD", "btnL", "btnR"];
