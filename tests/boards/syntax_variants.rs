//! The metamorphic test of botsim's reading of Verilog (tests/common/variants.rs): a design
//! re-emitted with the white space Verilog allows removed (`bot(`, `#(`, `a<=b;`) or added
//! (line breaks inside statements, block comments between tokens, `(* keep *)` before items),
//! or with a trailing comma in every list Vivado reads one in (`.over(over),` then `);`, a
//! module's ports, an instance's parameter overrides), must run exactly as the original: the same bot samples, the same display and pins, the
//! same summary.
//!
//! Designs: a team's repository with an unnamed bot, the example VGA design, and
//! `BOTSIM_VARIANT_DESIGNS` (default 1) random designs from seed `BOTSIM_VARIANT_SEED`
//! (default 11). On the restored corpus (scripts/dev/corpus.py restore), locally:
//! `BOTSIM_CORPUS=../corpus cargo test --release --test boards syntax_variants:: -- --ignored`.

use std::path::{Path, PathBuf};

use crate::common;

use common::variants::{tokens, variant, Style};
use common::{board_in, root, stderr};

/// Every Verilog file under `dir` (not `.git`) re-emitted in `style`.
fn rewrite_tree(dir: &Path, style: Style) -> usize {
    let mut n = 0;
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() && p.file_name().is_some_and(|f| f != ".git") {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x.eq_ignore_ascii_case("v")) {
                // Teams' files are not always UTF-8 (comments in Latin-1): those as they are.
                if let Ok(text) = std::fs::read_to_string(&p) {
                    std::fs::write(&p, variant(&text, style, n as u64 + 1)).unwrap();
                    n += 1;
                }
            }
        }
    }
    n
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap().flatten() {
        let (p, q) = (e.path(), to.join(e.file_name()));
        if p.is_dir() {
            copy_tree(&p, &q);
        } else {
            std::fs::copy(&p, &q).unwrap();
        }
    }
}

/// What a run recorded that a syntax variant must not change.
#[derive(Debug, PartialEq)]
struct Record {
    trace: String,
    display: String,
    pins: String,
    summary: serde_json::Value,
}

fn record(dir: &Path, inputs: &[&str], args: &[&str], out: &Path, bot: bool) -> Record {
    std::fs::create_dir_all(out).unwrap();
    let file = |n: &str| out.join(n).to_str().unwrap().to_string();
    let (trace, display, pins) = (file("trace.csv"), file("display.txt"), file("pins.csv"));
    let mut all: Vec<&str> = inputs.to_vec();
    all.extend(args);
    all.extend(["--display", &display, "--pins", &pins, "--json"]);
    if bot {
        all.extend(["--trace-csv", &trace]);
    }
    let o = board_in(dir, &all);
    assert!(o.status.success(), "{}: {}", dir.display(), stderr(&o));
    let mut summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // What depends on the machine, not the design.
    for k in ["wall_seconds", "build_seconds", "design_lines", "verilator"] {
        summary.as_object_mut().unwrap().remove(k);
    }
    // The name botsim gives an unnamed instance says its line (`bot_64`), which a variant
    // moves: each bot's path without it.
    for b in summary["bots"].as_array_mut().into_iter().flatten() {
        if let Some(p) = b["path"].as_str() {
            let unlined = p.trim_end_matches(|c: char| c.is_ascii_digit()).to_string();
            b["path"] = unlined.into();
        }
    }
    // What kept the fast-forward busy is named at its line, which a variant moves.
    if let Some(busy) = summary["fast_forward"]["kept_busy_by"].as_object_mut() {
        busy.remove("line");
    }
    let read = |p: &str| std::fs::read_to_string(p).unwrap_or_default();
    Record { trace: read(&trace), display: read(&display), pins: read(&pins), summary }
}

