//! `botsim suite`: a course's check of many board designs on many maps, run in parallel.
//!
//! A suite file (TOML) names the designs (their sources and options), the maps, what every
//! run must show, and the options common to all. Every design × map is one `botsim board`
//! run in a process of its own (its own model; a crash stays in its run), `-j` at a time;
//! each run's trace, path picture and display log are kept in `OUT/<design>/<map>/`, and a
//! failed run is run again to keep a waveform of the samples around its failure. The table
//! goes to stdout, `OUT/report.json` and `OUT/junit.xml` (the JUnit XML that CI systems
//! display) are written at the end, and the exit status is 1 when any run failed.
//!
//! ```toml
//! samples = 6000                          # each run's budget, in bot samples
//! expect = ["line-end", "never-blocked"]  # what every run must show
//! cpu = "iss"                             # rtl, iss or lockstep
//! args = ["--timing", "hw", "--compat", "botsim20"]
//!
//! [[design]]
//! name = "team01"
//! sources = ["team01/src"]                # relative to this file
//! args = ["--param", "SIMULATE=1"]
//!
//! [[map]]
//! name = "builtin"                        # no file: the built-in course
//! [[map]]
//! name = "lr"
//! file = "maps/world_map_lr.txt"
//! ```

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use botsim::files::write_atomic;
use serde::Deserialize;

/// Run a suite of board designs × maps in parallel, with a summary table, a JSON report and
/// a JUnit XML report.
#[derive(clap::Args)]
#[command(after_help = "Examples:
  botsim suite course.toml -j 2
  botsim suite course.toml --shard 1/4 --out results-1")]
pub struct Args {
    /// The suite file (TOML: designs, maps, expectations; see docs/SUITE.md)
    #[arg(value_name = "SUITE")]
    suite: PathBuf,
    /// Runs at once [default: the machine's cores]
    #[arg(short = 'j', long, value_name = "N")]
    jobs: Option<usize>,
    /// The folder for the reports and every run's files
    #[arg(long, value_name = "DIR", default_value = "botsim-suite")]
    out: PathBuf,
    /// Only the runs of shard K of N (1-based), to split one suite across CI jobs
    #[arg(long, value_name = "K/N")]
    shard: Option<String>,
    /// Print only failures
    #[arg(short, long)]
    quiet: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SuiteFile {
    /// Each run's budget in bot samples.
    samples: u64,
    #[serde(default)]
    expect: Vec<Expect>,
    #[serde(default)]
    cpu: Option<String>,
    #[serde(default)]
    args: Vec<String>,
    design: Vec<Design>,
    map: Vec<MapEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Design {
    name: String,
    sources: Vec<PathBuf>,
    #[serde(default)]
    args: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MapEntry {
    name: String,
    #[serde(default)]
    file: Option<PathBuf>,
}

/// What a run must show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum Expect {
    /// The bot reaches the end of the line (stopped on it, a wall ahead) within the budget.
    LineEnd,
    /// The world never refuses a move (the bot never drives into an obstruction).
    NeverBlocked,
}

/// One design on one map.
struct Run {
    design: usize,
    map: usize,
    dir: PathBuf,
}

/// How a run ended.
#[derive(Clone, Debug, Default)]
struct Outcome {
    passed: bool,
    /// Why it failed, one line.
    failure: Option<String>,
    samples: u64,
    simulated_seconds: f64,
    wall_seconds: f64,
    end: String,
    /// The summary `botsim board --json` printed.
    summary: serde_json::Value,
}

pub fn run(a: Args) -> Result<(), String> {
    botsim::interrupt::catch();
    let text =
        std::fs::read_to_string(&a.suite).map_err(|e| format!("{}: error: cannot read: {e}", a.suite.display()))?;
    let suite: SuiteFile = toml::from_str(&text).map_err(|e| {
        let (line, col) = e.span().map_or((0, 0), |s| line_col(&text, s.start));
        format!("{}:{line}:{col}: error: {}", a.suite.display(), e.message())
    })?;
    // Every run works in the suite file's folder: its paths (and those in `args`) are
    // relative to it; the outputs go where --out says from here.
    let base =
        a.suite.parent().filter(|p| !p.as_os_str().is_empty()).map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let out = std::path::absolute(&a.out).map_err(|e| format!("{}: error: {e}", a.out.display()))?;
    let cpu = suite.cpu.clone().unwrap_or_else(|| "iss".into());
    if !matches!(cpu.as_str(), "rtl" | "iss" | "lockstep") {
        return Err(format!("{}: error: cpu = \"{cpu}\": expected rtl, iss or lockstep", a.suite.display()));
    }
    for (what, names) in [("design", names(&suite.design, |d| &d.name)), ("map", names(&suite.map, |m| &m.name))] {
        if let Some(n) = names.iter().enumerate().find(|(i, n)| names[..*i].contains(n)).map(|(_, n)| n) {
            return Err(format!("{}: error: two {what}s are named `{n}`", a.suite.display()));
        }
    }
    let (shard, shards) = match &a.shard {
        Some(s) => parse_shard(s)?,
        None => (1, 1),
    };
    let jobs = a.jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())).max(1);

