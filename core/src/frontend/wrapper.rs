//! The Verilog botsim generates around a user's design: `botsim_board`, a top with the same
//! ports for every design (so one C++ harness runs them all), the behavioural ROMs and the
//! stubs.
//!
//! `botsim_board`'s ports: `clk` (the 100 MHz oscillator), `reset_pressed`, `btn[4:0]`
//! (C, U, D, L, R), `sw[15:0]` in; `led[15:0]`, `an[7:0]`, `seg[6:0]` (g..a), `dp`,
//! `vga_r/g/b[3:0]`, `hsync`, `vsync` out (active low where the board's are, and "off" when
//! the design has no such pin); and the substituted bot's `bot_upd`, registers, MotCtl and
//! `bot_cycles` (rising edges of the bot's clock since power-up), read through hierarchical
//! references; the design's other bots' `upd_sysregs` as the bits of `xbot_upd` and their
//! registers and MotCtl packed as `bot_*` are, LocX in the low byte, as `xbot_regs1`..
//! (`MAX_BOTS` in all; 0 where there is none).
//!
//! The peripherals (rtl/board/devices.v, instantiated when the design has their pins): the
//! bytes the host sends to the USB-UART's line into the FPGA and to the keyboard come in
//! through `push_bytes`/`push_n` and a toggle of `uart_push` or `ps2_push` (`*_room`,
//! `*_pending` say when another push fits); `uart_div` is the UART's clocks per bit, `tilt_*`
//! the board's tilt in mg; `lines` are the peripherals' lines as they are on the board, bit
//! 0 up: RsTx, ampPWM, ampSD, RsRx, PS2_CLK, PS2_DATA, aclSCK, aclMOSI, aclMISO, aclSS (each
//! idle when the design has no such pin).

use kcpsm6::asm::RomSize;
use kcpsm6::output::verilog_rom;

use super::pins::{Peripheral, Role};
use super::plan::{BotSite, Plan, MAX_BOTS};

/// The wrapper module's name.
pub const TOP: &str = "botsim_board";

/// The wrapper's board outputs, and what each shows when the design has no such pin
/// (everything dark: the display and VGA syncs are active low).
const OUTPUTS_OFF: [(&str, &str); 13] = [
    ("led", "16'h0000"),
    ("seg", "7'h7F"),
    ("dp", "1'b1"),
    ("an", "8'hFF"),
    ("vga_r", "4'h0"),
    ("vga_g", "4'h0"),
    ("vga_b", "4'h0"),
    ("hsync", "1'b1"),
    ("vsync", "1'b1"),
    ("uart_room", "7'd0"),
    ("uart_pending", "1'b0"),
    ("ps2_room", "7'd0"),
    ("ps2_pending", "1'b0"),
];

/// What a board input pin of `w` bits is connected to.
fn input(role: Role, w: u32) -> Option<String> {
    Some(match role {
        Role::Clock => "clk".into(),
        Role::Reset { active_low: true } => "~reset_pressed".into(),
        Role::Reset { active_low: false } => "reset_pressed".into(),
        Role::Button(b) => format!("btn[{b}]"),
        Role::Switches => format!("sw[{}:0]", w.min(16) - 1),
        Role::UartRx => "uart_line".into(),
        Role::Ps2Clock => "ps2_clk_line".into(),
        Role::Ps2Data => "ps2_data_line".into(),
        Role::AclMiso => "acl_miso".into(),
        Role::AclInt(1) => "acl_int1".into(),
        Role::AclInt(2) => "acl_int2".into(),
        Role::AclInt(_) => "{acl_int2, acl_int1}".into(),
        _ => return None,
    })
}

