//! The build script's own logic, included from build/ (it cannot be linked otherwise).

#[path = "../build/sources.rs"]
mod sources;

use std::path::{Path, PathBuf};

#[test]
fn a_checkout_under_usr_or_in_a_verilator_folder_still_tracks_its_rtl() {
    let dat = r#"# DESCRIPTION: Verilator output: Timestamp data for --skip-identical.  Delete at will.
C "--cc --prefix Vbot rtl/bot.v"
S      4890 1234 1700000000 0 1700000000 0 "/usr/share/verilator/bin/verilator_bin"
S      2048 1235 1700000000 0 1700000000 0 "/usr/share/verilator/include/verilated_std.sv"
S      8000 1236 1700000000 0 1700000000 0 "/usr/src/botsim/rtl/bot.v"
S      9000 1237 1700000000 0 1700000000 0 "/home/me/verilator-projects/botsim/rtl/kcpsm6.v"
S       700 1238 1700000000 0 1700000000 0 "/usr/src/botsim/target/release/build/botsim-1/out/bot_pgm.v"
T      1000 1239 1700000000 0 1700000000 0 "/tmp/Vbot.cpp"
"#;
    let got = sources::design_sources(
        dat,
        Path::new("/usr/share/verilator"),
        Path::new("/usr/src/botsim/target/release/build/botsim-1/out"),
    );
    let want: Vec<PathBuf> = ["/usr/src/botsim/rtl/bot.v", "/home/me/verilator-projects/botsim/rtl/kcpsm6.v"]
        .iter()
        .map(PathBuf::from)
        .collect();
    assert_eq!(got, want);
}