    let mut runs = Vec::new();
    for (d, design) in suite.design.iter().enumerate() {
        for (m, map) in suite.map.iter().enumerate() {
            // Run k of all the suite's runs goes to shard k mod N.
            let k = d * suite.map.len() + m;
            if k % shards == shard - 1 {
                runs.push(Run { design: d, map: m, dir: out.join(&design.name).join(&map.name) });
            }
        }
    }
    let t0 = Instant::now();
    let exe = std::env::current_exe().map_err(|e| format!("cannot find botsim itself: {e}"))?;
    let board_args = |d: &Design| -> Vec<String> {
        let mut v: Vec<String> = vec!["board".into()];
        v.extend(d.sources.iter().map(|s| s.display().to_string()));
        v.extend(suite.args.iter().cloned());
        v.extend(d.args.iter().cloned());
        v.extend(["--cpu".to_string(), cpu.clone()]);
        v
    };

    // Every design is built once (in parallel), before its runs share the build.
    let designs: Vec<usize> = {
        let mut v: Vec<usize> = runs.iter().map(|r| r.design).collect();
        v.dedup();
        v
    };
    let build_errors: Vec<Option<String>> = parallel(designs.len(), jobs, |i| {
        let d = &suite.design[designs[i]];
        let mut args = board_args(d);
        args.extend(["--build-only".into(), "-q".into()]);
        let o = Command::new(&exe).args(&args).current_dir(&base).output();
        match o {
            Ok(o) if o.status.success() => None,
            Ok(o) => Some(last_line(&o.stderr)),
            Err(e) => Some(format!("cannot run botsim: {e}")),
        }
    });
    if !a.quiet {
        eprintln!(
            "botsim suite: {} runs ({} designs x {} maps{}), {jobs} at a time, designs built in {:.1} s",
            runs.len(),
            designs.len(),
            suite.map.len(),
            if shards > 1 { format!(", shard {shard} of {shards}") } else { String::new() },
            t0.elapsed().as_secs_f64()
        );
    }

    let printed = Mutex::new(());
    let outcomes: Vec<Outcome> = parallel(runs.len(), jobs, |i| {
        let r = &runs[i];
        let (design, map) = (&suite.design[r.design], &suite.map[r.map]);
        let built = designs.iter().position(|&d| d == r.design).and_then(|k| build_errors[k].clone());
        let outcome = match built {
            Some(e) => Outcome { failure: Some(format!("build: {e}")), ..Outcome::default() },
            None => one_run(&exe, &base, board_args(design), map.file.clone(), r, &suite),
        };
        if !a.quiet || !outcome.passed {
            let _guard = printed.lock();
            println!("{}", row(&design.name, &map.name, &outcome));
        }
        outcome
    });

    let failed = outcomes.iter().filter(|o| !o.passed).count();
    let wall = t0.elapsed().as_secs_f64();
    let report: Vec<serde_json::Value> = runs
        .iter()
        .zip(&outcomes)
        .map(|(r, o)| {
            serde_json::json!({
                "design": suite.design[r.design].name, "map": suite.map[r.map].name,
                "passed": o.passed, "failure": o.failure, "samples": o.samples,
                "simulated_seconds": o.simulated_seconds, "wall_seconds": o.wall_seconds,
                "files": r.dir, "summary": o.summary,
            })
        })
        .collect();
    let json = serde_json::json!({
        "suite": a.suite, "runs": report, "failed": failed, "jobs": jobs,
        "shard": [shard, shards], "wall_seconds": wall,
    });
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: error: cannot create: {e}", out.display()))?;
    write_atomic(&out.join("report.json"), format!("{json:#}\n").as_bytes())?;
    write_atomic(&out.join("junit.xml"), junit(&suite, &runs, &outcomes, wall).as_bytes())?;
    if !a.quiet {
        eprintln!(
            "botsim suite: {} passed, {failed} failed in {wall:.1} s; reports in {}",
            outcomes.len() - failed,
            a.out.display()
        );
    }
    if failed > 0 {
        return Err(format!("botsim suite: {failed} of {} runs failed", outcomes.len()));
    }
    Ok(())
}

fn names<T>(v: &[T], f: impl Fn(&T) -> &String) -> Vec<String> {
    v.iter().map(|x| f(x).clone()).collect()
}

