//! What botsim brings to a design, known to every step that decides what a design is
//! (`resolve`), plans its build (`plan`) and writes its Verilog (`wrapper`): botsim's own
//! modules, the Xilinx primitives it models, its helper modules, the shape of a program ROM,
//! a line of the substitution report and a stub's Verilog. Below all of them: no import
//! circle through it.

use super::scan::{Dir, Module};

/// botsim's own modules that replace the user's, with the file each comes from.
pub const OWN_MODULES: [(&str, &str); 5] = [
    ("kcpsm6", "kcpsm6.v"),
    ("bot", "bot.v"),
    ("world_if", "world_if.v"),
    ("map", "map.v"),
    ("world_map", "world_map.v"),
];

/// The Xilinx primitives rtl/board/xilinx.v models, with the output ports of each in the
/// bit order of its `BOTSIM_USED_<NAME>` mask (empty: not a clock manager): buffers, clock
/// managers, and the logic primitives designs instantiate by hand (the KCPSM6 package's UART
/// macros are built of LUTs, flip-flops and shift registers).
pub const PRIMITIVES: [(&str, &[&str]); 34] = [
    ("BUFG", &[]),
    ("BUFH", &[]),
    ("IBUF", &[]),
    ("IBUFG", &[]),
    ("BUFGCE", &[]),
    ("MMCME2_ADV", &["CLKOUT0", "CLKOUT1", "CLKOUT2", "CLKOUT3", "CLKOUT4", "CLKOUT5", "CLKOUT6", "CLKFBOUT"]),
    ("MMCME2_BASE", &["CLKOUT0", "CLKOUT1", "CLKOUT2", "CLKOUT3", "CLKOUT4", "CLKOUT5", "CLKOUT6", "CLKFBOUT"]),
    ("PLLE2_ADV", &["CLKOUT0", "CLKOUT1", "CLKOUT2", "CLKOUT3", "CLKOUT4", "CLKOUT5", "CLKOUT6", "CLKFBOUT"]),
    ("PLLE2_BASE", &["CLKOUT0", "CLKOUT1", "CLKOUT2", "CLKOUT3", "CLKOUT4", "CLKOUT5", "CLKOUT6", "CLKFBOUT"]),
    ("DCM_SP", &["CLK0", "CLK90", "CLK180", "CLK270", "CLK2X", "CLK2X180", "CLKDV", "CLKFX"]),
    ("LUT1", &[]),
    ("LUT2", &[]),
    ("LUT3", &[]),
    ("LUT4", &[]),
    ("LUT5", &[]),
    ("LUT6", &[]),
    ("LUT6_2", &[]),
    ("MUXF7", &[]),
    ("MUXF8", &[]),
    ("MUXCY", &[]),
    ("XORCY", &[]),
    ("CARRY4", &[]),
    ("FD", &[]),
    ("FDE", &[]),
    ("FDR", &[]),
    ("FDS", &[]),
    ("FDRE", &[]),
    ("FDSE", &[]),
    ("FDC", &[]),
    ("FDP", &[]),
    ("FDCE", &[]),
    ("FDPE", &[]),
    ("SRL16E", &[]),
    ("SRLC32E", &[]),
];

/// botsim's own building blocks (rtl/board/xilinx.v, botsim_clkgen.v) that the Verilog it
/// generates for a design (clock cores) instantiates.
pub const HELPERS: [&str; 3] = ["botsim_clkgen", "botsim_lock", "botsim_mmcm"];

/// botsim's own module `name` (one of [`OWN_MODULES`]), as its Verilog declares it.
pub fn own_module(name: &str) -> Option<Module> {
    let text = match name {
        "kcpsm6" => include_str!("../../../rtl/kcpsm6.v"),
        "bot" => include_str!("../../../rtl/bot.v"),
        "world_if" => include_str!("../../../rtl/world_if.v"),
        "map" => include_str!("../../../rtl/map.v"),
        "world_map" => include_str!("../../../rtl/world_map.v"),
        _ => return None,
    };
    super::scan::scan(text).into_iter().find(|m| m.name == name)
}

/// The ports of botsim's own module `name` (one of [`OWN_MODULES`]), as its Verilog declares
/// them (the bot's include `Loc_Y_reg`, the later course files' spelling).
pub fn own_ports(name: &str) -> Vec<String> {
    own_module(name).map(|m| m.ports.iter().map(|p| p.name.clone()).collect()).unwrap_or_default()
}

