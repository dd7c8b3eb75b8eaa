//! Files kept in the repository for FPGA users must equal what the toolchain generates now:
//! rtl/bot_pgm.v (from rtl/bot_pgm.psm), rtl/default_world.mem (the built-in world) and the
//! example board design's program ROM (examples/common/proj2demo.v, as `botsim asm`
//! writes it from proj2demo.psm) and the VGA example's icon ROM (examples/nexys4_vga/icon.v, from
//! the display icon of `botsim frame`).
//! Run `scripts/dev/regen.sh` (BOTSIM_BLESS=1) after changing either source.

use std::path::Path;

use botsim::world::World;
use kcpsm6::asm::{assemble_file, Options, RomSize};
use kcpsm6::output::{render, verilog_rom, OutputFormat};

fn check(rel: &str, want: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    if std::env::var_os("BOTSIM_BLESS").is_some() {
        botsim::files::write_atomic(&path, want.as_bytes()).unwrap();
        return;
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(have == want, "{rel} is out of date: run scripts/dev/regen.sh and commit it");
}

#[test]
fn rom_module_matches_the_firmware_source() {
    let psm = Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl/bot_pgm.psm");
    let p = assemble_file(&psm, &Options { rom_size: Some(RomSize::K1), ..Options::default() }).unwrap();
    check("rtl/bot_pgm.v", &verilog_rom(&p.image, "bot_pgm", "bot_pgm.psm", RomSize::K1, p.default_jump));
}

#[test]
fn default_world_file_matches_the_builtin_world() {
    check("rtl/default_world.mem", &World::builtin().to_mem());
}

#[test]
fn example_rom_matches_its_program() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/common");
    let (psm, v) = (dir.join("proj2demo.psm"), dir.join("proj2demo.v"));
    let p = assemble_file(&psm, &Options::default()).unwrap();
    check("examples/common/proj2demo.v", &render(&p, OutputFormat::Verilog, &v, &psm, None));
}

/// The VGA example's icon ROM: botsim's display icon (`render::display::icon`) for the
/// eight headings, as the example's `icon` module (so its frames can equal `botsim frame`'s).
fn icon_verilog() -> String {
    use botsim::render::display::icon;
    use botsim::Orientation;
    let mut v = String::from(
        "// icon.v: the bot's 16 x 16 icon for the eight headings (BotInfo[2:0]), centred on its\n\
         // cell at 4 x 4 pixels per cell; 0 transparent, 1-3 the colorizer's icon colours.\n\
         // Generated from botsim's display icon by tests/generated.rs (scripts/dev/regen.sh).\n\
         `timescale 1ns / 1ps\n\
         module icon (\n\
         \x20   input  wire [9:0] pixel_row,\n\
         \x20   input  wire [9:0] pixel_column,\n\
         \x20   input  wire [7:0] locx,\n\
         \x20   input  wire [7:0] locy,\n\
         \x20   input  wire [7:0] botinfo,\n\
         \x20   output wire [1:0] icon\n\
         );\n\
         \x20   reg [1:0] bitmap [0:2047];  // {heading, y, x}\n\
         \x20   integer i;\n\
         \x20   initial begin\n\
         \x20       for (i = 0; i < 2048; i = i + 1) bitmap[i] = 2'd0;\n",
    );
    for h in Orientation::ALL {
        for (y, row) in icon(h).iter().enumerate() {
            for (x, &p) in row.iter().enumerate() {
                if p != 0 {
                    v.push_str(&format!("        bitmap[{}] = 2'd{p};\n", (h as usize) << 8 | y << 4 | x));
                }
            }
        }
    }
    v.push_str(
        "    end\n\
         \x20   // The icon's pixel (x, y) is at column 4 * LocX + 2 - 8 + x, row 4 * LocY + 2 - 8 + y.\n\
         \x20   wire signed [11:0] x = $signed({2'b00, pixel_column}) - $signed({3'b000, locx[6:0], 2'b00}) + 12'sd6;\n\
         \x20   wire signed [11:0] y = $signed({2'b00, pixel_row}) - $signed({3'b000, locy[6:0], 2'b00}) + 12'sd6;\n\
         \x20   wire on_icon = x >= 0 && x < 16 && y >= 0 && y < 16;\n\
         \x20   assign icon = on_icon ? bitmap[{botinfo[2:0], y[3:0], x[3:0]}] : 2'd0;\n\
         \x20   wire unused_ok = &{1'b0, locx[7], locy[7], botinfo[7:3], x[11:4], y[11:4], 1'b0};\n\
         endmodule\n",
    );
    v
}

#[test]
fn example_icon_matches_the_display_icon() {
    check("examples/nexys4_vga/icon.v", &icon_verilog());
}