/// `K/N`, 1 <= K <= N.
fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("--shard {s}: expected K/N with 1 <= K <= N (e.g. 2/4)");
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let (k, n): (usize, usize) = (k.parse().map_err(|_| bad())?, n.parse().map_err(|_| bad())?);
    if k == 0 || k > n {
        return Err(bad());
    }
    Ok((k, n))
}

/// Line and column (1-based) of byte `at` in `text`.
fn line_col(text: &str, at: usize) -> (usize, usize) {
    let before = &text[..at.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, col)
}

/// `f(0..n)` on `jobs` threads; the results in order.
fn parallel<T: Send + Default + Clone>(n: usize, jobs: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let next = AtomicUsize::new(0);
    let results = Mutex::new(vec![T::default(); n]);
    std::thread::scope(|s| {
        for _ in 0..jobs.min(n) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= n || crate::cli::interrupted() {
                    break;
                }
                let r = f(i);
                results.lock().unwrap_or_else(|p| p.into_inner())[i] = r;
            });
        }
    });
    results.into_inner().unwrap_or_else(|p| p.into_inner())
}

fn last_line(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("").trim().to_string()
}

/// One run, and on failure a second one that keeps the waveform around it.
fn one_run(
    exe: &Path,
    base: &Path,
    mut args: Vec<String>,
    map: Option<PathBuf>,
    r: &Run,
    suite: &SuiteFile,
) -> Outcome {
    if let Err(e) = std::fs::create_dir_all(&r.dir) {
        return Outcome { failure: Some(format!("{}: cannot create: {e}", r.dir.display())), ..Outcome::default() };
    }
    if let Some(m) = &map {
        args.extend(["--map".into(), m.display().to_string()]);
    }
    let file = |n: &str| r.dir.join(n).display().to_string();
    let mut run_args = args.clone();
    run_args.extend(["--samples".into(), suite.samples.to_string(), "--json".into()]);
    // A run stops as soon as its outcome is known: at the end of the line, or at the first
    // refused move when that fails the check (the rest of the budget would change nothing).
    if suite.expect.contains(&Expect::LineEnd) {
        run_args.push("--stop-at-line-end".into());
    }
    if suite.expect.contains(&Expect::NeverBlocked) {
        run_args.push("--stop-when-blocked".into());
    }
    for (opt, name) in [("--trace-csv", "trace.csv"), ("--png", "path.png"), ("--display", "display.txt")] {
        run_args.extend([opt.into(), file(name)]);
    }
    let t = Instant::now();
    let o = match Command::new(exe).args(&run_args).current_dir(base).output() {
        Ok(o) => o,
        Err(e) => return Outcome { failure: Some(format!("cannot run botsim: {e}")), ..Outcome::default() },
    };
    let wall_seconds = t.elapsed().as_secs_f64();
    if !o.status.success() {
        return Outcome { failure: Some(last_line(&o.stderr)), wall_seconds, ..Outcome::default() };
    }
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap_or_default();
    let samples = summary["samples"].as_u64().unwrap_or(0);
    let e = &summary["end"];
    let end = if e.is_object() {
        format!(
            "({}, {}) {} {}",
            e["loc_x"],
            e["loc_y"],
            e["orientation"].as_str().unwrap_or(""),
            e["movement"].as_str().unwrap_or("")
        )
    } else {
        "no sample".into()
    };
    // The first expectation that failed, and the sample to keep the waveform around.
    let mut failure = None;
    for x in &suite.expect {
        match x {
            Expect::NeverBlocked => {
                if let Some(k) = summary["first_blocked_sample"].as_u64() {
                    failure = Some((format!("the world refused a move at sample {k}"), k));
                    break;
                }
            }
            // A run stopped at a refused move has not used its budget: its failure is that.
            Expect::LineEnd if summary["stopped_by"] == "blocked" => {}
            Expect::LineEnd => {
                if summary["stopped_by"] != "line-end" {
                    let why =
                        format!("did not reach the end of the line within {} samples: ended at {end}", suite.samples);
                    failure = Some((why, samples.saturating_sub(1)));
                    break;
                }
            }
        }
    }
    if let Some((_, k)) = &failure {
        // The same run again, to the failure and its next sample, with the waveform around it:
        // from the sample before to the one after, at most 0.5 ms before and 1 ms after (at
        // hw timing a sample is 53 ms of every signal: gigabytes).
        let (from, to) = failure_window(&std::fs::read_to_string(file("trace.csv")).unwrap_or_default(), *k);
        let mut again = args;
        again.extend([
            "--samples".into(),
            (k + 1).to_string(),
            "--vcd".into(),
            file("failure.vcd"),
            "--trace-from".into(),
            format!("{from}c"),
            "--trace-to".into(),
            format!("{to}c"),
            "-q".into(),
        ]);
        let _ = Command::new(exe).args(&again).current_dir(base).output();
    }
    Outcome {
        passed: failure.is_none(),
        failure: failure.map(|(w, _)| w),
        samples,
        simulated_seconds: summary["simulated_seconds"].as_f64().unwrap_or(0.0),
        wall_seconds,
        end,
        summary,
    }
}

