//! Where a team's constraint file places its top's ports: `LOC` in an ISE `.ucf`,
//! `PACKAGE_PIN` in a Vivado `.xdc`. The package pin, not the port's name, says what a port
//! is on the board (a team may call the USB-UART's lines `uart_rx`/`uart_tx`, or put `led`
//! on the Pmod header); [`super::pins`] uses the name only where no constraint says.
//!
//! The boards' package pins (Nexys3, Nexys4, Nexys4 DDR) are Digilent's published pinouts,
//! the ones the course's constraint files carry (board.md §1).
//!
//! ```
//! use botsim_core::frontend::constraints::{placements, Board, Function};
//! let ucf = "NET \"uart_rx\" LOC = N17 | IOSTANDARD = LVCMOS33;\n# NET \"led<0>\" LOC = U16;\nNet \"sw<3>\" LOC=M8;\n";
//! let p = placements(ucf);
//! assert_eq!((p[0].port.as_str(), p[0].bit, p[0].pin.as_str(), p[0].line), ("uart_rx", None, "N17", 1));
//! assert_eq!((p[1].port.as_str(), p[1].bit), ("sw", Some(3)));
//! assert_eq!(Board::Nexys3.function("N17"), Some(Function::UartRx));
//! let xdc = "set_property -dict { PACKAGE_PIN C4 IOSTANDARD LVCMOS33 } [get_ports { RsRx }];\nset_property PACKAGE_PIN E3 [get_ports clk]\n";
//! let p = placements(xdc);
//! assert_eq!((p[0].port.as_str(), p[0].pin.as_str()), ("RsRx", "C4"));
//! assert_eq!(Board::Nexys4.function(&p[1].pin), Some(Function::Clock));
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::repo::common_depth;
use super::role::Role;
use super::scan::Module;

/// One port (or one bit of it) placed on a package pin, and the line that says so.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Placement {
    pub port: String,
    pub bit: Option<u32>,
    /// The package pin, upper case (`N17`).
    pub pin: String,
    pub line: u32,
}

/// The placements a `.ucf` or `.xdc` text makes (commented lines left out).
pub fn placements(text: &str) -> Vec<Placement> {
    let mut out = Vec::new();
    for (n, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("");
        let lower = line.to_ascii_lowercase();
        let found = if lower.contains("package_pin") {
            xdc_line(line)
        } else if lower.trim_start().starts_with("net") && lower.contains("loc") {
            ucf_line(line)
        } else {
            None
        };
        if let Some((name, pin)) = found {
            let (port, bit) = split_bit(&name);
            out.push(Placement { port, bit, pin: pin.to_ascii_uppercase(), line: n as u32 + 1 });
        }
    }
    out
}

/// `NET "name<3>" LOC = "T10" | ...;` (quotes, spaces and case as teams write them).
fn ucf_line(line: &str) -> Option<(String, String)> {
    let rest = line.trim_start();
    let rest = rest.get(3..)?.trim_start();
    let (name, rest) = if let Some(r) = rest.strip_prefix('"') {
        let end = r.find('"')?;
        (r[..end].to_string(), &r[end + 1..])
    } else {
        let end = rest.find(|c: char| c.is_whitespace() || c == '|' || c == ';').unwrap_or(rest.len());
        (rest[..end].to_string(), &rest[end..])
    };
    let at = rest.to_ascii_lowercase().find("loc")?;
    let after = rest[at + 3..].trim_start().strip_prefix('=')?.trim_start().trim_start_matches('"');
    let pin: String = after.chars().take_while(|c| c.is_ascii_alphanumeric()).collect();
    (!name.is_empty() && !pin.is_empty()).then_some((name, pin))
}