/// The original design in `dir` and its two variants run with `args`; each variant's record
/// equals the original's.
fn variants_run_as_the_original(name: &str, dir: &Path, inputs: &[&str], args: &[&str], bot: bool) {
    let work = root().join("target/syntax-variants").join(name);
    let _ = std::fs::remove_dir_all(&work);
    let original = record(dir, inputs, args, &work.join("original"), bot);
    assert!(!bot || original.trace.lines().count() >= 2 || original.summary["samples"] == 0, "{name}: no sample");
    // The variants outside any git work tree (a project's repository is its work tree: under
    // target/ it would be botsim's own), kept for a failure's message.
    let designs = std::env::temp_dir().join("botsim-syntax-variants").join(name);
    let _ = std::fs::remove_dir_all(&designs);
    for style in [Style::Tight, Style::Loose, Style::Commas] {
        let copy = designs.join(format!("{style:?}").to_lowercase()).join("design");
        copy_tree(dir, &copy);
        let files = rewrite_tree(&copy, style);
        assert!(files > 0, "{name}: no Verilog file");
        let got = record(&copy, inputs, args, &work.join(format!("{style:?}").to_lowercase()), bot);
        for (what, a, b) in [
            ("--trace-csv", &original.trace, &got.trace),
            ("--display", &original.display, &got.display),
            ("--pins", &original.pins, &got.pins),
        ] {
            let i = a.lines().zip(b.lines()).position(|(x, y)| x != y);
            assert!(a == b, "{name}, {style:?} ({}): {what} differs at row {i:?}", copy.display());
        }
        assert_eq!(original.summary, got.summary, "{name}, {style:?} ({}): the summaries differ", copy.display());
        eprintln!("{name}: {style:?} ({files} files re-emitted) runs as the original");
    }
    // Kept for a failure only.
    let _ = std::fs::remove_dir_all(&designs);
    let _ = std::fs::remove_dir_all(&work);
}

#[test]
fn the_tight_variant_writes_what_students_write_and_both_keep_every_token() {
    let src = "`timescale 1ns / 1ps\nmodule m #(parameter N = 8'h0A) (input clk, output reg [3:0] q);\n  // a comment\n  always @(*) q <= (q == 4'b1111) ? 1'b0 : q + 1'b1; /* x */\n  bot (.clk(clk));\n  sub # (.W(2)) u ( .a (b) );\n  assign \\bus[0] = 32'd4_000_000 / 2;\nendmodule\n";
    let tight = variant(src, Style::Tight, 1);
    assert!(
        tight.starts_with(
            "`timescale 1ns / 1ps\nmodule m#(parameter N=8'h0A)(input clk,output reg[3:0]q);// a comment\n"
        ),
        "{tight}"
    );
    assert!(
        tight.contains("always@( * )q<=(q==4'b1111)?1'b0:q+1'b1;/* x */bot(.clk(clk));sub#(.W(2))u(.a(b));"),
        "{tight}"
    );
    assert!(tight.contains("assign \\bus[0] =32'd4_000_000/2;endmodule"), "{tight}");
    let loose = variant(src, Style::Loose, 3);
    assert!(loose.contains("(* keep = \"true\" *) always @ ( * )"), "{loose}");
    let attribute = tokens("(* keep = \"true\" *)");
    for (style, v) in [(Style::Tight, tight), (Style::Loose, loose)] {
        let mut got = tokens(&v);
        // The loose variant's own attributes aside.
        let mut k = 0;
        while k + attribute.len() <= got.len() {
            if got[k..k + attribute.len()] == attribute[..] {
                got.drain(k..k + attribute.len());
            } else {
                k += 1;
            }
        }
        assert_eq!(got, tokens(src), "{style:?}:\n{v}");
    }
    // A trailing comma in the named lists and the module's ports, none in a positional list
    // or a call.
    let commas = variant(src, Style::Commas, 1);
    assert!(
        commas.contains("module m # ( parameter N = 8'h0A ) ( input clk , output reg [ 3 : 0 ] q , ) ;"),
        "{commas}"
    );
    assert!(commas.contains("bot ( . clk ( clk ) , ) ;"), "{commas}");
    assert!(commas.contains("sub # ( . W ( 2 ) , ) u ( . a ( b ) , ) ;"), "{commas}");
    assert!(commas.contains("? 1'b0 : q + 1'b1 ;"), "{commas}");
    // Operators that would merge are kept apart.
    assert_eq!(variant("a <= - b;", Style::Tight, 1), "a<=-b;\n");
    assert_eq!(variant("x = y / /* c */ z;", Style::Tight, 1), "x=y/ /* c */z;\n");
    assert_eq!(variant("x = a & & b;", Style::Tight, 1), "x=a& &b;\n");
}