/// What the user's output wire `u` (`w` bits, a board output pin) drives: (wrapper output,
/// expression). Narrower LEDs are zero-extended; missing anodes are off; VGA colours of
/// fewer than 4 bits are aligned to the most significant bit.
fn drives(role: Role, u: &str, w: u32) -> Vec<(&'static str, String)> {
    let vga = |name: &'static str| {
        let x = if w < 4 { format!("{{{u}, {}'b0}}", 4 - w) } else { format!("{u}[{}:{}]", w - 1, w - 4) };
        vec![(name, x)]
    };
    match role {
        Role::Leds => vec![("led", u.into())],
        Role::Segments if w >= 8 => vec![("seg", format!("{u}[6:0]")), ("dp", format!("{u}[7]"))],
        Role::Segments => vec![("seg", format!("{u}[6:0]"))],
        Role::DecimalPoint => vec![("dp", u.into())],
        Role::Anodes if w < 8 => vec![("an", format!("{{{{{}{{1'b1}}}}, {u}}}", 8 - w))],
        Role::Anodes => vec![("an", format!("{u}[7:0]"))],
        Role::VgaRed => vga("vga_r"),
        Role::VgaGreen => vga("vga_g"),
        Role::VgaBlue => vga("vga_b"),
        Role::Hsync => vec![("hsync", u.into())],
        Role::Vsync => vec![("vsync", u.into())],
        _ => vec![],
    }
}

/// The user's top port (of a plan's `pins`) that a variable of the wrapper (Verilator's
/// name) carries: the wire that connects it (`botsim_board__DOT__user_an`), or a board output
/// it drives (`an`, `led`, `vga_r`); `None` for every other name.
///
/// ```
/// use botsim_core::frontend::pins::Role;
/// use botsim_core::frontend::wrapper::top_port;
/// let pins = vec![("AN".to_string(), Role::Anodes)];
/// assert_eq!(top_port(&pins, "an"), Some("AN"));
/// assert_eq!(top_port(&pins, "botsim_board__DOT__user_AN"), Some("AN"));
/// assert_eq!(top_port(&pins, "led"), None);
/// ```
pub fn top_port<'a>(pins: &'a [(String, Role)], verilator_name: &str) -> Option<&'a str> {
    let wire = verilator_name.strip_prefix("botsim_board__DOT__user_");
    pins.iter().find_map(|(port, role)| {
        let carries = wire == Some(port) || drives(*role, "", 1).iter().any(|(out, _)| *out == verilator_name);
        carries.then_some(port.as_str())
    })
}