/// `set_property PACKAGE_PIN E3 [get_ports clk]`, or `-dict { PACKAGE_PIN E3 ... } [get_ports { clk }]`.
fn xdc_line(line: &str) -> Option<(String, String)> {
    let at = line.to_ascii_lowercase().find("package_pin")?;
    let pin: String = line[at + 11..].trim_start().chars().take_while(|c| c.is_ascii_alphanumeric()).collect();
    let ports = line.to_ascii_lowercase().find("get_ports")?;
    let rest = line[ports + 9..].trim_start();
    let name: String = if let Some(braced) = rest.strip_prefix('{') {
        braced.split('}').next().unwrap_or("").trim().to_string()
    } else {
        // `[get_ports sw[0]]`: a bracket of the name's own is kept.
        let mut depth = 0;
        rest.chars()
            .take_while(|c| match c {
                '[' => {
                    depth += 1;
                    true
                }
                ']' if depth == 0 => false,
                ']' => {
                    depth -= 1;
                    true
                }
                c => !c.is_whitespace() && *c != ';',
            })
            .collect()
    };
    let name = name.trim_matches('"').to_string();
    (!name.is_empty() && !pin.is_empty()).then_some((name, pin))
}

/// `sw<3>`, `sw[3]` or `sw(3)` → (`sw`, 3).
fn split_bit(name: &str) -> (String, Option<u32>) {
    let name = name.trim().trim_start_matches('\\');
    for (open, close) in [('<', '>'), ('[', ']'), ('(', ')')] {
        if let Some(stripped) = name.strip_suffix(close) {
            if let Some((base, bit)) = stripped.rsplit_once(open) {
                if let Ok(b) = bit.trim().parse() {
                    return (base.trim().to_string(), Some(b));
                }
            }
        }
    }
    (name.to_string(), None)
}

/// The boards of the course.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Board {
    Nexys3,
    Nexys4,
    Nexys4Ddr,
}

/// What a package pin is on the board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Function {
    Clock,
    Reset {
        active_low: bool,
    },
    /// C, U, D, L, R = 0..4.
    Button(u8),
    Switch(u8),
    Led(u8),
    /// Segment a..g = 0..6.
    Segment(u8),
    DecimalPoint,
    Anode(u8),
    Red(u8),
    Green(u8),
    Blue(u8),
    Hsync,
    Vsync,
    UartRx,
    UartTx,
    Ps2Clock,
    Ps2Data,
    AclSck,
    AclMosi,
    AclMiso,
    AclSs,
    AclInt(u8),
    AudioPwm,
    AudioOn,
}

use Function as F;

const NEXYS3: &[(&str, Function)] = &[
    ("V10", F::Clock),
    ("B8", F::Reset { active_low: false }),
    ("A8", F::Button(1)),
    ("C9", F::Button(2)),
    ("C4", F::Button(3)),
    ("D9", F::Button(4)),
    ("T10", F::Switch(0)),
    ("T9", F::Switch(1)),
    ("V9", F::Switch(2)),
    ("M8", F::Switch(3)),
    ("N8", F::Switch(4)),
    ("U8", F::Switch(5)),
    ("V8", F::Switch(6)),
    ("T5", F::Switch(7)),
    ("U16", F::Led(0)),
    ("V16", F::Led(1)),
    ("U15", F::Led(2)),
    ("V15", F::Led(3)),
    ("M11", F::Led(4)),
    ("N11", F::Led(5)),
    ("R11", F::Led(6)),
    ("T11", F::Led(7)),
    ("T17", F::Segment(0)),
    ("T18", F::Segment(1)),
    ("U17", F::Segment(2)),
    ("U18", F::Segment(3)),
    ("M14", F::Segment(4)),
    ("N14", F::Segment(5)),
    ("L14", F::Segment(6)),
    ("M13", F::DecimalPoint),
    ("N16", F::Anode(0)),
    ("N15", F::Anode(1)),
    ("P18", F::Anode(2)),
    ("P17", F::Anode(3)),
    ("U7", F::Red(0)),
    ("V7", F::Red(1)),
    ("N7", F::Red(2)),
    ("P8", F::Green(0)),
    ("T6", F::Green(1)),
    ("V6", F::Green(2)),
    ("R7", F::Blue(1)),
    ("T7", F::Blue(2)),
    ("N6", F::Hsync),
    ("P7", F::Vsync),
    ("N17", F::UartRx),
    ("N18", F::UartTx),
    ("L12", F::Ps2Clock),
    ("J13", F::Ps2Data),
];