/// A team's module named like one of botsim's own ([`OWN_MODULES`]) is the course's when
/// every port it declares is one of botsim's, and botsim's replaces it; a port botsim's
/// does not have makes it the team's own (a BotSim 3.1 `bot` with `Bot_Config_reg`, a
/// `world_if` with a configuration port), kept as committed. The first such port.
///
/// ```
/// use botsim_core::frontend::{parts::foreign_port, scan};
/// let m = &scan::scan("module bot(input clk, input [7:0] Bot_Config_reg); endmodule")[0];
/// assert_eq!(foreign_port(m), Some("Bot_Config_reg"));
/// let m = &scan::scan("module bot(input clk, output upd_sysregs); endmodule")[0];
/// assert_eq!(foreign_port(m), None);
/// ```
pub fn foreign_port(m: &Module) -> Option<&str> {
    if !OWN_MODULES.iter().any(|(o, _)| *o == m.name) {
        return None;
    }
    let own = own_ports(&m.name);
    m.ports.iter().map(|p| p.name.as_str()).find(|p| !own.iter().any(|o| o == p))
}

/// The ports by which a module is a bot (BotSim 2.0's, a team's BotSim 3.1, whatever its
/// name): its motor input, its registers, its update flag and its clock. The Y register is
/// `LocY_reg` or `Loc_Y_reg` ([`bot_locy_port`]).
pub const BOT_PORTS: [&str; 6] = ["MotCtl_in", "LocX_reg", "Sensors_reg", "BotInfo_reg", "upd_sysregs", "clk"];

/// The Y-register port of a module with the bot's ports, as it spells it.
pub fn bot_locy_port(m: &Module) -> Option<&str> {
    ["LocY_reg", "Loc_Y_reg"].into_iter().find(|p| m.port(p).is_some())
}

/// Is the module a bot: the bot's ports ([`BOT_PORTS`]; the motor input an input, the
/// registers and the update flag outputs) around a KCPSM6 of its own (a module that only
/// passes a bot's ports through, or the CPU's side of them, is not one)?
pub fn is_bot(m: &Module) -> bool {
    let dir = |p: &str, d: Dir| m.port(p).is_some_and(|p| p.dir == d);
    BOT_PORTS.iter().all(|p| m.port(p).is_some())
        && dir("MotCtl_in", Dir::Input)
        && ["LocX_reg", "BotInfo_reg", "upd_sysregs"].iter().all(|p| dir(p, Dir::Output))
        && bot_locy_port(m).is_some()
        && m.instances.iter().any(|i| i.module == "kcpsm6")
}

/// One line of the substitution report.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Replacement {
    pub module: String,
    /// Where the user's copy is (empty when they have none).
    pub from: String,
    pub with: String,
}

/// The ROM interface of a kcpsm6 program ROM (spec kcpsm6.md 3).
pub fn is_program_rom(m: &Module) -> bool {
    ["address", "instruction", "enable", "clk"].iter().all(|p| m.port(p).is_some())
        && m.port("instruction").is_some_and(|p| p.dir == Dir::Output && (p.width == 18 || p.width == 0))
}

/// What the substitution report says a stub is (a stub's ports are 1-bit inputs on purpose:
/// no width of it is a mistake).
pub const STUB: &str = "a stub (--stub: inputs ignored, outputs 0)";

/// A stub: the module with every port it is connected by, as a 1-bit input, and no logic.
/// The parameters its instances set are declared (and unused), so any instance builds.
pub fn stub(module: &str, ports: &[String], params: &[String]) -> String {
    let named: Vec<&String> = ports.iter().filter(|p| !p.starts_with('#')).collect();
    let list = named.iter().map(|p| format!("    input wire {p}")).collect::<Vec<_>>().join(",\n");
    let params: String = params.iter().map(|p| format!("    parameter {p} = 0;\n")).collect();
    format!(
        "// Generated by botsim board: --stub {module} (ports tied off, no logic).\n\
         /* verilator lint_off UNUSEDSIGNAL */\n\
         /* verilator lint_off UNUSEDPARAM */\n\
         module {module} (\n{list}\n);\n{params}endmodule\n"
    )
}
