//! Broken and unusual designs and options (issue 28): every one ends within a time bound, with
//! exit status 1 and one line that says what is wrong (the user's file:line:col where there is
//! one), or runs as Vivado would have it built. The designs are written here, each a few lines
//! around a `bot`; each is built once per cache (target/botsim-board-cache).

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::common;

use common::board_cache as cache;

/// `botsim board ARGS` in `dir` with the cache `cache`, stopped if it has not ended within
/// `budget` (a hang is a failure, not a stuck test); with the time it took.
fn board_within(dir: &Path, cache: &Path, args: &[&str], budget: Duration) -> (Output, Duration) {
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_botsim"))
        .arg("board")
        .args(args)
        .current_dir(dir)
        .env("BOTSIM_CACHE", cache)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if start.elapsed() > budget {
            let _ = child.kill();
            let o = child.wait_with_output().unwrap();
            panic!("botsim board {args:?} did not end within {budget:?}: {}", String::from_utf8_lossy(&o.stderr));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    (child.wait_with_output().unwrap(), start.elapsed())
}

/// A build and a short run take seconds; a minute is the bound of any of these.
const BOUND: Duration = Duration::from_secs(90);

fn board(dir: &Path, args: &[&str]) -> Output {
    board_within(dir, &cache(), args, BOUND).0
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The last line of a failed run's standard error (botsim's own; the design's printing and
/// the build's notes come before it), checked to be its only error line.
fn failure(o: &Output) -> String {
    assert_eq!(o.status.code(), Some(1), "{}", stderr(o));
    stderr(o).lines().last().unwrap_or("").to_string()
}

/// A folder with `top.v` (a `bot` is added inside the module) and other files.
fn design(top: &str, files: &[(&str, &[u8])]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let at = top.rfind("endmodule").unwrap();
    let text = format!("{}  bot ROJOBOT (.clk(clk), .reset(1'b0), .MotCtl_in(8'h00));\n{}", &top[..at], &top[at..]);
    std::fs::write(dir.path().join("top.v"), text).unwrap();
    for (name, bytes) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    dir
}

#[test]
fn a_combinational_loop_stops_with_the_signal_and_its_line_instead_of_hanging() {
    // Through two modules, and an `always` with no event: neither ever settles.
    let d = design(
        "module inv(input a, output y);\n  assign y = ~a;\nendmodule\n\
         module top(input clk, output [15:0] led);\n  wire a, b;\n  inv i1 (.a(a), .y(b));\n  inv i2 (.a(b), .y(a));\n\
         \x20 reg tog = 1'b0;\n  always tog = ~tog;\n  assign led = {14'd0, tog, a};\nendmodule\n",
        &[],
    );
    let (o, took) = board_within(d.path(), &cache(), &["top.v", "--seconds", "1"], BOUND);
    let e = failure(&o);
    assert!(
        e.contains("depends on itself (a combinational loop): the design never settles, stopped at 0.000000 ms"),
        "{e}"
    );
    assert!(e.starts_with("top.v:"), "{e}");
    assert!(took < BOUND, "{took:?}");
}

#[test]
fn failures_of_the_design_fail_the_run_with_their_file_and_line() {
    // One design, three ways to fail (chosen by the switches after the reset), a table read
    // from beside the source, and a byte-order mark, as Windows editors write.
    let top = "\u{feff}module top(input clk, input [15:0] sw, output [15:0] led);\n\
               \x20 reg [7:0] n = 8'd0;\n  reg [7:0] table_rom [0:3];\n\
               \x20 initial $readmemh(\"table.mem\", table_rom);\n\
               \x20 always @(posedge clk) begin\n    n <= n + 8'd1;\n\
               \x20   if (sw[0] && n == 8'd200) $fatal(1, \"n reached %0d\", n);\n\
               \x20   if (sw[1] && n == 8'd200) $stop;\n\
               \x20   if (sw[2] && n == 8'd200) $error(\"bad n\");\n  end\n\
               \x20 assign led = {table_rom[1], n};\nendmodule\n";
    let d = design(top, &[("table.mem", b"11 22 33 44\n")]);
    let o = board(d.path(), &[".", "--seconds", "0.0001", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["leds"].as_u64().unwrap() >> 8, 0x22, "the table beside the source: {summary}");
    let said = stderr(&board(d.path(), &[".", "--seconds", "0.0001"]));
    assert!(said.contains("top.v:4:21: reads \"table.mem\": beside the source, as Vivado reads it"), "{said}");
    for (sw, want) in [
        ("0001", "top.v:7: the design reported an error: n reached 200 (botsim stops at a design's first $error or $fatal, as Verilator does) (stopped at 0.002010 ms)"),
        ("0002", "top.v:8: the design called $stop (stopped at 0.002010 ms)"),
        ("0004", "top.v:9: the design reported an error: bad n (botsim stops at a design's first $error or $fatal, as Verilator does) (stopped at 0.002010 ms)"),
    ] {
        let e = failure(&board(d.path(), &[".", "--switches", sw, "--seconds", "0.001"]));
        assert_eq!(e, want);
    }
    // A table that is nowhere: one line before anything is built.
    std::fs::remove_file(d.path().join("table.mem")).unwrap();
    let e = failure(&board(d.path(), &["."]));
    assert_eq!(e, "top.v:4:21: $readmem reads \"table.mem\", which is not in the repository (add the file)");
}

#[test]
fn delays_simulate_and_the_designs_own_finish_ends_the_run() {
    let d = design(
        "module top(input clk, input [15:0] sw, output reg [15:0] led = 16'd0);\n\
         \x20 always @(posedge clk) led <= #1 sw;\n\
         \x20 initial #2_000_000 $finish;\nendmodule\n",
        &[],
    );
    let o = board(d.path(), &[".", "--switches", "00A5", "--seconds", "0.01", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        (s["stopped_by"].as_str(), s["leds"].as_u64(), s["simulated_seconds"].as_f64()),
        (Some("finish"), Some(0xA5), Some(0.002))
    );
    let said = stderr(&board(d.path(), &[".", "--seconds", "0.01"]));
    assert!(said.contains("note: top.v:2:32: the design has delays (#): botsim simulates them as written"), "{said}");
    assert!(said.contains("botsim board: the design called $finish at top.v:3 (2.000000 ms)"), "{said}");
    assert!(!said.contains("--timing"), "Verilator's option names are not botsim's: {said}");
}

#[test]
fn a_design_that_prints_every_clock_is_capped_and_the_summary_stands_alone() {
    let d = design(
        "module top(input clk, output [15:0] led);\n  reg [15:0] n = 16'd0;\n\
         \x20 always @(posedge clk) begin\n    n <= n + 16'd1;\n    $write(\"n=%0d \", n);\n    if (n[1:0] == 2'd3) $display(\"\");\n  end\n\
         \x20 assign led = n;\nendmodule\n",
        &[],
    );
    let log = d.path().join("design.log");
    let o = board(d.path(), &[".", "--seconds", "0.0001"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    let lines: Vec<&str> = e.lines().collect();
    assert!(lines.iter().filter(|l| l.starts_with("n=")).count() == 200, "{e}");
    assert!(e.contains(
        "botsim board: the design prints more than 200 lines; the rest is not shown (--design-log FILE keeps it all)"
    ));
    // The summary (standard output) is a line of its own; so is the JSON.
    assert!(
        String::from_utf8_lossy(&o.stdout).starts_with("simulated 0.000 s"),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    let o = board(d.path(), &[".", "--seconds", "0.0001", "--json", "--design-log", log.to_str().unwrap()]);
    let s: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(s["design_lines"], 2500, "{s}");
    assert_eq!(std::fs::read_to_string(&log).unwrap().lines().count(), 2500);
    // A waveform past its limit is removed, and the run says so.
    let vcd = d.path().join("w.vcd");
    let e = failure(&board(d.path(), &[".", "--vcd", vcd.to_str().unwrap(), "--vcd-max", "200K", "--seconds", "0.01"]));
    assert!(
        e.starts_with(&format!("{}: the waveform passed 0 MB at", vcd.display())) && e.contains("ask for a window"),
        "{e}"
    );
    assert!(!vcd.exists());
}

#[test]
fn bad_arguments_are_answered_by_botsim_before_anything_is_built() {
    let d = design(
        "module top #(parameter SIMULATE = 0) (input clk, output [15:0] led);\n  assign led = 16'd0;\nendmodule\n",
        &[],
    );
    let p = d.path();
    std::fs::write(p.join("broken.xpr"), "<Project>\n  <FileSets>\n</Project>\n").unwrap();
    std::fs::write(p.join("w.coe"), "memory_initialization_radix=2;\nmemory_initialization_vector=\n0,1,2,3;\n")
        .unwrap();
    for (args, want) in [
        (&["top.v", "--seconds", "-1"][..], "--seconds -1: expected a positive number of seconds of board time"),
        (&["top.v", "--seconds", "inf"], "--seconds inf: expected a positive number of seconds of board time"),
        (
            &["top.v", "--seconds", "1e9"],
            "--seconds 1000000000: more than 600 s of board time takes about as long to simulate, or longer; add --long to run it",
        ),
        (&["broken.xpr"], "broken.xpr:3:1: not a well-formed project file: expected 'FileSets' tag, not 'Project' at 3:1"),
        (&["top.v", "--map", "w.coe"], "w.coe:3:5: error: '2' is not a radix-2 number (the file's memory_initialization_radix)"),
        (&["top.v", "--param", "NO_SUCH=1"], "--param NO_SUCH: the top `top` (top.v:1) has no parameter NO_SUCH (its parameters: SIMULATE)"),
    ] {
        let (o, took) = board_within(p, &cache(), args, Duration::from_secs(10));
        assert_eq!(failure(&o), want, "{args:?}");
        assert!(took < Duration::from_secs(5), "{args:?}: {took:?}");
    }
}

/// The build folders of a cache (finished or not).
fn builds(cache: &Path) -> Vec<String> {
    std::fs::read_dir(cache.join("boards"))
        .map(|r| r.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect())
        .unwrap_or_default()
}

#[test]
fn ctrl_c_stops_a_build_whole_and_two_runs_share_one_build() {
    let d = design("module top(input clk, output [15:0] led);\n  assign led = 16'hBEEF;\nendmodule\n", &[]);
    let cache = tempfile::tempdir().unwrap();
    // Ctrl-C two seconds into the build: exit 130, its compilers gone with it, no folder left.
    let mut child = Command::new(env!("CARGO_BIN_EXE_botsim"))
        .args(["board", "top.v", "--seconds", "0.0001"])
        .current_dir(d.path())
        .env("BOTSIM_CACHE", cache.path())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_secs(2));
    // SAFETY: signals the child this test started.
    unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) };
    let status = common::exit_within(&mut child, Duration::from_secs(10), "Ctrl-C did not stop the build");
    assert_eq!(status.code(), Some(130));
    assert!(builds(cache.path()).is_empty(), "{:?}", builds(cache.path()));
    // No process of that build remains (the compilers ran in their own process group).
    let ps = Command::new("ps").args(["-eo", "pid,args"]).output().unwrap();
    let left: Vec<String> = String::from_utf8_lossy(&ps.stdout)
        .lines()
        .filter(|l| l.contains(cache.path().to_str().unwrap()) && !l.contains("<defunct>"))
        .map(str::to_string)
        .collect();
    assert!(left.is_empty(), "{left:?}");
    // Two runs at once: the second waits for the first's build and reuses it.
    let spawn = || {
        Command::new(env!("CARGO_BIN_EXE_botsim"))
            .args(["board", "top.v", "--seconds", "0.0001"])
            .current_dir(d.path())
            .env("BOTSIM_CACHE", cache.path())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let first = spawn();
    std::thread::sleep(Duration::from_millis(300));
    let second = spawn();
    let (a, b) = (first.wait_with_output().unwrap(), second.wait_with_output().unwrap());
    assert!(a.status.success() && b.status.success(), "{}\n{}", stderr(&a), stderr(&b));
    let built = [&a, &b].iter().filter(|o| stderr(o).contains("  built in ")).count();
    assert_eq!(built, 1, "{}\n{}", stderr(&a), stderr(&b));
    assert!(
        stderr(&b).contains("botsim board: waiting for another botsim that is building this design"),
        "{}",
        stderr(&b)
    );
}

/// Two processes driving one variable: Vivado reports it, and so does botsim, with the
/// line, and simulates the drivers as written (the run goes on).
#[test]
fn a_variable_with_two_drivers_is_reported_with_its_line_and_the_run_goes_on() {
    let d = design(
        "module top(input clk, input [15:0] sw, output [15:0] led);\n  reg shown = 1'b0;\n\
         \x20 always @(posedge clk) shown <= sw[0];\n  always @(negedge clk) shown <= sw[1];\n\
         \x20 assign led = {15'd0, shown};\nendmodule\n",
        &[],
    );
    let (o, took) = board_within(d.path(), &cache(), &["top.v", "--seconds", "0.002"], BOUND);
    let said = stderr(&o);
    assert!(o.status.success(), "{said}");
    let note = said.lines().find(|l| l.contains("more than one driver")).unwrap_or_else(|| panic!("{said}"));
    assert!(
        note.starts_with("note: top.v:2:") || note.starts_with("note: top.v:3:") || note.starts_with("note: top.v:4:"),
        "{note}"
    );
    assert!(took < BOUND, "{took:?}");
}

#[test]
fn verilators_errors_reach_the_user_in_botsims_words() {
    // A port the user's own module does not have: theirs, with the module's ports.
    let d = design(
        "module sub(input clk, output [15:0] y);\n  assign y = 16'h0;\nendmodule\nmodule nexys4fpga(input clk, output [15:0] led);\n  sub s (.clk(clk), .nope(1'b0), .y(led));\nendmodule\n",
        &[],
    );
    let e = failure(&board(d.path(), &["."]));
    // (Verilator's column: the port's name after its dot.)
    assert_eq!(e, "top.v:5:22: `sub` has no port `nope` (its ports: clk, y)");
    // A port botsim's model of a fixed part lacks: the design's, said against the part.
    let d = design(
        "module nexys4fpga(input clk, output [15:0] led);\n  wire [17:0] instruction;\n  kcpsm6 cpu (.clk(clk), .instruction(instruction), .turbo(1'b1));\nendmodule\n",
        &[],
    );
    let e = failure(&board(d.path(), &[".", "--cpu", "rtl"]));
    assert!(
        e.starts_with("top.v:3:54: `kcpsm6` has no port `turbo`: botsim's `kcpsm6` has the real one's (its ports: "),
        "{e}"
    );
    // A line that does not parse, as the user wrote it.
    let d = design("module nexys4fpga(input clk, output [15:0] led);\n  assign led = 16'h00 +;\nendmodule\n", &[]);
    let e = failure(&board(d.path(), &["."]));
    assert!(e.starts_with("top.v:2:") && e.contains("this does not parse (syntax error"), "{e}");
    // No Verilator words of its own asides.
    assert!(!e.contains("%Error") && !e.contains("verilator.org"), "{e}");
}

#[test]
fn a_core_narrower_than_the_design_connects_is_one_warning_said_as_vivado_builds_it() {
    // A ROM of 16 words (a 4-bit address, from its .xci) that the design addresses with 10
    // bits: the core reads the low 4 bits, as Vivado's would; botsim says so, as its own.
    let xci = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<spirit:design xmlns:xilinx=\"http://www.xilinx.com\" xmlns:spirit=\"http://www.spiritconsortium.org/XMLSchema/SPIRIT/1685-2009\">\n  <spirit:componentInstances>\n    <spirit:componentInstance>\n      <spirit:instanceName>rom16</spirit:instanceName>\n      <spirit:componentRef spirit:vendor=\"xilinx.com\" spirit:library=\"ip\" spirit:name=\"blk_mem_gen\" spirit:version=\"8.3\"/>\n      <spirit:configurableElementValues>\n        <spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.Component_Name\">rom16</spirit:configurableElementValue>\n        <spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.Memory_Type\">Single_Port_ROM</spirit:configurableElementValue>\n        <spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.Enable_A\">Always_Enabled</spirit:configurableElementValue>\n        <spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.Write_Depth_A\">16</spirit:configurableElementValue>\n        <spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.Write_Width_A\">8</spirit:configurableElementValue>\n        <spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.Read_Width_A\">8</spirit:configurableElementValue>\n        <spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.Load_Init_File\">false</spirit:configurableElementValue>\n      </spirit:configurableElementValues>\n    </spirit:componentInstance>\n  </spirit:componentInstances>\n</spirit:design>\n";
    let d = design(
        "module nexys4fpga(input clk, input [15:0] sw, output [15:0] led);\n  wire [7:0] q;\n  rom16 ROM (.clka(clk), .addra(sw[9:0]), .douta(q));\n  assign led = {8'd0, q};\nendmodule\n",
        &[("rom16.xci", xci.as_bytes())],
    );
    let o = board(d.path(), &[".", "--seconds", "0.0001"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    let line = e.lines().find(|l| l.contains("addra")).unwrap_or_else(|| panic!("{e}"));
    assert!(
        line.starts_with("warning: top.v:3:")
            && line.contains(
                "the design connects 10 bits to `addra` of `rom16`, 4 bits wide in a Block Memory Generator core"
            )
            && line.ends_with(": as Vivado builds it, the design's upper 6 bits are dropped"),
        "{line}"
    );
    // The width is the design's configuration's: not botsim's to be reported.
    assert!(!e.contains("%Warning") && !e.contains("please report"), "{e}");
}

#[test]
fn botsim_keep_generated_keeps_every_file_of_a_build_that_fails() {
    // A line Verilator cannot parse: the build stops; what botsim wrote for it is kept (the
    // user's file edited: its unnamed instance named).
    let d = design(
        "module nexys4fpga(input clk, output [15:0] led);\n  sub (.a(clk));\n  assign led = 16'h00 +;\nendmodule\nmodule sub(input a);\nendmodule\n",
        &[],
    );
    let keep = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_botsim"))
        .args(["board", "."])
        .current_dir(d.path())
        .env("BOTSIM_CACHE", cache())
        .env("BOTSIM_KEEP_GENERATED", keep.path())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let kept: Vec<String> = std::fs::read_dir(keep.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    for file in ["botsim_board.sv", "harness.cpp", "botsim_kcpsm6.sv"] {
        assert!(kept.iter().any(|k| k == file), "{file} not kept: {kept:?}");
    }
    // The user's file, as botsim compiled it.
    let user = kept.iter().find(|k| k.contains("top")).unwrap_or_else(|| panic!("{kept:?}"));
    assert!(std::fs::read_to_string(keep.path().join(user)).unwrap().contains("sub sub_2 ("));
}

#[test]
fn a_parameter_declaration_that_does_not_parse_is_said_at_its_line_not_as_a_missing_parameter() {
    // A typo in the top's SIMULATE parameter (issue 41's mutants): the run with --param
    // SIMULATE=1 says where the line is wrong, not that the top has no such parameter.
    for decl in ["  parameter SIMULATE <= 0;\n", "  localparam W = 2; parameter SIMULATE 0;\n"] {
        let d = design(
            &format!("module nexys4fpga(input clk, output [15:0] led);\n{decl}  assign led = 16'h0;\nendmodule\n"),
            &[],
        );
        let e = failure(&board(d.path(), &[".", "--param", "SIMULATE=1", "--seconds", "0.0001"]));
        assert!(e.starts_with("top.v:2:") && e.contains("does not parse"), "{decl}: {e}");
    }
    // A top that has none is still told so.
    let d = design("module nexys4fpga(input clk, output [15:0] led);\n  assign led = 16'h0;\nendmodule\n", &[]);
    let e = failure(&board(d.path(), &[".", "--param", "SIMULATE=1"]));
    assert!(e.contains("has no parameter SIMULATE (its parameters: none)"), "{e}");
}