/// The pins the two Nexys4 boards share (the clock, the VGA port, the USB-UART, the
/// keyboard, the audio output, the reset button).
const NEXYS4_COMMON: &[(&str, Function)] = &[
    ("E3", F::Clock),
    ("C12", F::Reset { active_low: true }),
    ("A3", F::Red(0)),
    ("B4", F::Red(1)),
    ("C5", F::Red(2)),
    ("A4", F::Red(3)),
    ("C6", F::Green(0)),
    ("A5", F::Green(1)),
    ("B6", F::Green(2)),
    ("A6", F::Green(3)),
    ("B7", F::Blue(0)),
    ("C7", F::Blue(1)),
    ("D7", F::Blue(2)),
    ("D8", F::Blue(3)),
    ("B11", F::Hsync),
    ("B12", F::Vsync),
    ("C4", F::UartRx),
    ("D4", F::UartTx),
    ("F4", F::Ps2Clock),
    ("B2", F::Ps2Data),
    ("A11", F::AudioPwm),
    ("D12", F::AudioOn),
];

const NEXYS4: &[(&str, Function)] = &[
    ("E16", F::Button(0)),
    ("F15", F::Button(1)),
    ("V10", F::Button(2)),
    ("T16", F::Button(3)),
    ("R10", F::Button(4)),
    ("U9", F::Switch(0)),
    ("U8", F::Switch(1)),
    ("R7", F::Switch(2)),
    ("R6", F::Switch(3)),
    ("R5", F::Switch(4)),
    ("V7", F::Switch(5)),
    ("V6", F::Switch(6)),
    ("V5", F::Switch(7)),
    ("U4", F::Switch(8)),
    ("V2", F::Switch(9)),
    ("U2", F::Switch(10)),
    ("T3", F::Switch(11)),
    ("T1", F::Switch(12)),
    ("R3", F::Switch(13)),
    ("P3", F::Switch(14)),
    ("P4", F::Switch(15)),
    ("T8", F::Led(0)),
    ("V9", F::Led(1)),
    ("R8", F::Led(2)),
    ("T6", F::Led(3)),
    ("T5", F::Led(4)),
    ("T4", F::Led(5)),
    ("U7", F::Led(6)),
    ("U6", F::Led(7)),
    ("V4", F::Led(8)),
    ("U3", F::Led(9)),
    ("V1", F::Led(10)),
    ("R1", F::Led(11)),
    ("P5", F::Led(12)),
    ("U1", F::Led(13)),
    ("R2", F::Led(14)),
    ("P2", F::Led(15)),
    ("L3", F::Segment(0)),
    ("N1", F::Segment(1)),
    ("L5", F::Segment(2)),
    ("L4", F::Segment(3)),
    ("K3", F::Segment(4)),
    ("M2", F::Segment(5)),
    ("L6", F::Segment(6)),
    ("M4", F::DecimalPoint),
    ("N6", F::Anode(0)),
    ("M6", F::Anode(1)),
    ("M3", F::Anode(2)),
    ("N5", F::Anode(3)),
    ("N2", F::Anode(4)),
    ("N4", F::Anode(5)),
    ("L1", F::Anode(6)),
    ("M1", F::Anode(7)),
    ("D15", F::AclSck),
    ("B14", F::AclMosi),
    ("D13", F::AclMiso),
    ("C15", F::AclSs),
    ("C16", F::AclInt(1)),
    ("E15", F::AclInt(2)),
];

