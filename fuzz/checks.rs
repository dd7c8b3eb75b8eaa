//! The checks behind the fuzz targets, one per parser users feed: the fuzz targets
//! (fuzz_targets/*.rs) run them under libFuzzer, and tests/fuzz_corpus.rs replays the kept
//! corpora and every crash reproducer through them in the normal test run. Each check must
//! return without a panic for any input; a panic is a finding.

use std::path::Path;

use botsim_core::script::MotorScript;
use botsim_core::world::{World, WorldFormat};
use kcpsm6::asm::{assemble_source, Options};
use kcpsm6::output::{render, OutputFormat};
use kcpsm6::Image;

/// The assembler on arbitrary source text: it must return a program or diagnostics, never
/// panic or hang; a program it accepts must render in every output format, and its
/// disassembly must assemble to the same image.
pub fn asm(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    // INCLUDEs resolve against a directory that does not exist: they must fail cleanly.
    let source = Path::new("/nonexistent/botsim-fuzz/prog.psm");
    let opts = Options { defines: vec![("fuzz_const".into(), "2A".into())], ..Options::default() };
    if let Ok(program) = assemble_source(source, text, &opts) {
        for (format, out) in [
            (OutputFormat::Hex, "prog.hex"),
            (OutputFormat::Mem, "prog.mem"),
            (OutputFormat::Log, "prog.log"),
            (OutputFormat::Verilog, "prog.v"),
        ] {
            let _ = render(&program, format, Path::new(out), source, None);
        }
        let text = kcpsm6::disasm::disassemble(&program.image);
        let again = kcpsm6::asm::assemble_str(&text).expect("the disassembly must assemble");
        assert!(again.image == program.image, "disassembly round trip");
    }
}

/// The program image loaders (.hex, .mem, Xilinx-template .v) on arbitrary text: an error or
/// an image, never a panic; an image survives a round trip through .hex and .mem unchanged.
pub fn image(data: &[u8]) {
    let Some((&which, rest)) = data.split_first() else { return };
    let text = String::from_utf8_lossy(rest);
    let parsed = match which % 3 {
        0 => Image::parse_hex(Path::new("fuzz.hex"), &text),
        1 => Image::parse_mem(Path::new("fuzz.mem"), &text),
        _ => Image::parse_verilog(Path::new("fuzz.v"), &text),
    };
    if let Ok(image) = parsed {
        let hex = Image::parse_hex(Path::new("round.hex"), &image.to_hex()).expect("own .hex must load");
        assert_eq!(hex.words, image.words, ".hex round trip");
        let mem = Image::parse_mem(Path::new("round.mem"), &image.to_mem()).expect("own .mem must load");
        assert_eq!(mem.words, image.words, ".mem round trip");
    }
}

/// The world map loaders (.txt, .coe, .mem, .png) on arbitrary bytes: an error naming the
/// file, or a world that survives a round trip through its own format unchanged.
pub fn world(data: &[u8]) {
    let Some((&which, rest)) = data.split_first() else { return };
    let (parsed, format) = match which % 4 {
        0 => (World::parse_txt(Path::new("fuzz.txt"), &String::from_utf8_lossy(rest)), WorldFormat::Txt),
        1 => (World::parse_coe(Path::new("fuzz.coe"), &String::from_utf8_lossy(rest)), WorldFormat::Coe),
        2 => (World::parse_mem(Path::new("fuzz.mem"), &String::from_utf8_lossy(rest)), WorldFormat::Mem),
        _ => (World::from_png(Path::new("fuzz.png"), rest), WorldFormat::Png),
    };
    if let Ok(world) = parsed {
        let bytes = world.to_format(format);
        let again = match format {
            WorldFormat::Png => World::from_png(Path::new("round.png"), &bytes),
            WorldFormat::Txt => World::parse_txt(Path::new("round.txt"), std::str::from_utf8(&bytes).unwrap()),
            WorldFormat::Coe => World::parse_coe(Path::new("round.coe"), std::str::from_utf8(&bytes).unwrap()),
            WorldFormat::Mem => World::parse_mem(Path::new("round.mem"), std::str::from_utf8(&bytes).unwrap()),
        };
        assert!(again.expect("own output must load").to_bytes() == world.to_bytes(), "round trip");
    }
}

/// The motor script parser on arbitrary text: an error with its line, or a script whose
/// totals (checked here even where overflow checks are off) and lookups never overflow.
pub fn script(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(script) = MotorScript::parse("fuzz.txt", text) {
        let total = script.total();
        let exact = script.segments.iter().try_fold(0u64, |a, s| a.checked_add(s.1));
        assert_eq!(exact, Some(total), "the total must not overflow");
        let _ = script.initial();
        for k in [0, 1, total / 2, total.saturating_sub(1), total, total.saturating_add(1), u64::MAX] {
            let _ = script.value_for(k);
        }
    }
}
