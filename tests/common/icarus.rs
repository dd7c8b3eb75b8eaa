//! The KCPSM6 under Icarus Verilog (rtl/sim/kcpsm6_icarus_tb.v around the CPU test harness):
//! a four-state simulator, where a read of a RAM entry nobody wrote, or an index out of range,
//! is `x` instead of Verilator's 0. A trace of ports per cycle, as [`super::lockstep::Core`]
//! gives them; a bit that is `x` makes its field [`X`].

use std::process::Command;

use botsim::sim::rtl::Ports;
use kcpsm6::iss::Pins;

/// What a field reads when any of its bits is unknown.
pub const X: u16 = 0xFFFF;

use super::root;

/// The ports of cycles 0..pins.len() of `program` under Icarus, or `None` when Icarus is not
/// installed (an error when BOTSIM_REQUIRE_TOOLS is set, as in CI).
pub fn trace(program: &[u32], pins: &[Pins]) -> Option<Vec<Ports>> {
    if Command::new("iverilog").arg("-V").output().is_err() {
        assert!(std::env::var_os("BOTSIM_REQUIRE_TOOLS").is_none(), "iverilog is not installed (scripts/setup.sh)");
        eprintln!("note: iverilog is not installed; the Icarus run is skipped");
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
    let sim = dir.path().join("sim");
    let o = Command::new("iverilog")
        .args(["-g2005", "-o"])
        .arg(&sim)
        .args(["-s", "kcpsm6_icarus_tb"])
        .arg(root().join("rtl/sim/kcpsm6_icarus_tb.v"))
        .arg(root().join("rtl/sim/kcpsm6_harness.v"))
        .arg(root().join("rtl/kcpsm6.v"))
        .output()
        .unwrap();
    assert!(o.status.success(), "iverilog: {}", String::from_utf8_lossy(&o.stderr));
    let o = Command::new("vvp")
        .arg("-n")
        .arg(&sim)
        .arg(format!("+rom={}", dir.path().join("rom.mem").display()))
        .arg(format!("+pins={}", dir.path().join("pins.mem").display()))
        .arg(format!("+cycles={}", pins.len()))
        .output()
        .unwrap();
    assert!(o.status.success(), "vvp: {}", String::from_utf8_lossy(&o.stderr));
    let hex = |s: &str| u32::from_str_radix(s, 16).unwrap_or(X as u32);
    let bit = |s: &str| s == "1";
    let ports = String::from_utf8_lossy(&o.stdout)
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
    assert_eq!(ports.len(), pins.len(), "{}", String::from_utf8_lossy(&o.stdout));
    Some(ports)
}