const NEXYS4_DDR: &[(&str, Function)] = &[
    ("N17", F::Button(0)),
    ("M18", F::Button(1)),
    ("P18", F::Button(2)),
    ("P17", F::Button(3)),
    ("M17", F::Button(4)),
    ("J15", F::Switch(0)),
    ("L16", F::Switch(1)),
    ("M13", F::Switch(2)),
    ("R15", F::Switch(3)),
    ("R17", F::Switch(4)),
    ("T18", F::Switch(5)),
    ("U18", F::Switch(6)),
    ("R13", F::Switch(7)),
    ("T8", F::Switch(8)),
    ("U8", F::Switch(9)),
    ("R16", F::Switch(10)),
    ("T13", F::Switch(11)),
    ("H6", F::Switch(12)),
    ("U12", F::Switch(13)),
    ("U11", F::Switch(14)),
    ("V10", F::Switch(15)),
    ("H17", F::Led(0)),
    ("K15", F::Led(1)),
    ("J13", F::Led(2)),
    ("N14", F::Led(3)),
    ("R18", F::Led(4)),
    ("V17", F::Led(5)),
    ("U17", F::Led(6)),
    ("U16", F::Led(7)),
    ("V16", F::Led(8)),
    ("T15", F::Led(9)),
    ("U14", F::Led(10)),
    ("T16", F::Led(11)),
    ("V15", F::Led(12)),
    ("V14", F::Led(13)),
    ("V12", F::Led(14)),
    ("V11", F::Led(15)),
    ("T10", F::Segment(0)),
    ("R10", F::Segment(1)),
    ("K16", F::Segment(2)),
    ("K13", F::Segment(3)),
    ("P15", F::Segment(4)),
    ("T11", F::Segment(5)),
    ("L18", F::Segment(6)),
    ("H15", F::DecimalPoint),
    ("J17", F::Anode(0)),
    ("J18", F::Anode(1)),
    ("T9", F::Anode(2)),
    ("J14", F::Anode(3)),
    ("P14", F::Anode(4)),
    ("T14", F::Anode(5)),
    ("K2", F::Anode(6)),
    ("U13", F::Anode(7)),
    ("F15", F::AclSck),
    ("F14", F::AclMosi),
    ("E15", F::AclMiso),
    ("D15", F::AclSs),
    ("B13", F::AclInt(1)),
    ("C16", F::AclInt(2)),
];

impl Board {
    pub const ALL: [Board; 3] = [Board::Nexys3, Board::Nexys4, Board::Nexys4Ddr];

    /// Its name in botsim's messages.
    pub fn name(self) -> &'static str {
        match self {
            Board::Nexys3 => "Nexys3",
            Board::Nexys4 => "Nexys4",
            Board::Nexys4Ddr => "Nexys4 DDR",
        }
    }

    /// Every package pin botsim's board models on this board, with what it is.
    pub fn pins(self) -> impl Iterator<Item = (&'static str, Function)> {
        let tables: &[&[(&str, Function)]] = match self {
            Board::Nexys3 => &[NEXYS3],
            Board::Nexys4 => &[NEXYS4_COMMON, NEXYS4],
            Board::Nexys4Ddr => &[NEXYS4_COMMON, NEXYS4_DDR],
        };
        tables.iter().flat_map(|t| t.iter()).copied()
    }

    /// What the package pin `pin` is on this board, if botsim's board has it.
    pub fn function(self, pin: &str) -> Option<Function> {
        self.pins().find(|(p, _)| p.eq_ignore_ascii_case(pin)).map(|(_, f)| f)
    }
}

/// A constraint file and the placements it makes.
pub type ConstraintFile = (PathBuf, Vec<Placement>);

/// The placements of each of `files` (those that cannot be read left out).
pub fn read_all(files: &[PathBuf]) -> Vec<ConstraintFile> {
    files
        .iter()
        .filter_map(|f| std::fs::read(f).ok().map(|b| (f.clone(), placements(&String::from_utf8_lossy(&b)))))
        .filter(|(_, p)| !p.is_empty())
        .collect()
}

/// A constraint file's placements of a top's ports, on the board they fit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Placed {
    pub file: PathBuf,
    pub board: Board,
    /// By port: each placed bit (`None` for a scalar) and its pin.
    pub ports: BTreeMap<String, Vec<Placement>>,
}

