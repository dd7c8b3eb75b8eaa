//! The Verilog botsim generates around a user's design: `botsim_board`, a top with the same
//! ports for every design (so one C++ harness runs them all), the behavioural ROMs and the
//! stubs.
//!
//! `botsim_board`'s ports: `clk` (the 100 MHz oscillator), `reset_pressed`, `btn[4:0]`
//! (C, U, D, L, R), `sw[15:0]` in; `led[15:0]`, `an[7:0]`, `seg[6:0]` (g..a), `dp`,
//! `vga_r/g/b[3:0]`, `hsync`, `vsync` out (active low where the board's are, and "off" when
//! the design has no such pin); and the substituted bot's `bot_upd`, registers, MotCtl and
//! `bot_cycles` (rising edges of the bot's clock since power-up), read through hierarchical
//! references.

use kcpsm6::asm::RomSize;
use kcpsm6::output::verilog_rom;

use super::pins::Role;
use super::plan::Plan;

/// The wrapper module's name.
pub const TOP: &str = "botsim_board";

/// The Verilog of `botsim_board` for `plan`.
pub fn board_top(plan: &Plan, params: &[(String, String)]) -> String {
    let width = |port: &str| plan.widths.get(port).copied().unwrap_or(1).max(1);
    let mut decl = String::new();
    let mut conns = Vec::new();
    let mut assigns = Vec::new();
    let (mut has_seg, mut has_dp, mut has_an, mut has_led) = (false, false, false, false);
    let (mut has_r, mut has_g, mut has_b, mut has_hs, mut has_vs) = (false, false, false, false, false);
    let mut seg_bits = Vec::new();
    for (port, role) in &plan.pins {
        let w = width(port);
        let c = match role {
            Role::Clock => "clk".to_string(),
            Role::Reset { active_low: true } => "~reset_pressed".to_string(),
            Role::Reset { active_low: false } => "reset_pressed".to_string(),
            Role::Button(b) => format!("btn[{b}]"),
            Role::Switches => format!("sw[{}:0]", w.min(16) - 1),
            Role::Leds => {
                has_led = true;
                decl.push_str(&format!("    wire [{}:0] user_led;\n", w - 1));
                assigns.push(format!(
                    "assign led = {{{{{}{{1'b0}}}}, user_led[{}:0]}};",
                    16 - w.min(16),
                    w.min(16) - 1
                ));
                "user_led".into()
            }
            Role::Segments => {
                has_seg = true;
                decl.push_str(&format!("    wire [{}:0] user_seg;\n", w - 1));
                assigns.push("assign seg = user_seg[6:0];".into());
                if w >= 8 {
                    has_dp = true;
                    assigns.push("assign dp = user_seg[7];".into());
                }
                "user_seg".into()
            }
            Role::Segment(i) => {
                seg_bits.push(*i);
                decl.push_str(&format!("    wire user_seg_{i};\n"));
                format!("user_seg_{i}")
            }
            Role::DecimalPoint => {
                has_dp = true;
                decl.push_str("    wire user_dp;\n");
                assigns.push("assign dp = user_dp;".into());
                "user_dp".into()
            }
            Role::Anodes => {
                has_an = true;
                decl.push_str(&format!("    wire [{}:0] user_an;\n", w - 1));
                let pad = 8 - w.min(8);
                assigns.push(if pad > 0 {
                    format!("assign an = {{{{{pad}{{1'b1}}}}, user_an[{}:0]}};", w.min(8) - 1)
                } else {
                    "assign an = user_an[7:0];".into()
                });
                "user_an".into()
            }
            Role::VgaRed | Role::VgaGreen | Role::VgaBlue => {
                let (name, flag) = match role {
                    Role::VgaRed => ("r", &mut has_r),
                    Role::VgaGreen => ("g", &mut has_g),
                    _ => ("b", &mut has_b),
                };
                *flag = true;
                decl.push_str(&format!("    wire [{}:0] user_vga_{name};\n", w - 1));
                let w4 = w.min(4);
                assigns.push(if w4 < 4 {
                    format!("assign vga_{name} = {{user_vga_{name}[{}:{}], {}'b0}};", w - 1, w - w4, 4 - w4)
                } else {
                    format!("assign vga_{name} = user_vga_{name}[{}:{}];", w - 1, w - 4)
                });
                format!("user_vga_{name}")
            }
            Role::Hsync => {
                has_hs = true;
                decl.push_str("    wire user_hsync;\n");
                assigns.push("assign hsync = user_hsync;".into());
                "user_hsync".into()
            }
            Role::Vsync => {
                has_vs = true;
                decl.push_str("    wire user_vsync;\n");
                assigns.push("assign vsync = user_vsync;".into());
                "user_vsync".into()
            }
        };
        conns.push(format!(".{port}({c})"));
    }
    if !seg_bits.is_empty() {
        has_seg = true;
        let bits: Vec<String> =
            (0..7).rev().map(|i| if seg_bits.contains(&i) { format!("user_seg_{i}") } else { "1'b1".into() }).collect();
        assigns.push(format!("assign seg = {{{}}};", bits.join(", ")));
    }
    // Ports with no board role: inputs low, outputs open.
    for name in &plan.unknown_pins {
        let input = plan.inputs.contains(name);
        conns.push(if input { format!(".{name}({}'d0)", width(name)) } else { format!(".{name}()") });
    }
    let off = [
        (has_led, "assign led = 16'h0000;"),
        (has_seg, "assign seg = 7'h7F;"),
        (has_dp, "assign dp = 1'b1;"),
        (has_an, "assign an = 8'hFF;"),
        (has_r, "assign vga_r = 4'h0;"),
        (has_g, "assign vga_g = 4'h0;"),
        (has_b, "assign vga_b = 4'h0;"),
        (has_hs, "assign hsync = 1'b1;"),
        (has_vs, "assign vsync = 1'b1;"),
    ];
    for (has, a) in off {
        if !has {
            assigns.push(a.into());
        }
    }
    let bot = format!("user.{}", plan.bot_path);
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
         \x20   output wire        bot_upd,\n\
         \x20   output wire [ 7:0] bot_locx,\n\
         \x20   output wire [ 7:0] bot_locy,\n\
         \x20   output wire [ 7:0] bot_info,\n\
         \x20   output wire [ 7:0] bot_sensors,\n\
         \x20   output wire [ 7:0] bot_lmdist,\n\
         \x20   output wire [ 7:0] bot_rmdist,\n\
         \x20   output wire [ 7:0] bot_motctl,\n\
         \x20   output reg  [63:0] bot_cycles\n\
         );\n\
         {decl}\
         \x20   {top} {overrides}user (\n        {conns}\n    );\n\
         \x20   {assigns}\n\
         \x20   // The substituted bot, seen through hierarchical references.\n\
         \x20   wire bot_clk = {bot}.clk;\n\
         \x20   assign bot_upd = {bot}.upd_sysregs;\n\
         \x20   assign bot_locx = {bot}.LocX_reg;\n\
         \x20   assign bot_locy = {bot}.loc_y;\n\
         \x20   assign bot_info = {bot}.BotInfo_reg;\n\
         \x20   assign bot_sensors = {bot}.Sensors_reg;\n\
         \x20   assign bot_lmdist = {bot}.LMDist_reg;\n\
         \x20   assign bot_rmdist = {bot}.RMDist_reg;\n\
         \x20   assign bot_motctl = {bot}.MotCtl_in;\n\
         \x20   initial bot_cycles = 64'd0;\n\
         \x20   always @(posedge bot_clk) bot_cycles <= bot_cycles + 64'd1;\n\
         endmodule\n",
        top = plan.top,
        conns = conns.join(",\n        "),
        assigns = assigns.join("\n    "),
    )
}

/// The behavioural ROMs of the plan: (module name, Verilog).
pub fn roms(plan: &Plan) -> Vec<(String, String)> {
    plan.roms
        .iter()
        .map(|r| (r.module.clone(), verilog_rom(&r.image, &r.module, &r.origin, RomSize::K4, None)))
        .collect()
}

/// A stub: the module with every port it is connected by, as a 1-bit input, and no logic.
pub fn stub(module: &str, ports: &[String]) -> String {
    let named: Vec<&String> = ports.iter().filter(|p| !p.starts_with('#')).collect();
    let list = named.iter().map(|p| format!("    input wire {p}")).collect::<Vec<_>>().join(",\n");
    format!(
        "// Generated by botsim board: --stub {module} (ports tied off, no logic).\n\
         /* verilator lint_off UNUSEDSIGNAL */\n\
         module {module} (\n{list}\n);\nendmodule\n"
    )
}
