//! Robustness as a user meets it: every kind of bad input gets one clear line and exit 1,
//! nothing hangs, Ctrl-C leaves complete files, and a full disk is an error, never a
//! truncated file presented as success. The README's bad-input table lists these cases.

use crate::common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use botsim::{CpuAt, Error, RtlBot, Timing};
use common::{botsim, stderr};

/// Run `botsim ARGS` in `dir`; the single stderr line and the exit status.
fn fails(dir: &Path, args: &str) -> String {
    let o = botsim(&args.split_whitespace().collect::<Vec<_>>(), dir);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "botsim {args}: {e}");
    assert_eq!(e.lines().count(), 1, "botsim {args}: one line expected, got:\n{e}");
    assert!(!e.contains("panicked") && !e.contains("RUST_BACKTRACE"), "{e}");
    e.trim_end().to_string()
}

/// Files left in `dir` besides the inputs the test wrote.
fn leftovers(dir: &Path, inputs: &[&str]) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !inputs.contains(&n.as_str()))
        .collect();
    v.sort();
    v
}

#[test]
fn bad_input_table() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path();
    let inputs: &[(&str, &[u8])] = &[
        ("digit.psm", b"LOAD s0, 1G\n"),
        ("past.psm", b"ADDRESS 3FF\nLOAD s0, 01\nLOAD s1, 02\n"),
        ("short.hex", b"00000\n00001\n"),
        ("digit.hex", b"0000G\n"),
        ("digit.mem", b"@0000\n0000X\n"),
        ("empty.v", b"module x; endmodule\n"),
        ("range.coe", b"memory_initialization_radix=16;\nmemory_initialization_vector=0,1,5;\n"),
        ("past.mem", b"@3FFF\n0 1\n"),
        ("bad.png", b"\x89PNG but not really"),
        ("small.txt", b"0000\n"),
        ("motion.txt", b"forward 3\nsideways 2\n"),
        ("count.txt", b"forward 3\n33 x\n"),
        ("huge.txt", b"forward 5\nforward 1000000000000\n"),
        ("motctl.txt", b"1FF 3\n"),
        ("empty.txt", b"# nothing\n"),
    ];
    for (name, data) in inputs {
        std::fs::write(p.join(name), data).unwrap();
    }
    std::fs::create_dir(p.join("adir.txt")).unwrap();
    let big = p.join("big.hex");
    let mut words = vec!["00000"; 4096];
    words[0x400] = "01001";
    std::fs::write(&big, words.join("\r\n") + "\r\n").unwrap();

    let table: &[(&str, &str)] = &[
        // programs: bad digits, wrong sizes, too big for the 1K ROM, unknown formats, missing
        ("run --program digit.psm", "digit.psm:1:10: error: undefined constant '1G'"),
        ("run --program past.psm", "past.psm:3:1: error: program runs past the 1024-word ROM (last address 3FF)"),
        ("run --program big.hex", "big.hex: error: the program uses address 400; bot_pgm is a 1K ROM (000-3FF)"),
        ("run --program short.hex", "short.hex: error: has 2 words; a KCPSM6 .hex has exactly 4096"),
        ("run --program digit.hex", "digit.hex:1:1: error: '0000G' is not an instruction word"),
        ("run --program digit.mem", "digit.mem:2:1: error: '0000X' is not an instruction word"),
        ("run --program empty.v", "empty.v: error: no program found"),
        ("run --program prog.exe", "prog.exe: error: unknown program format"),
        ("run --program nope.hex", "nope.hex: error: cannot read file: no such file or directory"),
        ("disasm short.hex", "short.hex: error: has 2 words"),
        ("asm digit.psm -o out.hex", "digit.psm:1:10: error: undefined constant '1G'"),
        // worlds: out-of-range cells, wrong sizes, not an image, a folder, missing, unknown
        ("run --map range.coe", "range.coe:2:5: error: '5' is not a cell value 0-3"),
        ("run --map past.mem", "past.mem:2:3: error: value past the last cell (address 3FFF)"),
        ("run --map small.txt", "small.txt: error: row 000 is missing (128 of 128 rows missing)"),
        ("run --map bad.png", "bad.png: error: not a readable PNG"),
        ("run --map adir.txt", "adir.txt: error: cannot read file: is a directory"),
        ("run --map nope.coe", "nope.coe: error: cannot read file: no such file or directory"),
        ("map convert builtin out.xyz", "out.xyz: error: unknown world format"),
        // motor scripts: a bad line, a bad count, a count too large, a bad value, nothing
        ("run --motors motion.txt", "motion.txt:2:1: error: 'sideways' is not a MotCtl value"),
        ("run --motors count.txt", "count.txt:2:4: error: 'x' is not a count"),
        ("run --motors huge.txt", "huge.txt:2:9: error: the script covers more than 1000000000 iterations"),
        ("run --motors motctl.txt", "motctl.txt:1:1: error: '1FF' is not a MotCtl value"),
        ("run --motors empty.txt", "empty.txt: error: no segments"),
        ("run --motors adir.txt", "adir.txt: error: cannot read file: is a directory"),
        // outputs that cannot be written: reported before the run starts
        ("run --trace-csv no/dir/t.csv", "no/dir/t.csv: error: cannot write file: no such file or directory"),
        ("run --vcd adir.txt", "adir.txt: error: cannot write file"),
        ("run --png no/dir/p.png", "no/dir/p.png: error: cannot write file"),
        ("frame -o no/dir/f.png", "no/dir/f.png: error: cannot write file"),
        ("asm digit.psm -o out.exe", "out.exe: error: unknown output format"),
        // bad usage
        ("run --samples x", "error: invalid value 'x' for '--samples <N>'"),
        ("run --backend iss --vcd w.vcd", "error: --vcd needs the RTL backend; --backend iss has no waveform"),
    ];
    for (args, want) in table {
        let o = botsim(&args.split_whitespace().collect::<Vec<_>>(), p);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "botsim {args}: {e}");
        assert!(e.starts_with(want), "botsim {args}:\n  got  {e}  want {want}");
        assert!(!e.contains("panicked"), "{e}");
        if !args.contains("--samples x") {
            assert_eq!(e.lines().count(), 1, "botsim {args}: {e}");
        }
    }
    let names: Vec<&str> = inputs.iter().map(|i| i.0).chain(["adir.txt", "big.hex"]).collect();
    assert_eq!(leftovers(p, &names), Vec::<String>::new(), "a failed command left files");
}