/// The Verilog of `botsim_board` for `plan`, with `params` overriding the top's parameters.
pub fn board_top(plan: &Plan, params: &[(String, String)]) -> String {
    let width = |port: &str| plan.widths.get(port).copied().unwrap_or(1).max(1);
    let mut decl = String::new();
    let mut conns = Vec::new();
    let mut driven: Vec<(&str, String)> = Vec::new();
    // Nexys4 DDR style: one port per segment (CA..CG).
    let mut seg_lines: [Option<String>; 7] = Default::default();
    for (port, role) in &plan.pins {
        let w = width(port);
        if let Some(c) = input(*role, w) {
            conns.push(format!(".{port}({c})"));
            continue;
        }
        let u = format!("user_{port}");
        // The audio line driven low or left floating (open drain) reads high when floating.
        let net = if *role == Role::AudioPwm { "tri1" } else { "wire" };
        decl.push_str(&format!("    {net} [{}:0] {u};\n", w - 1));
        conns.push(format!(".{port}({u})"));
        match role {
            Role::Segment(i) => seg_lines[*i as usize] = Some(u),
            _ => driven.extend(drives(*role, &u, w)),
        }
    }
    if seg_lines.iter().any(Option::is_some) {
        let bits: Vec<String> = seg_lines.iter().rev().map(|l| l.clone().unwrap_or_else(|| "1'b1".into())).collect();
        driven.push(("seg", format!("{{{}}}", bits.join(", "))));
    }
    // Ports with no board role: inputs low, outputs open.
    for name in &plan.unknown_pins {
        let w = width(name);
        let conn = if plan.inputs.contains(name) { format!(".{name}({w}'d0)") } else { format!(".{name}()") };
        conns.push(conn);
    }
    let (devices, device_outputs) = devices(plan);
    driven.extend(device_outputs);
    let mut assigns: Vec<String> = driven.iter().map(|(o, x)| format!("assign {o} = {x};")).collect();
    for (out, off) in OUTPUTS_OFF {
        if !driven.iter().any(|(o, _)| *o == out) {
            assigns.push(format!("assign {out} = {off};"));
        }
    }
    let overrides = if params.is_empty() {
        String::new()
    } else {
        format!("#({}) ", params.iter().map(|(n, v)| format!(".{n}({v})")).collect::<Vec<_>>().join(", "))
    };
    format!(
        "// Generated by botsim board for `{top}`: the simulated board around the user's design.\n\
         `timescale 1ns / 1ps\n\
         /* verilator lint_off WIDTH */\n\
         /* verilator lint_off PINMISSING */\n\
         module {TOP} (\n\
         \x20   input  wire        clk,\n\
         \x20   input  wire        reset_pressed,\n\
         \x20   input  wire [ 4:0] btn,\n\
         \x20   input  wire [15:0] sw,\n\
         \x20   output wire [15:0] led,\n\
         \x20   output wire [ 7:0] an,\n\
         \x20   output wire [ 6:0] seg,\n\
         \x20   output wire        dp,\n\
         \x20   output wire [ 3:0] vga_r,\n\
         \x20   output wire [ 3:0] vga_g,\n\
         \x20   output wire [ 3:0] vga_b,\n\
         \x20   output wire        hsync,\n\
         \x20   output wire        vsync,\n\
         \x20   input  wire        uart_push,\n\
         \x20   input  wire        ps2_push,\n\
         \x20   input  wire [ 3:0] push_n,\n\
         \x20   input  wire [63:0] push_bytes,\n\
         \x20   input  wire [31:0] uart_div,\n\
         \x20   input  wire [15:0] tilt_x,\n\
         \x20   input  wire [15:0] tilt_y,\n\
         \x20   input  wire [15:0] tilt_z,\n\
         \x20   output wire [ 9:0] lines,\n\
         \x20   output wire [ 6:0] uart_room,\n\
         \x20   output wire        uart_pending,\n\
         \x20   output wire [ 6:0] ps2_room,\n\
         \x20   output wire        ps2_pending,\n\
         \x20   output wire        bot_upd,\n\
         \x20   output wire [ 7:0] bot_locx,\n\
         \x20   output wire [ 7:0] bot_locy,\n\
         \x20   output wire [ 7:0] bot_info,\n\
         \x20   output wire [ 7:0] bot_sensors,\n\
         \x20   output wire [ 7:0] bot_lmdist,\n\
         \x20   output wire [ 7:0] bot_rmdist,\n\
         \x20   output wire [ 7:0] bot_motctl,\n\
         \x20   output reg  [63:0] bot_cycles,\n\
         \x20   output wire [ 2:0] xbot_upd,\n\
         \x20   output wire [55:0] xbot_regs1,\n\
         \x20   output wire [55:0] xbot_regs2,\n\
         \x20   output wire [55:0] xbot_regs3\n\
         );\n\
         {decl}\
         {devices}\
         \x20   {top} {overrides}user (\n        {conns}\n    );\n\
         \x20   {assigns}\n\
         {bot}\
         \x20   initial bot_cycles = 64'd0;\n\
         \x20   always @(posedge bot_clk) bot_cycles <= bot_cycles + 64'd1;\n\
         endmodule\n",
        top = plan.top,
        bot = bot_taps(plan),
        conns = conns.join(",\n        "),
        devices = devices,
        assigns = assigns.join("\n    "),
    )
}

/// The instances of botsim's peripheral models in the wrapper, with what each is to a user.
const DEVICES: [(&str, &str); 3] = [
    ("uart_in", "the board's USB-UART"),
    ("keyboard", "the board's keyboard"),
    ("accelerometer", "the board's accelerometer"),
];

/// What of botsim's board a variable of the wrapper (Verilator's name) is part of: a
/// peripheral's model or its queue's status, the peripherals' lines; `None` for the user's
/// design and the rest of the wrapper.
///
/// ```
/// use botsim_core::frontend::wrapper::board_part;
/// assert_eq!(board_part("botsim_board__DOT__accelerometer__DOT__since"), Some("the board's accelerometer"));
/// assert_eq!(board_part("uart_room"), Some("the board's USB-UART"));
/// assert_eq!(board_part("botsim_board__DOT__user__DOT__count"), None);
/// ```
pub fn board_part(verilator_name: &str) -> Option<&'static str> {
    let name = verilator_name.strip_prefix("botsim_board__DOT__").unwrap_or(verilator_name);
    if name.starts_with("user__DOT__") {
        return None;
    }
    match name {
        "uart_room" | "uart_pending" | "uart_line" => return Some(DEVICES[0].1),
        "ps2_room" | "ps2_pending" | "ps2_clk_line" | "ps2_data_line" | "kbd_clk_low" | "kbd_data_low" => {
            return Some(DEVICES[1].1)
        }
        "lines" => return Some("the board's peripheral lines"),
        _ => {}
    }
    DEVICES.iter().find(|(inst, _)| name.starts_with(&format!("{inst}__DOT__"))).map(|(_, what)| *what)
}

