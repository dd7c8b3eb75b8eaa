//! `botsim suite`: designs × maps in parallel, the table, the JSON and JUnit XML reports,
//! the files of a failed run, shards.

use std::path::PathBuf;
use std::process::Command;

use crate::common;

use common::root;

/// A suite of the example design with the line follower (passes) and with the demo firmware
/// (does not follow the line: fails), on the built-in course.
fn suite_file(dir: &std::path::Path) -> PathBuf {
    let ex = root().join("examples");
    let text = format!(
        r#"samples = 5000
expect = ["line-end", "never-blocked"]
cpu = "iss"
args = ["--param", "SIMULATE=1", "--timing", "fast", "--compat", "botsim20"]

[[design]]
name = "follower"
sources = ["{c}", "{p}"]
args = ["--program", "{c}/linefollow.psm"]

[[design]]
name = "demo"
sources = ["{c}", "{p}"]

[[map]]
name = "builtin"
"#,
        c = ex.join("common").display(),
        p = ex.join("nexys4_proj2").display()
    );
    let f = dir.join("course.toml");
    std::fs::write(&f, text).unwrap();
    f
}

fn suite(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_botsim"))
        .arg("suite")
        .args(args)
        .env("BOTSIM_CACHE", common::board_cache())
        .output()
        .unwrap()
}

#[test]
fn a_suite_runs_every_design_on_every_map_and_reports_each_outcome() {
    let dir = tempfile::tempdir().unwrap();
    let f = suite_file(dir.path());
    let out = dir.path().join("results");
    let o = suite(&[f.to_str().unwrap(), "-j", "2", "--out", out.to_str().unwrap()]);
    let (stdout, stderr) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    // The demo firmware fails the check: exit 1, with one line saying so.
    assert_eq!(o.status.code(), Some(1), "{stdout}{stderr}");
    assert_eq!(stderr.lines().last().unwrap(), "botsim suite: 1 of 2 runs failed", "{stderr}");
    let pass = stdout.lines().find(|l| l.contains("follower")).unwrap();
    assert!(pass.starts_with("pass") && pass.contains("3842 samples"), "{stdout}");
    // The demo drives into the wall east of the start: the run stops at that sample (it could
    // not pass any more) rather than running out its 5,000-sample budget.
    let fail = stdout.lines().find(|l| l.contains("demo")).unwrap();
    assert!(fail.starts_with("FAIL") && fail.contains("the world refused a move at sample "), "{stdout}");

    let report: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["failed"], 1);
    let runs = report["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    assert_eq!(runs[0]["design"], "follower");
    assert_eq!(runs[0]["summary"]["end"]["at_line_end"], true);
    assert_eq!(runs[1]["passed"], false);
    let demo = &runs[1]["summary"];
    assert_eq!(demo["stopped_by"], "blocked", "{demo}");
    assert_eq!(demo["samples"].as_u64(), demo["first_blocked_sample"].as_u64().map(|k| k + 2), "{demo}");

    let junit = std::fs::read_to_string(out.join("junit.xml")).unwrap();
    assert!(junit.contains(r#"<testsuites name="botsim suite" tests="2" failures="1""#), "{junit}");
    assert_eq!(junit.matches("<testcase ").count(), 2);
    assert_eq!(junit.matches("<failure ").count(), 1);
    assert_eq!(junit.matches("<testsuite ").count(), junit.matches("</testsuite>").count());

    // Every run keeps its files; the failed one also a waveform around its failure.
    for d in ["follower", "demo"] {
        for f in ["trace.csv", "path.png", "display.txt"] {
            assert!(out.join(d).join("builtin").join(f).exists(), "{d}/{f}");
        }
    }
    let vcd = std::fs::read_to_string(out.join("demo/builtin/failure.vcd")).unwrap();
    assert!(vcd.contains("$enddefinitions") && vcd.lines().filter(|l| l.starts_with('#')).count() > 100);
    assert!(!out.join("follower/builtin/failure.vcd").exists());
}

#[test]
fn shards_split_a_suite_across_jobs() {
    let dir = tempfile::tempdir().unwrap();
    let f = suite_file(dir.path());
    let mut designs = Vec::new();
    for k in ["1/2", "2/2"] {
        let out = dir.path().join(k.replace('/', "-"));
        let o = suite(&[f.to_str().unwrap(), "--shard", k, "--out", out.to_str().unwrap(), "-q"]);
        let report: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
        let runs = report["runs"].as_array().unwrap();
        assert_eq!(runs.len(), 1, "{k}: {}", String::from_utf8_lossy(&o.stderr));
        designs.push(runs[0]["design"].as_str().unwrap().to_string());
    }
    assert_eq!(designs, ["follower", "demo"]);
}

#[test]
fn a_bad_suite_file_is_one_error_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("bad.toml");
    std::fs::write(&f, "samples = 10\n[[design]]\nname = \"a\"\nsourcez = [\"x\"]\n").unwrap();
    let o = suite(&[f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.starts_with(&format!("{}:4:1: error:", f.display())), "{e}");
}