#[test]
fn a_firmware_that_never_pulses_is_reported_with_where_the_cpu_is() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("stuck.psm"), "start: LOAD s0, 01\nhere: JUMP here\n").unwrap();
    let t = Instant::now();
    let e = fails(d.path(), "run --program stuck.psm --timing fast --trace-csv t.csv");
    assert_eq!(
        e,
        "error: sample 0: no upd_sysregs pulse within 16000 cycles (stopped at cycle 16000, the CPU at address 001)"
    );
    assert!(t.elapsed() < Duration::from_secs(20));
    assert!(!d.path().join("t.csv").exists());
}

#[test]
fn every_backend_waits_the_budget_of_the_chosen_timing() {
    // --backend iss and lockstep used the hw budget whatever --timing said.
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("stuck.psm"), "start: LOAD s0, 01\nhere: JUMP here\n").unwrap();
    for backend in ["rtl", "iss", "lockstep"] {
        let e = fails(d.path(), &format!("run --backend {backend} --program stuck.psm --timing fast"));
        assert!(e.starts_with("error: sample 0: no upd_sysregs pulse within 16000 cycles"), "{backend}: {e}");
    }
}

#[test]
fn a_failed_run_keeps_the_previous_output_files() {
    // The early writability check used to write and delete the outputs: a run that then failed
    // lost the user's files from the last run.
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("stuck.psm"), "start: LOAD s0, 01\nhere: JUMP here\n").unwrap();
    for name in ["t.csv", "t.json", "p.png", "w.vcd"] {
        std::fs::write(d.path().join(name), "from the last run").unwrap();
    }
    fails(
        d.path(),
        "run --program stuck.psm --timing fast --trace-csv t.csv --trace-json t.json --png p.png --vcd w.vcd",
    );
    for name in ["t.csv", "t.json", "p.png", "w.vcd"] {
        assert_eq!(std::fs::read_to_string(d.path().join(name)).unwrap(), "from the last run", "{name}");
    }
    let mut names: Vec<String> =
        std::fs::read_dir(d.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["p.png", "stuck.psm", "t.csv", "t.json", "w.vcd"]);
}

