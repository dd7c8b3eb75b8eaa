//! The board's pins: which port of a user's top module is the clock, the reset button, the
//! buttons, switches, LEDs, the seven-segment display and VGA (spec board.md 1), by the names
//! the course's constraint files use (Nexys4 2014 and 2016, Nexys3, Nexys4 DDR / A7).

use super::scan::{Dir, Module};

/// What a top-level port is wired to in the simulated board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// The 100 MHz oscillator.
    Clock,
    /// The CPU reset button; `active_low` as on the Nexys4.
    Reset {
        active_low: bool,
    },
    /// Push button 0..4 = C, U, D, L, R.
    Button(u8),
    Switches,
    Leds,
    /// `seg[6:0]` = g..a, or `seg[7:0]` with the decimal point in bit 7 (Nexys3).
    Segments,
    /// One segment line (Nexys4 DDR: CA..CG = 0..6).
    Segment(u8),
    DecimalPoint,
    Anodes,
    VgaRed,
    VgaGreen,
    VgaBlue,
    Hsync,
    Vsync,
}

/// Whether a port of no board role named `name` is a line the board holds high while idle
/// (board.md §7): the USB-UART's receive line into the FPGA (`RsRx`, `UART_TXD_IN`) and the
/// PS/2 clock and data (open collector, pulled up). Other ports of no role are held low.
pub fn idle_high(name: &str) -> bool {
    matches!(name.to_ascii_lowercase().as_str(), "rsrx" | "uart_txd_in" | "ps2_clk" | "ps2_data")
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
        Role::Clock | Role::Reset { .. } | Role::Button(_) | Role::Switches => Dir::Input,
        _ => Dir::Output,
    }
}

/// The roles of a top's ports, and the ports with none.
pub type PinMap = (Vec<(String, Role)>, Vec<String>);

/// Map every port of `top` to a role; ports with no role are reported in `unknown` (inputs
/// are tied low, outputs left open). A known name with the wrong direction, or a top with no
/// clock, is an error.
pub fn map(top: &Module) -> Result<PinMap, PinError> {
    let mut roles = Vec::new();
    let mut unknown = Vec::new();
    for p in &top.ports {
        match role(&p.name) {
            Some(r) => {
                if p.dir != expected_dir(r) {
                    return Err(PinError {
                        port: p.name.clone(),
                        reason: format!(
                            "is the board's {} pin, an {}, but `{}` declares it an {}",
                            describe(r),
                            dir_word(expected_dir(r)),
                            top.name,
                            dir_word(p.dir)
                        ),
                    });
                }
                roles.push((p.name.clone(), r));
            }
            None => unknown.push(p.name.clone()),
        }
    }
    if !roles.iter().any(|(_, r)| *r == Role::Clock) {
        return Err(PinError {
            port: top.name.clone(),
            reason: "has no clock input (expected one of clk, clk100, CLK100MHZ)".into(),
        });
    }
    Ok((roles, unknown))
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
    }
}

/// The button names accepted by `--press`, in the order of [`Role::Button`].
pub const BUTTONS: [&str; 5] = ["btnC", "btnU", "btnD", "btnL", "btnR"];