/// The failure waveform's window around sample `k`, in cycles of the 100 MHz clock, from a
/// run's `--trace-csv` (`sample,cycle,...`): from sample `k - 1` to as far after `k`, at most
/// 50,000 cycles before and 100,000 after.
fn failure_window(trace_csv: &str, k: u64) -> (u64, u64) {
    let cycle = |n: u64| {
        trace_csv.lines().skip(1).find_map(|l| {
            let mut f = l.split(',');
            (f.next()?.parse::<u64>().ok()? == n).then(|| f.next()?.parse::<u64>().ok()).flatten()
        })
    };
    let at = cycle(k).unwrap_or(0);
    let gap = k.checked_sub(1).and_then(cycle).map_or(50_000, |before| at - before.min(at));
    (at - gap.min(50_000).min(at), at + gap.min(100_000))
}

fn row(design: &str, map: &str, o: &Outcome) -> String {
    let result = if o.passed { "pass" } else { "FAIL" };
    let what = o.failure.clone().unwrap_or_else(|| format!("ended at {}", o.end));
    format!(
        "{result}  {design:<16} {map:<14} {:>6} samples {:>9.3} s simulated {:>7.1} s  {what}",
        o.samples, o.simulated_seconds, o.wall_seconds
    )
}

/// XML text with the five special characters escaped.
fn xml(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;").replace('\'', "&apos;")
}

/// The JUnit XML report: one test suite per design, one test case per map.
fn junit(suite: &SuiteFile, runs: &[Run], outcomes: &[Outcome], wall: f64) -> String {
    let failed = outcomes.iter().filter(|o| !o.passed).count();
    let mut x = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"botsim suite\" tests=\"{}\" failures=\"{failed}\" time=\"{wall:.3}\">\n",
        runs.len()
    );
    for (d, design) in suite.design.iter().enumerate() {
        let mine: Vec<(&Run, &Outcome)> = runs.iter().zip(outcomes).filter(|(r, _)| r.design == d).collect();
        if mine.is_empty() {
            continue;
        }
        let f = mine.iter().filter(|(_, o)| !o.passed).count();
        let t: f64 = mine.iter().map(|(_, o)| o.wall_seconds).sum();
        x.push_str(&format!(
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{f}\" time=\"{t:.3}\">\n",
            xml(&design.name),
            mine.len()
        ));
        for (r, o) in mine {
            x.push_str(&format!(
                "    <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\">\n",
                xml(&design.name),
                xml(&suite.map[r.map].name),
                o.wall_seconds
            ));
            if let Some(why) = &o.failure {
                x.push_str(&format!(
                    "      <failure message=\"{}\">files: {}</failure>\n",
                    xml(why),
                    xml(&r.dir.display().to_string())
                ));
            }
            x.push_str(&format!(
                "      <system-out>{} samples, {:.3} s simulated, ended at {}</system-out>\n    </testcase>\n",
                o.samples,
                o.simulated_seconds,
                xml(&o.end)
            ));
        }
        x.push_str("  </testsuite>\n");
    }
    x.push_str("</testsuites>\n");
    x
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_failure_window_is_two_samples_or_1_5_ms() {
        let fast = "sample,cycle,loc_x\n0,100293,64\n1,100539,64\n2,102600,64\n";
        assert_eq!(super::failure_window(fast, 2), (100_539, 104_661));
        let hw = "sample,cycle,loc_x\n0,100293,64\n1,100539,64\n2,5413799,64\n";
        assert_eq!(super::failure_window(hw, 2), (5_363_799, 5_513_799));
        assert_eq!(super::failure_window(hw, 0), (50_293, 100_293 + 50_000));
    }

    use super::*;

    #[test]
    fn shards_split_the_runs_and_reject_nonsense() {
        assert_eq!(parse_shard("2/4"), Ok((2, 4)));
        for bad in ["0/4", "5/4", "x/2", "3"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn xml_escapes_what_it_must() {
        assert_eq!(xml("a<b & \"c\"'"), "a&lt;b &amp; &quot;c&quot;&apos;");
    }

    #[test]
    fn line_and_column_of_a_byte() {
        assert_eq!(line_col("ab\ncd", 4), (2, 2));
        assert_eq!(line_col("ab", 0), (1, 1));
    }
}