#[test]
fn a_cpu_held_in_reset_is_reported() {
    let mut bot = RtlBot::builder().timing(Timing::Fast).build().unwrap();
    bot.wait_update().unwrap();
    bot.hold_reset(true);
    match bot.wait_update_within(5_000) {
        Err(e @ Error::Timeout { cpu: CpuAt::Reset, .. }) => assert_eq!(
            e.to_string(),
            format!(
                "no upd_sysregs pulse within 5000 cycles (stopped at cycle {}, the CPU held in reset)",
                bot.cycle()
            )
        ),
        other => panic!("{other:?}"),
    }
    // Released, the firmware starts again from sample 0.
    bot.hold_reset(false);
    let s = bot.wait_update().unwrap();
    assert_eq!((s.sample, s.location()), (0, (64, 64)));
    // The ISS backend says the same.
    let fw = botsim::Firmware { timing: Timing::Fast, ..Default::default() };
    let mut iss = botsim::IssBot::new(&fw.assemble().unwrap(), botsim::World::builtin()).unwrap();
    assert!(matches!(iss.wait_update_within(10), Err(Error::Timeout { cpu: CpuAt::Address(_), budget: 10, .. })));
}

#[test]
fn ctrl_c_stops_a_long_run_and_leaves_complete_files() {
    let d = tempfile::tempdir().unwrap();
    // hw timing: 1000 samples take over a minute; a waveform window over the first 20,000 cycles.
    let mut child = Command::new(env!("CARGO_BIN_EXE_botsim"))
        .args(["run", "--samples", "1000", "--trace-csv", "t.csv", "--trace-json", "t.jsonl"])
        .args(["--vcd", "w.vcd", "--trace-from", "0c", "--trace-to", "20000c", "--png", "p.png"])
        .current_dir(d.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let kill = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let status = common::exit_within(&mut child, Duration::from_secs(30), "no exit within 30 s of Ctrl-C");
    let o = child.wait_with_output().unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(status.code(), Some(130), "{e}");
    let line = e.lines().find(|l| l.starts_with("interrupted:")).unwrap_or_else(|| panic!("{e}"));
    // "interrupted: stopped in sample K at cycle C; the outputs hold samples 0-(K-1)"
    let k: usize = line.split_whitespace().nth(4).unwrap().parse().unwrap();
    assert!((1..1000).contains(&k), "{line}");
    let csv = std::fs::read_to_string(d.path().join("t.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + k, "header and one row per sample taken");
    let json = std::fs::read_to_string(d.path().join("t.jsonl")).unwrap();
    assert_eq!(json.lines().count(), k);
    for l in json.lines() {
        serde_json::from_str::<serde_json::Value>(l).unwrap();
    }
    // The waveform is complete: it parses to its end and reaches the window's last cycle.
    let mut r = vcd::Parser::new(std::io::BufReader::new(std::fs::File::open(d.path().join("w.vcd")).unwrap()));
    r.parse_header().unwrap();
    let mut last = 0;
    for cmd in r {
        if let vcd::Command::Timestamp(t) = cmd.unwrap() {
            last = t;
        }
    }
    assert!(last >= 20_000 * 10_000 - 5_000, "last time stamp {last}");
    assert!(d.path().join("p.png").exists());
    let mut left = leftovers(d.path(), &[]);
    left.retain(|n| n.starts_with('.'));
    assert_eq!(left, Vec::<String>::new(), "temporary files left");
}

/// `botsim ARGS` with the file size limited to `kbytes` (as on a full disk: writes fail),
/// killed after two minutes (exit 124): Verilator's own fatal-error path hangs here, which
/// the shim's `vl_fatal` replaces.
fn with_file_limit(dir: &Path, kbytes: u32, args: &str) -> std::process::Output {
    let bin = env!("CARGO_BIN_EXE_botsim");
    Command::new("sh")
        .arg("-c")
        .arg(format!("trap '' XFSZ; ulimit -f {kbytes}; exec timeout 120 {bin} {args}"))
        .current_dir(dir)
        .output()
        .unwrap()
}

#[test]
fn a_full_disk_is_an_error_and_leaves_no_file() {
    let d = tempfile::tempdir().unwrap();
    // The waveform outgrows the limit while the run goes on.
    let o = with_file_limit(d.path(), 2000, "run --timing fast --samples 30 --vcd w.vcd --trace-csv t.csv");
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.starts_with("w.vcd: error: cannot write file: File too large (in sample "), "{e}");
    assert_eq!(e.lines().count(), 1);
    // A trace file that does not fit.
    let o = with_file_limit(d.path(), 1, "run --timing fast --samples 60 --trace-csv t.csv");
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).starts_with("t.csv: error: cannot write file: "), "{}", stderr(&o));
    assert_eq!(leftovers(d.path(), &[]), Vec::<String>::new());
    // The same runs fit without the limit.
    let o = botsim(&["run", "--timing", "fast", "--samples", "30", "--vcd", "w.vcd", "--trace-csv", "t.csv"], d.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}
