//! `botsim run` looking inside the bot's CPU, as `botsim board` does (one implementation:
//! botsim_core::debug, kcpsm6::trace): the source-level trace and profile of the firmware, its
//! breakpoints, and a waveform with the KCPSM6's debug signals and a GTKWave save file.

use std::path::Path;
use std::process::Output;

use crate::common;

use common::{botsim, stderr};

fn run(dir: &Path, args: &[&str]) -> Output {
    let mut all = vec!["run"];
    all.extend_from_slice(args);
    let o = botsim(&all, dir);
    assert!(o.status.success(), "{}", stderr(&o));
    o
}

/// The firmware `--timing fast` assembles, with its listing.
fn firmware() -> kcpsm6::asm::Program {
    botsim::Firmware { timing: botsim::Timing::Fast, ..Default::default() }.program(0).unwrap()
}

#[test]
fn the_cpu_trace_of_the_bot_names_its_psm_lines_as_the_assemblers_listing() {
    let dir = tempfile::tempdir().unwrap();
    run(dir.path(), &["--timing", "fast", "--samples", "3", "--cpu-trace", "t.txt", "--trace-csv", "traced.csv", "-q"]);
    common::debug::check_trace_against_listing(&dir.path().join("t.txt"), &firmware(), "bot_pgm.psm", 1000);
    // The ISS under the trace takes the RTL's samples, cycle for cycle.
    run(dir.path(), &["--timing", "fast", "--samples", "3", "--trace-csv", "rtl.csv", "-q"]);
    let read = |f: &str| std::fs::read_to_string(dir.path().join(f)).unwrap();
    assert_eq!(read("traced.csv"), read("rtl.csv"));
}

/// The D cycle of the first instruction at `label` in a trace.
fn first_at(trace: &Path, label: &str) -> u64 {
    let text = std::fs::read_to_string(trace).unwrap();
    let line = text.lines().skip(1).find(|l| l.split_whitespace().nth(3) == Some(label)).unwrap();
    line.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn a_breakpoint_stops_where_the_trace_shows_the_instruction_and_the_waveform_ends_there() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run(d, &["--timing", "fast", "--samples", "2", "--cpu-trace", "whole.txt", "-q"]);
    let at = first_at(&d.join("whole.txt"), "publish_snapshot");
    let o = run(
        d,
        &[
            "--timing",
            "fast",
            "--samples",
            "5",
            "--break",
            "label=publish_snapshot",
            "--vcd",
            "w.vcd",
            "--trace-csv",
            "c.csv",
        ],
    );
    let e = stderr(&o);
    let line = e.lines().find(|l| l.starts_with("stopped by --break")).unwrap_or_else(|| panic!("{e}"));
    let map = botsim::kcpsm6::source::SourceMap::of(&firmware());
    let psm_line = map.line(map.label_address("publish_snapshot").unwrap()).unwrap().line;
    assert_eq!(
        line,
        format!(
            "stopped by --break label=publish_snapshot: pc {:03X} publish_snapshot (bot_pgm.psm:{psm_line}) in cycle {at} ({:.6} ms), in sample 0's iteration",
            map.label_address("publish_snapshot").unwrap(),
            at as f64 / 1e5
        )
    );
    // The outputs end at the stop: it came before sample 0.
    assert_eq!(std::fs::read_to_string(d.join("c.csv")).unwrap().lines().count(), 1);
    // The waveform from power-up to the stop: the instruction text as the disassembler gives
    // it, the save file listing only what the waveform has.
    let checked = common::debug::check_debug_signals(&d.join("w.vcd"), &[&["TOP", "bot", "BOTSIMCPU"]]);
    assert!(checked[0] > 50, "{checked:?}");
    let have = common::debug::vcd_signals(&d.join("w.vcd"));
    let gtkw = std::fs::read_to_string(d.join("w.gtkw")).unwrap();
    let listed: Vec<&str> = gtkw.lines().filter(|l| l.starts_with("TOP.")).collect();
    assert!(listed.len() > 30, "{gtkw}");
    let missing: Vec<&&str> = listed.iter().filter(|l| !have.contains(**l)).collect();
    assert!(missing.is_empty(), "{missing:?}");
    assert!(gtkw.contains("w.labels.txt") && d.join("w.labels.txt").exists());
}

#[test]
fn a_bot_condition_stops_at_the_first_sample_that_shows_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let follow = ["--timing", "fast", "--driver", "line-follow", "--samples", "400"];
    run(d, &[&follow[..], &["--trace-csv", "all.csv", "-q"]].concat());
    // The first sample whose sensors differ from the start's.
    let rows: Vec<Vec<u64>> = std::fs::read_to_string(d.join("all.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let first = rows.iter().find(|r| r[5] != rows[0][5]).expect("the follower moves the bot over something");
    let spec = format!("bot=sensors:{:02X}", first[5]);
    let o = run(d, &[&follow[..], &["--break", &spec, "--trace-csv", "stop.csv"]].concat());
    assert!(stderr(&o).contains(&format!("stopped by --break {spec}: sample {},", first[0])), "{}", stderr(&o));
    let stopped = std::fs::read_to_string(d.join("stop.csv")).unwrap();
    assert_eq!(stopped.lines().count() as u64, first[0] + 2, "the samples up to the one that shows it");
}
