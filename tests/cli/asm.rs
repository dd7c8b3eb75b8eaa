//! `botsim asm` and `botsim disasm` as a user runs them.

use crate::common;

use std::path::Path;

use common::{botsim, stderr};

const PROG: &str = "CONSTANT threshold, 0F\nstart: LOAD s0, threshold\nOUTPUT s0, 01\nJUMP start\n";

#[test]
fn asm_writes_each_format_by_extension() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("p.psm"), PROG).unwrap();
    let o = botsim(&["asm", "p.psm", "-o", "p.hex", "-o", "p.mem", "-o", "my_rom.v", "-o", "p.log"], d.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let hex = std::fs::read_to_string(d.path().join("p.hex")).unwrap();
    assert_eq!(hex.len(), 28_672);
    assert!(hex.starts_with("0100F\r\n2D001\r\n22000\r\n00000\r\n"));
    let mem = std::fs::read_to_string(d.path().join("p.mem")).unwrap();
    assert!(mem.starts_with("@00000000\n0100F\n"));
    let v = std::fs::read_to_string(d.path().join("my_rom.v")).unwrap();
    assert!(v.contains("module my_rom #("));
    let log = std::fs::read_to_string(d.path().join("p.log")).unwrap();
    assert!(log.contains(" 000  0100F           LOAD s0, 0F[threshold]"), "{log}");
}

#[test]
fn asm_defines_override_constants() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("p.psm"), PROG).unwrap();
    let o = botsim(&["asm", "p.psm", "-o", "p.mem", "-D", "threshold=04"], d.path());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(d.path().join("p.mem")).unwrap().starts_with("@00000000\n01004\n"));
}

#[test]
fn asm_reports_every_error_with_file_line_col_and_exit_1() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("bad.psm"), "LOAD s0, 7\nJUMP nowhere\n").unwrap();
    let o = botsim(&["asm", "bad.psm", "-o", "bad.hex"], d.path());
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr(&o),
        "bad.psm:1:10: error: hex value '7' must have exactly 2 digits\nbad.psm:2:6: error: undefined label 'nowhere'\n"
    );
    assert!(!d.path().join("bad.hex").exists(), "no output on error");
    let o = botsim(&["asm", "bad.psm", "-o", "bad.bin"], d.path());
    assert_eq!((o.status.code(), stderr(&o).lines().count()), (Some(1), 1));
    let o = botsim(&["asm", "missing.psm", "-o", "x.hex"], d.path());
    assert_eq!(stderr(&o), "missing.psm: error: cannot read file: no such file or directory\n");
    let o = botsim(&["asm", "bad.psm", "-o", "no/such/dir/x.hex", "-D", "x=01"], d.path());
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn asm_rom_size_check() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("big.psm"), "ADDRESS 400\nLOAD s0, 00\n").unwrap();
    let o = botsim(&["asm", "big.psm", "-o", "big.v", "--rom-size", "1K"], d.path());
    assert_eq!(stderr(&o), "big.psm:2:1: error: program runs past the 1024-word ROM (last address 3FF)\n");
    let o = botsim(&["asm", "big.psm", "-o", "big.v"], d.path());
    assert!(o.status.success());
    assert!(std::fs::read_to_string(d.path().join("big.v")).unwrap().contains("localparam integer WORDS = 2048;"));
}

#[test]
fn disasm_reads_every_format_and_round_trips() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("p.psm"), PROG).unwrap();
    assert!(botsim(&["asm", "p.psm", "-o", "p.hex", "-o", "p.mem", "-o", "p.v"], d.path()).status.success());
    for input in ["p.hex", "p.mem", "p.v", "p.psm"] {
        let o = botsim(&["disasm", input, "-o", "back.psm"], d.path());
        assert!(o.status.success(), "{input}: {}", stderr(&o));
        assert!(botsim(&["asm", "back.psm", "-o", "back.hex"], d.path()).status.success());
        assert_eq!(std::fs::read(d.path().join("back.hex")).unwrap(), std::fs::read(d.path().join("p.hex")).unwrap());
    }
    let o = botsim(&["disasm", "p.hex"], d.path());
    assert!(String::from_utf8_lossy(&o.stdout).contains("JUMP L_000"));
    std::fs::write(d.path().join("short.hex"), "00000\r\n").unwrap();
    let o = botsim(&["disasm", "short.hex"], d.path());
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).starts_with("short.hex: error: has 1 words"));
}

#[test]
fn help_has_examples() {
    for sub in ["asm", "disasm"] {
        let o = botsim(&[sub, "--help"], Path::new("."));
        assert!(o.status.success());
        assert!(String::from_utf8_lossy(&o.stdout).contains("Examples:"), "{sub}");
    }
}

#[test]
fn quiet_hides_warnings_also_when_the_assembly_fails() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("p.psm"), "CONSTANT unused, 01\nRETURN NZ,\nJUMP nowhere\n").unwrap();
    let loud = common::botsim(&["asm", "p.psm", "-o", "p.hex"], dir.path());
    let quiet = common::botsim(&["asm", "p.psm", "-o", "p.hex", "-q"], dir.path());
    assert_eq!(loud.status.code(), Some(1));
    assert_eq!(quiet.status.code(), Some(1));
    assert_eq!(
        common::stderr(&loud).lines().collect::<Vec<_>>(),
        [
            "p.psm:1:10: warning: constant 'unused' is never used",
            "p.psm:2:10: warning: trailing ',' ignored",
            "p.psm:3:6: error: undefined label 'nowhere'"
        ]
    );
    assert_eq!(common::stderr(&quiet).trim_end(), "p.psm:3:6: error: undefined label 'nowhere'");
    assert!(!dir.path().join("p.hex").exists());
}