impl Placed {
    /// The constraint file among `files` (`.ucf`/`.xdc`) that places the most of `top`'s
    /// ports (then the nearest to `near`, the top's file), on the board whose clock pin it
    /// places the clock on and that knows the most of its pins; `None` when none places one.
    pub fn choose(files: &[ConstraintFile], top: &Module, near: &Path) -> Option<Placed> {
        let mut best: Option<(usize, usize, Placed)> = None;
        for (f, placed) in files {
            let mut ports: BTreeMap<String, Vec<Placement>> = BTreeMap::new();
            for p in placed {
                if let Some(port) = top.ports.iter().find(|tp| tp.name == p.port) {
                    ports.entry(port.name.clone()).or_default().push(p.clone());
                }
            }
            if ports.is_empty() {
                continue;
            }
            let pins: Vec<&Placement> = ports.values().flatten().collect();
            let known = |b: Board| pins.iter().filter(|p| b.function(&p.pin).is_some()).count();
            let clocked = |b: Board| pins.iter().any(|p| b.function(&p.pin) == Some(Function::Clock));
            let Some(board) = Board::ALL.into_iter().filter(|b| clocked(*b)).max_by_key(|b| known(*b)) else {
                continue;
            };
            let canon = |p: &Path| std::fs::canonicalize(p).unwrap_or(p.to_path_buf());
            let depth = common_depth(&canon(f), &canon(near));
            let better = match &best {
                None => true,
                Some((n, d, _)) => (ports.len(), depth) > (*n, *d),
            };
            if better {
                best = Some((ports.len(), depth, Placed { file: f.clone(), board, ports }));
            }
        }
        best.map(|(_, _, p)| p)
    }

    /// The role the constraints give the port `port` of `width` bits from `lsb` up: what its
    /// pins are on the board (`Some(None)`: placed, but on no pin botsim models, or its bits
    /// on pins that are not one vector in order); `None` when no constraint places it.
    pub fn role(&self, port: &str, lsb: u32, width: u32) -> Option<Option<Role>> {
        let placed = self.ports.get(port)?;
        let f = |p: &Placement| self.board.function(&p.pin);
        if width <= 1 && placed.len() == 1 && placed[0].bit.map_or(true, |b| b == lsb) {
            return Some(f(&placed[0]).and_then(scalar));
        }
        Some(vector(placed.iter().map(|p| (p.bit.map(|b| b.saturating_sub(lsb)), f(p))).collect()))
    }
}

/// The role of a one-bit port on the pin of function `f`.
fn scalar(f: Function) -> Option<Role> {
    Some(match f {
        F::Clock => Role::Clock,
        F::Reset { active_low } => Role::Reset { active_low },
        F::Button(n) => Role::Button(n),
        F::Segment(n) => Role::Segment(n),
        F::DecimalPoint => Role::DecimalPoint,
        F::Hsync => Role::Hsync,
        F::Vsync => Role::Vsync,
        F::UartRx => Role::UartRx,
        F::UartTx => Role::UartTx,
        F::Ps2Clock => Role::Ps2Clock,
        F::Ps2Data => Role::Ps2Data,
        F::AclSck => Role::AclSck,
        F::AclMosi => Role::AclMosi,
        F::AclMiso => Role::AclMiso,
        F::AclSs => Role::AclSs,
        F::AclInt(n) => Role::AclInt(n),
        F::AudioPwm => Role::AudioPwm,
        F::AudioOn => Role::AudioOn,
        // One switch, LED, anode or colour bit alone is no role of botsim's board.
        _ => return None,
    })
}