/// The peripherals the design's pins reach (rtl/board/devices.v), as Verilog before the user's
/// instance, and the wrapper outputs they drive. The PS/2 lines of an inout port are the
/// board's: pulled up, the keyboard and the design each pulling low; of an input port, the
/// keyboard's alone. The accelerometer's inputs a design lacks are idle (select high).
fn devices(plan: &Plan) -> (String, Vec<(&'static str, String)>) {
    let pin = |r: Role| plan.pins.iter().find(|(_, x)| *x == r).map(|(p, _)| p.as_str());
    let has = |p: Peripheral| plan.pins.iter().any(|(_, r)| r.peripheral() == Some(p));
    let mut v = String::new();
    let mut out: Vec<(&'static str, String)> = Vec::new();
    // A device the host feeds bytes: the queue's ports, its status on the wrapper's outputs.
    let mut queue = |name: &'static str, room: &'static str, pending: &'static str, v: &mut String| {
        v.push_str(&format!("    wire [6:0] {name}_room_w;\n    wire {name}_pending_w;\n"));
        out.extend([(room, format!("{name}_room_w")), (pending, format!("{name}_pending_w"))]);
        format!(".push({name}_push), .push_n(push_n), .push_bytes(push_bytes), .room({name}_room_w), .pending({name}_pending_w)")
    };
    if pin(Role::UartRx).is_some() {
        v.push_str("    // The USB-UART bridge's line into the FPGA.\n    wire uart_line;\n");
        let q = queue("uart", "uart_room", "uart_pending", &mut v);
        v.push_str(&format!(
            "    botsim_uart_source {} (.clk(clk), .div(uart_div), {q}, .line(uart_line));\n",
            DEVICES[0].0
        ));
    }
    if has(Peripheral::Keyboard) {
        v.push_str("    // The keyboard, open collector on the board's pulled-up PS/2 lines.\n    wire kbd_clk_low, kbd_data_low;\n");
        for (role, line, low) in
            [(Role::Ps2Clock, "ps2_clk_line", "kbd_clk_low"), (Role::Ps2Data, "ps2_data_line", "kbd_data_low")]
        {
            match pin(role) {
                Some(p) if plan.inouts.contains(p) => {
                    v.push_str(&format!("    tri1 {line};\n    assign {line} = {low} ? 1'b0 : 1'bz;\n"))
                }
                _ => v.push_str(&format!("    wire {line} = !{low};\n")),
            }
        }
        let q = queue("ps2", "ps2_room", "ps2_pending", &mut v);
        v.push_str(&format!(
            "    botsim_ps2_keyboard {} (.clk(clk), {q}, .clk_line(ps2_clk_line), .data_line(ps2_data_line), .clk_low(kbd_clk_low), .data_low(kbd_data_low));\n",
            DEVICES[1].0
        ));
    }
    if has(Peripheral::Accelerometer) {
        let line = |r: Role, idle: &str| pin(r).map_or(idle.to_string(), |p| format!("user_{p}[0]"));
        v.push_str(&format!(
            "    // The accelerometer, tilted as the board is.\n    wire acl_miso, acl_int1, acl_int2;\n    botsim_adxl362 {} (.clk(clk), .sck({}), .mosi({}), .cs_n({}), .miso(acl_miso), .int1(acl_int1), .int2(acl_int2), .x_mg(tilt_x), .y_mg(tilt_y), .z_mg(tilt_z));\n",
            DEVICES[2].0,
            line(Role::AclSck, "1'b0"),
            line(Role::AclMosi, "1'b0"),
            line(Role::AclSs, "1'b1"),
        ));
    }
    // The lines as they are on the board, idle where the design has no pin: an audio line
    // without an amplifier enable has the amplifier on.
    let user = |r: Role, idle: &str| pin(r).map_or(idle.to_string(), |p| format!("user_{p}[0]"));
    let of = |p: Peripheral, line: &str, idle: &str| if has(p) { line.to_string() } else { idle.to_string() };
    let amp_on = if pin(Role::AudioPwm).is_some() { "1'b1" } else { "1'b0" };
    let lines = [
        user(Role::AclSs, "1'b1"),
        of(Peripheral::Accelerometer, "acl_miso", "1'b0"),
        user(Role::AclMosi, "1'b0"),
        user(Role::AclSck, "1'b0"),
        of(Peripheral::Keyboard, "ps2_data_line", "1'b1"),
        of(Peripheral::Keyboard, "ps2_clk_line", "1'b1"),
        if pin(Role::UartRx).is_some() { "uart_line".to_string() } else { "1'b1".to_string() },
        user(Role::AudioOn, amp_on),
        user(Role::AudioPwm, "1'b0"),
        user(Role::UartTx, "1'b1"),
    ];
    out.push(("lines", format!("{{{}}}", lines.join(", "))));
    (v, out)
}

/// The board's view of the bots: the first's registers through hierarchical references to
/// its instance below the user's top, or all 0 (a clock that never ticks) without one; the
/// others' packed, each in its own `xbot_regs`.
fn bot_taps(plan: &Plan) -> String {
    let bots = plan.bots();
    let mut out = String::new();
    match bots.first() {
        None => out.push_str(
            "    // The design has no bot: its outputs are 0 and its clock stands still.\n    wire bot_clk = 1'b0;\n    assign {bot_upd, bot_locx, bot_locy, bot_info, bot_sensors, bot_lmdist, bot_rmdist, bot_motctl} = 57'd0;\n",
        ),
        Some(first) => {
            let r = registers(first);
            out.push_str(&format!(
                "    // {what}, seen through hierarchical references.\n\
                 \x20   wire bot_clk = {clk};\n\
                 \x20   assign bot_upd = {upd};\n\
                 \x20   assign {{bot_motctl, bot_rmdist, bot_lmdist, bot_sensors, bot_info, bot_locy, bot_locx}} = {regs};\n",
                what = r.what,
                clk = r.clk,
                upd = r.upd,
                regs = r.packed,
            ));
        }
    }
    let mut upd = Vec::new();
    for k in 1..MAX_BOTS {
        match bots.get(k) {
            Some(b) => {
                let r = registers(b);
                out.push_str(&format!("    // {}.\n    assign xbot_regs{k} = {};\n", r.what, r.packed));
                upd.push(r.upd);
            }
            None => {
                out.push_str(&format!("    assign xbot_regs{k} = 56'd0;\n"));
                upd.push("1'b0".into());
            }
        }
    }
    upd.reverse();
    out.push_str(&format!("    assign xbot_upd = {{{}}};\n", upd.join(", ")));
    out
}

/// A bot's clock, `upd_sysregs` and registers (MotCtl down to LocX, 56 bits) as the wrapper
/// reads them, and what it is.
struct BotRegisters {
    what: String,
    clk: String,
    upd: String,
    packed: String,
}

fn registers(site: &BotSite) -> BotRegisters {
    let bot = format!("user.{}", site.path);
    let (what, locy, distances) = match &site.team {
        // The team's own bot (a BotSim 3.1 `bot`), seen at its ports.
        Some(t) => (format!("The team's bot `{}` at `{}`", t.module, site.path), t.locy.as_str(), t.has_distances),
        None => (format!("The substituted bot at `{}`", site.path), "loc_y", true),
    };
    let (lm, rm) = if distances {
        (format!("{bot}.LMDist_reg"), format!("{bot}.RMDist_reg"))
    } else {
        ("8'd0".into(), "8'd0".into())
    };
    BotRegisters {
        what,
        clk: format!("{bot}.clk"),
        upd: format!("{bot}.upd_sysregs"),
        packed: format!(
            "{{{bot}.MotCtl_in, {rm}, {lm}, {bot}.Sensors_reg, {bot}.BotInfo_reg, {bot}.{locy}, {bot}.LocX_reg}}"
        ),
    }
}

/// The behavioural ROMs of the plan: (module name, Verilog). Their words are not in the
/// Verilog: each ROM reads them when the model starts from the file named by the run's
/// [`rom_plusarg`], so one build of a design runs any firmware.
pub fn roms(plan: &Plan) -> Vec<(String, String)> {
    plan.roms.iter().map(|r| (r.module.clone(), loaded_rom(&r.module))).collect()
}

/// The plusarg that names the file (`Image::to_hex`) a ROM module reads its words from.
pub fn rom_plusarg(module: &str) -> String {
    format!("botsim_rom_{module}")
}

/// A KCPSM6 program ROM (4K x 18, one clock per read while `enable` is high, the interface of
/// the Xilinx templates: `kcpsm6::output::verilog_rom`'s module) whose words come from the
/// file that `+botsim_rom_<module>=FILE` names; all zero without one.
fn loaded_rom(module: &str) -> String {
    let empty = verilog_rom(&kcpsm6::Image::zeroed(), module, "the run's +botsim_rom file", RomSize::K4, None);
    let load = format!(
        "        if ($value$plusargs(\"{}=%s\", rom_file)) $readmemh(rom_file, rom);\n    end\n",
        rom_plusarg(module)
    );
    let (head, tail) = empty.split_once("    end\n").expect("verilog_rom's initial block");
    format!("{}{load}{tail}", head.replace("    integer i;\n", "    integer i;\n    reg [8*4096-1:0] rom_file;\n"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend::plan::Request;
    use crate::frontend::resolve::Design;
    use crate::frontend::source::Source;

    fn plan(top: &str) -> Plan {
        let text = format!("{top}\nbot b (.clk(clk100));\nendmodule\n");
        let src = Source::new("top.v", text);
        let top = src.modules[0].name.clone();
        let req = Request {
            programs: vec![],
            bot_firmware: kcpsm6::image::Image::zeroed(),
            force_own_firmware: false,
            first_bot: None,
        };
        let design = Design {
            top,
            project: None,
            sources: vec![src],
            include_dirs: vec![],
            notes: vec![],
            generated: vec![],
            placed: None,
        };
        Plan::new(&design, &req).unwrap()
    }

    /// The assignments of the board's outputs (the bot's and the peripherals' aside).
    fn assigns(v: &str) -> Vec<&str> {
        let aside = ["bot_", "uart_", "ps2_", "lines"];
        v.lines().map(str::trim).filter(|l| l.starts_with("assign ") && !aside.iter().any(|a| l.contains(a))).collect()
    }

    #[test]
    fn nexys3_pins_map_to_the_nexys4_board() {
        // board.md 1: Nexys3 has an active-high reset `btns`, seg[7:0] with dp in bit 7,
        // four anodes and 3/3/2-bit VGA colours.
        let p = plan(
            "module n3(input clk100, input btns, input [7:0] sw, output [7:0] led, output [7:0] seg, \
             output [3:0] an, output [2:0] vgaRed, output [2:1] vgaBlue, output Hsync);",
        );
        let v = board_top(&p, &[]);
        for c in [".clk100(clk),", ".btns(reset_pressed),", ".sw(sw[7:0]),"] {
            assert!(v.lines().any(|l| l.trim() == c), "{c} in {v}");
        }
        assert_eq!(
            assigns(&v),
            [
                "assign led = user_led;",
                "assign seg = user_seg[6:0];",
                "assign dp = user_seg[7];",
                "assign an = {{4{1'b1}}, user_an};",
                "assign vga_r = {user_vgaRed, 1'b0};",
                "assign vga_b = {user_vgaBlue, 2'b0};",
                "assign hsync = user_Hsync;",
                "assign vga_g = 4'h0;",
                "assign vsync = 1'b1;",
            ]
        );
    }

    #[test]
    fn nexys4_ddr_segment_lines_and_parameters() {
        let p = plan(
            "module a7 #(parameter SIMULATE = 0) (input CLK100MHZ, input CPU_RESETN, output CA, output CB, \
             output CG, output DP, output [7:0] AN);",
        );
        let v = board_top(&p, &[("SIMULATE".into(), "1".into())]);
        assert!(v.contains("a7 #(.SIMULATE(1)) user ("), "{v}");
        assert!(v.lines().any(|l| l.trim() == ".CPU_RESETN(~reset_pressed),"), "{v}");
        assert!(assigns(&v).contains(&"assign seg = {user_CG, 1'b1, 1'b1, 1'b1, 1'b1, user_CB, user_CA};"), "{v}");
    }
}
