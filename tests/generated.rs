//! Files kept in the repository for FPGA users must equal what the toolchain generates now:
//! rtl/bot_pgm.v (from rtl/bot_pgm.psm), rtl/default_world.mem (the built-in world) and the
//! example board design's program ROM (examples/nexys4_proj2/proj2demo.v, as `botsim asm`
//! writes it from proj2demo.psm).
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
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/nexys4_proj2");
    let (psm, v) = (dir.join("proj2demo.psm"), dir.join("proj2demo.v"));
    let p = assemble_file(&psm, &Options::default()).unwrap();
    check("examples/nexys4_proj2/proj2demo.v", &render(&p, OutputFormat::Verilog, &v, &psm, None));
}
