//! Replays the fuzzers' seeds, kept corpora and crash reproducers (fuzz/) through the same
//! checks the fuzz targets run, so every finding stays fixed without cargo-fuzz installed.

#[path = "../../fuzz/checks.rs"]
mod checks;

use std::path::Path;

fn replay(target: &str, check: fn(&[u8])) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz");
    let mut n = 0;
    for dir in ["seeds", "corpus", "regressions"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir).join(target)) else { continue };
        for e in entries {
            let path = e.unwrap().path();
            // (A fuzzer running beside the tests may remove corpus files meanwhile.)
            let Ok(data) = std::fs::read(&path) else { continue };
            let r = std::panic::catch_unwind(|| check(&data));
            assert!(r.is_ok(), "{target}: {} fails its check", path.display());
            n += 1;
        }
    }
    assert!(n > 0, "{target}: no inputs found under fuzz/");
}

#[test]
fn assembler_inputs() {
    replay("asm", checks::asm);
}

#[test]
fn image_inputs() {
    replay("image", checks::image);
}

#[test]
fn world_inputs() {
    replay("world", checks::world);
}

#[test]
fn motor_script_inputs() {
    replay("script", checks::script);
}