/// The role of a vector whose bits (from its lsb) are on these pins: every bit on the same
/// kind of pin, in order (bit i on switch i; colours and the Nexys3's `seg[7]` = dp aside).
fn vector(bits: Vec<(Option<u32>, Option<Function>)>) -> Option<Role> {
    let mut role = None;
    for (bit, f) in bits {
        let (bit, f) = (bit?, f?);
        let (r, index) = match f {
            F::Switch(i) => (Role::Switches, Some(i)),
            F::Led(i) => (Role::Leds, Some(i)),
            F::Anode(i) => (Role::Anodes, Some(i)),
            F::Segment(i) => (Role::Segments, Some(i)),
            F::DecimalPoint if bit == 7 => (Role::Segments, Some(7)),
            F::Red(_) => (Role::VgaRed, None),
            F::Green(_) => (Role::VgaGreen, None),
            F::Blue(_) => (Role::VgaBlue, None),
            _ => return None,
        };
        if index.is_some_and(|i| i as u32 != bit) || role.is_some_and(|had| had != r) {
            return None;
        }
        role = Some(r);
    }
    role
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend::scan;

    #[test]
    fn ucf_and_xdc_lines_as_teams_write_them() {
        let text = "NET clk100 LOC=V10;\nnet \"btns\"   loc = \"B8\" ;\nNET \"an(2)\" LOC = P18;\n  set_property PACKAGE_PIN U9 [get_ports {sw[0]}]\nset_property -dict {PACKAGE_PIN C12 IOSTANDARD LVCMOS33} [get_ports btnCpuReset]\n#set_property PACKAGE_PIN U8 [get_ports {sw[1]}]\nNET \"x\" IOSTANDARD = LVCMOS33;\n";
        let p: Vec<(String, Option<u32>, String)> =
            placements(text).into_iter().map(|p| (p.port, p.bit, p.pin)).collect();
        let want = [
            ("clk100", None, "V10"),
            ("btns", None, "B8"),
            ("an", Some(2), "P18"),
            ("sw", Some(0), "U9"),
            ("btnCpuReset", None, "C12"),
        ];
        assert_eq!(p.len(), want.len(), "{p:?}");
        for ((port, bit, pin), (wp, wb, wpin)) in p.iter().zip(want) {
            assert_eq!((port.as_str(), *bit, pin.as_str()), (wp, wb, wpin));
        }
    }

    #[test]
    fn the_pins_decide_the_role_whatever_the_names() {
        let dir = tempfile::tempdir().unwrap();
        let top = &scan::scan(
            "module top(input clk100, input uart_rx, output uart_tx, output [7:0] lights, input [7:0] led, output [3:0] digits_on);\nendmodule\n",
        )[0];
        let ucf = dir.path().join("top.ucf");
        let mut text =
            String::from("NET \"clk100\" LOC = V10;\nNET \"uart_rx\" LOC = N17;\nNET \"uart_tx\" LOC = N18;\n");
        for (i, pin) in ["U16", "V16", "U15", "V15", "M11", "N11", "R11", "T11"].iter().enumerate() {
            text.push_str(&format!("NET \"lights<{i}>\" LOC = {pin};\n"));
        }
        // `led` on the Pmod header: not the LEDs.
        text.push_str("NET \"led<0>\" LOC = T12;\n");
        // Anodes out of order: not the display's.
        for (i, pin) in ["N15", "N16", "P18", "P17"].iter().enumerate() {
            text.push_str(&format!("NET \"digits_on<{i}>\" LOC = {pin};\n"));
        }
        std::fs::write(&ucf, text).unwrap();
        let other = dir.path().join("ip.xdc");
        std::fs::write(&other, "create_clock -period 10 [get_ports clk]\n").unwrap();
        let files = read_all(&[other, ucf.clone()]);
        assert_eq!(files.len(), 1, "a file that places nothing is left out");
        let placed = Placed::choose(&files, top, &dir.path().join("top.v")).unwrap();
        assert_eq!((placed.board, placed.file.as_path()), (Board::Nexys3, ucf.as_path()));
        assert_eq!(placed.role("uart_rx", 0, 1), Some(Some(Role::UartRx)));
        assert_eq!(placed.role("uart_tx", 0, 1), Some(Some(Role::UartTx)));
        assert_eq!(placed.role("clk100", 0, 1), Some(Some(Role::Clock)));
        assert_eq!(placed.role("lights", 0, 8), Some(Some(Role::Leds)));
        assert_eq!(placed.role("led", 0, 8), Some(None));
        assert_eq!(placed.role("digits_on", 0, 4), Some(None));
        assert_eq!(placed.role("nothing", 0, 1), None);
    }

    #[test]
    fn each_board_has_each_pin_once() {
        for b in Board::ALL {
            let mut seen = std::collections::BTreeSet::new();
            for (pin, f) in b.pins() {
                assert!(seen.insert(pin), "{} {pin} twice", b.name());
                assert_eq!(b.function(pin), Some(f));
            }
        }
    }

    #[test]
    fn the_same_pin_is_another_function_on_another_board() {
        assert_eq!(Board::Nexys3.function("N17"), Some(Function::UartRx));
        assert_eq!(Board::Nexys4Ddr.function("N17"), Some(Function::Button(0)));
        assert_eq!(Board::Nexys4.function("n17"), None);
    }
}