#[test]
fn a_repository_with_an_unnamed_bot_runs_the_same_written_tight_or_loose() {
    let clone = common::repo::clone_of("unnamed_bot");
    variants_run_as_the_original(
        "unnamed_bot",
        clone.path(),
        &["."],
        &["--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.03"],
        true,
    );
}

#[test]
fn the_example_vga_design_runs_the_same_written_tight_or_loose() {
    let dir = tempfile::tempdir().unwrap();
    for part in ["common", "nexys4_vga"] {
        copy_tree(&root().join("examples").join(part), &dir.path().join(part));
    }
    variants_run_as_the_original(
        "nexys4_vga",
        dir.path(),
        &["common", "nexys4_vga"],
        &["--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.02"],
        true,
    );
}

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

#[test]
fn random_designs_run_the_same_written_tight_or_loose() {
    let first = env("BOTSIM_VARIANT_SEED", 11);
    for seed in first..first + env("BOTSIM_VARIANT_DESIGNS", 1) {
        let d = common::random_design::generate(seed);
        let dir = tempfile::tempdir().unwrap();
        d.write(dir.path());
        let simulate = format!("SIMULATE={}", d.simulate as u8);
        let seconds = d.seconds.min(0.02).to_string();
        variants_run_as_the_original(
            &format!("random-{seed}"),
            dir.path(),
            &["."],
            &["--param", &simulate, "--seconds", &seconds, "--stimulus", "stimulus.txt"],
            true,
        );
    }
}

/// The restored corpus (scripts/dev/corpus.py restore): every repository of
/// ../shared/corpus/repos.toml that runs, with its options, for 0.01 s of board time.
#[test]
#[ignore = "local: needs the restored corpus (BOTSIM_CORPUS)"]
fn the_corpus_runs_the_same_written_tight_or_loose() {
    let corpus = PathBuf::from(std::env::var("BOTSIM_CORPUS").expect("BOTSIM_CORPUS: the restored clones' folder"));
    let list: toml::Value =
        toml::from_str(&std::fs::read_to_string(root().join("../shared/corpus/repos.toml")).unwrap()).unwrap();
    let only = std::env::var("BOTSIM_CORPUS_ONLY").ok();
    for repo in list["repo"].as_array().unwrap() {
        let name = repo["name"].as_str().unwrap();
        if repo["expect"].as_str() == Some("refused")
            || only.as_deref().is_some_and(|o| !o.split(',').any(|n| n == name))
        {
            continue;
        }
        let clone = corpus.join(name);
        let run = repo["run"].as_str().unwrap();
        let mut args: Vec<String> = repo
            .get("args")
            .and_then(|a| a.as_array())
            .into_iter()
            .flatten()
            .map(|a| a.as_str().unwrap().to_string())
            .collect();
        args.extend(["--seconds".into(), "0.01".into()]);
        // SIMULATE=1 where the top has it: tried, and left out when botsim says it has none.
        let probe = board_in(&clone, &[run, "--param", "SIMULATE=1", "--seconds", "0.0001"]);
        if !stderr(&probe).contains("no parameter SIMULATE") {
            args.extend(["--param".into(), "SIMULATE=1".into()]);
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let mut all = vec![run];
        all.extend(&args);
        let probe = board_in(&clone, &all);
        if !probe.status.success() {
            eprintln!("{name}: does not run as committed with its options (docs/ECOSYSTEM.md): left out");
            continue;
        }
        let bot = stderr(&probe).contains("bot at `");
        let dir = tempfile::tempdir().unwrap();
        copy_tree(&clone, dir.path());
        variants_run_as_the_original(name, dir.path(), &[run], &args, bot);
    }
}
