//! The KCPSM6 under Icarus Verilog (rtl/sim/kcpsm6_icarus_tb.v around the CPU test harness):
//! a four-state simulator, where a read of a RAM entry nobody wrote, or an index out of range,
//! is `x` instead of Verilator's 0. A trace of ports per cycle, as [`super::lockstep::Core`]
//! gives them; a bit that is `x` makes its field [`X`].

use std::path::{Path, PathBuf};
use std::process::Command;

use botsim::sim::rtl::Ports;
use kcpsm6::iss::Pins;

/// What a field reads when any of its bits is unknown.
pub const X: u16 = 0xFFFF;

use super::root;

/// Whether Icarus is installed: missing, an error when BOTSIM_REQUIRE_TOOLS is set (as in CI),
/// else a note and the caller skips its run.
pub fn installed() -> bool {
    if Command::new("iverilog").arg("-V").output().is_ok() {
        return true;
    }
    assert!(std::env::var_os("BOTSIM_REQUIRE_TOOLS").is_none(), "iverilog is not installed (scripts/setup.sh)");
    eprintln!("note: iverilog is not installed; the Icarus run is skipped");
    false
}

/// Compile the module `top` of `files` into `dir` and simulate it there with `plusargs`:
/// what it printed.
pub fn simulate(dir: &Path, top: &str, files: &[PathBuf], plusargs: &[String]) -> String {
    let sim = dir.join("sim");
    let o = Command::new("iverilog").args(["-g2005", "-o"]).arg(&sim).args(["-s", top]).args(files).output().unwrap();
    assert!(o.status.success(), "iverilog: {}", String::from_utf8_lossy(&o.stderr));
    let o = Command::new("vvp").arg("-n").arg(&sim).args(plusargs).current_dir(dir).output().unwrap();
    assert!(o.status.success(), "vvp: {}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The ports of cycles 0..pins.len() of `program` under Icarus, or `None` when Icarus is not
/// installed ([`installed`]).
pub fn trace(program: &[u32], pins: &[Pins]) -> Option<Vec<Ports>> {
    if !installed() {
        return None;
    }
    let dir = tempfile::tempdir().unwrap();
    let rom: String = program.iter().map(|w| format!("{w:05X}\n")).collect();
    let pin_text: String = pins
        .iter()
        .map(|p| format!("{:X}\n", p.reset as u8 | (p.sleep as u8) << 1 | (p.interrupt as u8) << 2))
        .collect();
    std::fs::write(dir.path().join("rom.mem"), rom).unwrap();
    std::fs::write(dir.path().join("pins.mem"), pin_text).unwrap();
    let files = ["rtl/sim/kcpsm6_icarus_tb.v", "rtl/sim/kcpsm6_harness.v", "rtl/kcpsm6.v"].map(|f| root().join(f));
    let plusargs = [
        format!("+rom={}", dir.path().join("rom.mem").display()),
        format!("+pins={}", dir.path().join("pins.mem").display()),
        format!("+cycles={}", pins.len()),
    ];
    let out = simulate(dir.path(), "kcpsm6_icarus_tb", &files, &plusargs);
    let hex = |s: &str| u32::from_str_radix(s, 16).unwrap_or(X as u32);
    let bit = |s: &str| s == "1";
    let ports = out
        .lines()
        .filter(|l| l.split(' ').count() == 9)
        .map(|l| {
            let f: Vec<&str> = l.split(' ').collect();
            Ports {
                address: hex(f[0]) as u16,
                instruction: hex(f[1]),
                bram_enable: bit(f[2]),
                port_id: hex(f[3]) as u8,
                out_port: hex(f[4]) as u8,
                in_port: 0,
                read_strobe: bit(f[5]),
                write_strobe: bit(f[6]),
                k_write_strobe: bit(f[7]),
                interrupt_ack: bit(f[8]),
            }
        })
        .collect::<Vec<_>>();
    assert_eq!(ports.len(), pins.len(), "{out}");
    Some(ports)
}
