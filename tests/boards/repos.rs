//! `botsim board` on repositories as teams commit them (tests/board_designs/repos, built into
//! real git clones by tests/common/repo.rs): a team runs `botsim board <clone>` (or names its
//! project file) and the design runs, every decision said in a line of its own, or stops with
//! one message that says what to add. Each shape of issue 26 has its own repository.

use std::path::Path;
use std::process::Output;

use crate::common;

use common::repo::{clone_of, clone_renamed};

use common::{board_in, stderr};

/// The `--json` summary of a run that must have succeeded, and its messages.
fn summary(o: &Output) -> (serde_json::Value, String) {
    assert!(o.status.success(), "{}", stderr(o));
    (serde_json::from_slice(&o.stdout).unwrap(), stderr(o))
}

/// The messages of a run asked for JSON are on standard error only when not `--json`; these
/// tests ask for both: the summary from a `--json` run, the lines from the same run without.
fn run(dir: &Path, args: &[&str]) -> (serde_json::Value, String) {
    let (s, said, _) = run_told(dir, args);
    (s, said)
}

/// As [`run`], with what the run without `--json` told on standard output too.
fn run_told(dir: &Path, args: &[&str]) -> (serde_json::Value, String, String) {
    let mut with_json = args.to_vec();
    with_json.push("--json");
    let (s, _) = summary(&board_in(dir, &with_json));
    let o = board_in(dir, args);
    assert!(o.status.success(), "{}", stderr(&o));
    (s, stderr(&o), String::from_utf8_lossy(&o.stdout).into_owned())
}

/// The display the example firmware shows for the bot's registers after `samples` samples
/// at fast timing, driving forward: LocX on digits 7-6, LocY on 5-4, the heading on digit 0.
fn shows_the_bot(summary: &serde_json::Value) {
    let display = summary["display"].as_str().unwrap();
    assert_eq!(display.len(), 8, "{summary}");
    assert!(display.ends_with("40   2"), "the bot at (x, 64) facing east: {summary}");
}

#[test]
fn a_repository_with_the_release_folder_stale_copies_and_a_testbench_runs_as_committed() {
    let clone = clone_of("release_stale");
    let c = clone.path();
    let (s, said) = run(c, &[".", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.03"]);
    assert_eq!(s["top"], "nexys4fpga");
    shows_the_bot(&s);
    // The live copies, each said once, the stale ones named.
    for (module, taken, other, why) in [
        ("nexys4fpga", "src/nexys4fpga.v", "old/nexys4fpga.v", "the last committed"),
        ("proj2_system", "src/proj2_system.v", "old/proj2_system.v", "beside src/nexys4fpga.v"),
        ("debounce", "src/debounce.v", "old/debounce.v", "beside src/proj2_system.v"),
        ("proj2demo", "src/proj2demo.v", "old/proj2demo.v", "beside src/proj2_system.v"),
    ] {
        let line = said
            .lines()
            .find(|l| l.starts_with(&format!("note: `{module}` has 2 different definitions")))
            .unwrap_or_else(|| panic!("no note on {module}: {said}"));
        assert!(line.contains(&format!("took {taken}:")) && line.contains(&format!("({why}")), "{line}");
        assert!(line.contains(&format!("over {other}:")), "{line}");
    }
    // Vivado's leniency, with the user's file:line:col.
    assert!(said.contains("note: src/nexys4_bot_if.v:29:34: `8'h1FF` has more digits than its width holds; Vivado keeps the low bits (`8'hFF`), and so does botsim"), "{said}");
    assert!(said.contains("note: src/nexys4_bot_if.v:28:15: a variable is given both blocking and non-blocking assignments; Vivado builds it"), "{said}");
    // The ROM's program from its INIT strings, the source beside it.
    assert!(
        said.contains(
            "replaced proj2demo (src/proj2demo.v:3) with a behavioural ROM holding the program from its own contents"
        ),
        "{said}"
    );
    // Nothing of the release folder, the testbench or Project 1 was compiled.
    for never in ["ROM_form", "kcpsm6_design_template", "tb_nexys4fpga", "nexys4fpga_p1", "jtag_loader_6", "bot_if_v1"]
    {
        assert!(!said.contains(never), "{never}: {said}");
    }
}

/// The rules go by what files hold and by their history, not by folder names: the same
/// repository with every folder named otherwise (the design in `hdl/`, the stale copies in
/// `backup_final/`, the release folder, Project 1 and the testbench elsewhere) makes the same
/// choices for the same reasons and runs the same; names as users write them (spaces, commas,
/// `&`, parentheses, accents) too.
#[test]
fn the_same_repository_with_its_folders_named_otherwise_makes_the_same_choices() {
    let renames = [
        ("src", "Verilog files"),
        ("old", "backup, final & (old)"),
        ("KCPSM6_Release9", "PicoBlaze é"),
        ("proj1", "lab 1"),
        ("sim", "verification"),
    ];
    let args = [".", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.03"];
    let (a, said_a) = run(clone_of("release_stale").path(), &args);
    let (b, said_b) = run(clone_renamed("release_stale", &renames).path(), &args);
    let renamed = |line: &str| {
        renames.iter().fold(line.to_string(), |l, (from, to)| l.replace(&format!("{from}/"), &format!("{to}/")))
    };
    let choices = |said: &str| -> Vec<String> {
        said.lines()
            .filter(|l| l.starts_with("note: `") && l.contains("different definitions"))
            .map(str::to_string)
            .collect()
    };
    let want: Vec<String> = choices(&said_a).iter().map(|l| renamed(l)).collect();
    assert_eq!(want.len(), 4, "{said_a}");
    assert_eq!(choices(&said_b), want);
    for k in ["top", "display", "leds", "samples", "end"] {
        assert_eq!(a[k], b[k], "{k}");
    }
}

#[test]
fn the_team_firmware_follows_the_line_to_its_end_through_a_repository_as_committed() {
    let clone = clone_of("release_stale");
    let args = [
        ".",
        "--param",
        "SIMULATE=1",
        "--program",
        "src/linefollow.psm",
        "--timing",
        "fast",
        "--compat",
        "botsim20",
        "--cpu",
        "iss",
        "--samples",
        "6000",
        "--stop-at-line-end",
        "--json",
    ];
    let (s, _) = summary(&board_in(clone.path(), &args));
    assert_eq!(s["stopped_by"], "line-end", "{s}");
    assert_eq!(s["end"]["at_line_end"], true, "{s}");
}

#[test]
fn a_vivado_project_whose_ip_is_only_its_configuration_runs_with_the_cores_it_describes() {
    let clone = clone_of("vivado_ip");
    let c = clone.path();
    let frames = c.join("frames");
    let csv = c.join("t.csv");
    let args = [
        "proj2vga/proj2vga.xpr",
        "--param",
        "SIMULATE=1",
        "--seconds",
        "0.052",
        "--frames",
        frames.to_str().unwrap(),
        "--trace-csv",
        csv.to_str().unwrap(),
    ];
    let (s, said) = run(c, &args);
    assert_eq!(s["top"], "nexys4fpga");
    assert!(said.contains("botsim board: the project proj2vga/proj2vga.xpr"), "{said}");
    // The clock from its .xci (25 MHz exactly: the frames are the display's own), the
    // palette from its .xci and .coe (read to its end without the `;`), nothing of the
    // library model or of the unused IP.
    assert!(said.contains("replaced clk_wiz_0 (proj2vga/proj2vga.srcs/sources_1/ip/clk_wiz_0/clk_wiz_0.xci) with a Clocking Wizard from its configuration (100 MHz in; clk_out1 25 MHz)"), "{said}");
    assert!(said.contains("with a Block Memory Generator core, read latency 1, 12 x 32, from proj2vga/proj2vga.srcs/sources_1/ip/palette/palette.xci"), "{said}");
    assert!(said.contains("note: coe/palette.coe:6: the vector does not end with `;` (Vivado reads it to the end of the file, and so does botsim)"), "{said}");
    assert!(!said.contains("unused_rom") && !said.contains("blk_mem_gen_v8_3"), "{said}");
    assert_eq!(s["vga_frames"], 2, "{s}");
    common::frames_show_sample(&frames, &csv, 1, &[0, 1]);
    // The folder finds the project by itself.
    let (s, said) = run(c, &[".", "--param", "SIMULATE=1", "--seconds", "0.002"]);
    assert_eq!(s["top"], "nexys4fpga");
    assert!(said.contains("botsim board: the project proj2vga/proj2vga.xpr"), "{said}");
}

#[test]
fn an_ise_project_for_the_nexys3_runs_with_its_core_generator_ip() {
    let clone = clone_of("ise_nexys3");
    let c = clone.path();
    let (s, said) = run(c, &["ise/proj2n3.xise", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.03"]);
    assert_eq!(s["top"], "Nexys3fpga");
    // Four digits (the other four dark): the heading on digit 0.
    assert_eq!(s["display"], "       2", "{s}");
    // The sensors on LED[7:0] (the example firmware), mirrored by the ROM on the 25 MHz clock.
    let csv = c.join("t.csv");
    let (s2, _) = run(
        c,
        &[
            "ise/proj2n3.xise",
            "--param",
            "SIMULATE=1",
            "--timing",
            "fast",
            "--seconds",
            "0.03",
            "--trace-csv",
            csv.to_str().unwrap(),
        ],
    );
    let last = std::fs::read_to_string(&csv).unwrap().lines().last().unwrap().to_string();
    let sensors: u8 = last.split(',').nth(5).unwrap().parse().unwrap();
    assert_eq!(s2["leds"].as_u64().unwrap(), sensors.reverse_bits() as u64, "{last}");
    assert!(said.contains("replaced clk25 (ise/ipcore_dir/clk25.xco) with a Clocking Wizard from its configuration (100 MHz in; CLK_OUT1 25 MHz)"), "{said}");
    assert!(said.contains("replaced led_map (ise/ipcore_dir/led_map.v:12) with a Block Memory Generator core, read latency 1, 8 x 256, from the parameters led_map gives `BLK_MEM_GEN_V7_3` (ise/ipcore_dir/led_map.v:24)"), "{said}");
    assert!(!said.contains("tb_nexys3fpga"), "{said}");
}

#[test]
fn a_repository_of_the_teams_own_files_says_all_it_lacks_at_once_and_runs_with_the_course_modules() {
    let clone = clone_of("team_files_only");
    let c = clone.path();
    // The course's modules are botsim's; the clock and the UART are one error, each with
    // its instance and what gets past it.
    let o = board_in(c, &[".", "--param", "SIMULATE=1"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    let lines: Vec<&str> = e.lines().filter(|l| !l.starts_with("note:")).collect();
    assert_eq!(lines[0], "2 modules of the design are missing:", "{e}");
    assert!(lines[1].starts_with("  hdl/nexys4fpga.v:38:5: `uart_tx` (instance `DEBUG_UART` in `nexys4fpga`): add its file, or tie it off with --stub uart_tx"), "{e}");
    assert!(lines[2].starts_with("  hdl/nexys4fpga.v:42:5: `clk_wiz_0` (instance `CLKGEN` in `nexys4fpga`): a clock core with no configuration (ports clk_in1, clk_out1, reset, locked): give its frequencies with --clock clk_wiz_0.clk_out1=25MHz"), "{e}");
    // The last line has every step, ready to paste.
    assert_eq!(lines[3], "  --stub uart_tx --clock clk_wiz_0.clk_out1=25MHz gets past all 2", "{e}");
    assert_eq!(lines.len(), 4, "{e}");
    // With them: the stand-ins said, and the frames are the display's own.
    let (frames, csv) = (c.join("frames"), c.join("t.csv"));
    let args = [
        ".",
        "--param",
        "SIMULATE=1",
        "--clock",
        "clk_wiz_0.clk_out1=25MHz",
        "--stub",
        "uart_tx",
        "--seconds",
        "0.052",
        "--frames",
        frames.to_str().unwrap(),
        "--trace-csv",
        csv.to_str().unwrap(),
    ];
    let (s, said) = run(c, &args);
    for m in ["debounce", "sevensegment", "dtg"] {
        assert!(
            said.contains(&format!("replaced {m} with botsim's clean-room course `{m}` (the repository has none)")),
            "{said}"
        );
    }
    assert!(
        said.contains("replaced clk_wiz_0 with a clock module as --clock describes it (100 MHz in; clk_out1 25 MHz)"),
        "{said}"
    );
    assert!(said.contains("replaced uart_tx with a stub (--stub: inputs ignored, outputs 0)"), "{said}");
    assert_eq!(s["vga_frames"], 2, "{s}");
    common::frames_show_sample(&frames, &csv, 1, &[0, 1]);
    assert_eq!(s["display"].as_str().unwrap().len(), 8, "{s}");
}

#[test]
fn of_two_projects_the_one_with_the_bot_runs_and_another_machines_paths_are_found_here() {
    let clone = clone_of("two_projects");
    let c = clone.path();
    // (The reset button is held for the first millisecond.)
    let (s, said) = run(c, &[".", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.0012"]);
    assert_eq!(s["top"], "nexys4fpga");
    assert!(said.contains("note: several projects here (proj1/proj1.xpr, proj2/proj2.xpr); using proj2/proj2.xpr, the one with a `bot`"), "{said}");
    assert!(said.contains("note: proj2/proj2.xpr: lists C:/Users/team/Desktop/ECE540/proj2/hdl/nexys4fpga.v, which is not here; using proj2/hdl/nexys4fpga.v"), "{said}");
    assert!(
        said.contains("replaced AccelCtl (proj2/hdl/AccelCtl.vhd) with GHDL's synthesis of the VHDL entity to Verilog"),
        "{said}"
    );
    assert!(said.contains("names c:/Users/team/Desktop/ECE540/coe/pattern.coe, which is not here; using proj2/proj2.srcs/sources_1/ip/led_rom/led_rom.mif, the .mif Vivado made from it"), "{said}");
    // LED[15:12]: the VHDL's reading for the 100 MHz its instance sets (not its default 50);
    // LED[11:8]: the ROM's word for switches 0 from the .mif.
    assert_eq!(s["leds"].as_u64().unwrap() >> 8, 0x4A, "{s}");
    let (s, _) = run(
        c,
        &["proj2/proj2.xpr", "--param", "SIMULATE=1", "--switches", "0002", "--timing", "fast", "--seconds", "0.0012"],
    );
    assert_eq!(s["leds"].as_u64().unwrap() >> 8, 0x4C, "{s}");
    // A third project with a bot: which one is the user's to say.
    std::fs::create_dir_all(c.join("final")).unwrap();
    std::fs::copy(c.join("proj2/proj2.xpr"), c.join("final/final.xpr")).unwrap();
    let o = board_in(c, &["."]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr(&o).trim(),
        "several projects here: final/final.xpr, proj1/proj1.xpr, proj2/proj2.xpr; name the one to run (botsim board final/final.xpr)"
    );
}

#[test]
fn a_bot_that_is_not_botsim_20s_is_one_line_naming_its_port() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("top.v"),
        "module nexys4fpga(input clk, output [15:0] led);\n  bot ROJOBOT (.clk(clk), .reset(1'b0), .Bot_Config_reg(8'h00), .MotCtl_in(8'h00));\nendmodule\n",
    )
    .unwrap();
    let o = board_in(dir.path(), &["."]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(
        e.starts_with(
            "top.v:2:3: this `bot` has a port `Bot_Config_reg` that BotSim 2.0's bot does not have (a later BotSim?)"
        ),
        "{e}"
    );
}

/// A run that must fail: its one line.
fn refused(dir: &Path, args: &[&str]) -> String {
    let o = board_in(dir, args);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    stderr(&o)
}

#[test]
fn a_bot_instance_without_a_name_is_named_said_and_runs() {
    let clone = clone_of("unnamed_bot");
    let c = clone.path();
    let (s, said) = run(c, &[".", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.03"]);
    let line = said.lines().find(|l| l.contains("has no name")).unwrap_or_else(|| panic!("{said}"));
    assert!(
        line.starts_with("note: src/proj2_system.v:")
            && line.contains("this `bot` instance has no name")
            && line.contains("Vivado"),
        "{line}"
    );
    let named = line.rsplit('`').nth(1).unwrap();
    assert!(said.contains(&format!("bot at `nexys4fpga.SYS.{named}`")), "{said}");
    // The team committed neither kcpsm6.v nor bot.v (it relied on the course folder): said.
    for m in ["kcpsm6", "bot"] {
        assert!(said.contains(&format!("replaced {m} with botsim's {m} (the repository has none)")), "{said}");
    }
    shows_the_bot(&s);
}

#[test]
fn a_memory_core_from_its_wrappers_parameters_keeps_the_wrappers_ports() {
    // Vivado's wrapper: attributes before a non-ANSI port list (clka, addra, douta).
    let clone = clone_of("ip_wrapper");
    let c = clone.path();
    let frames = c.join("frames");
    let f = frames.to_str().unwrap();
    let (s, said) = run(c, &[".", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.04", "--frames", f]);
    assert!(said.contains("replaced Icon_Rom"), "{said}");
    assert!(s["vga_frames"].as_u64().unwrap() >= 1, "{s}");
}

#[test]
fn of_two_tops_of_one_name_the_one_whose_design_has_the_bot_runs() {
    // Project 1's top was committed last: the newest is not the design.
    let clone = clone_of("two_tops");
    let c = clone.path();
    let (s, said) = run(c, &[".", "--param", "SIMULATE=1", "--timing", "fast", "--seconds", "0.03"]);
    assert!(
        said.contains("note: the top `nexys4fpga` has 2 definitions: took proj2/nexys4fpga.v:5, whose design has the bot, over proj1/nexys4fpga.v:4"),
        "{said}"
    );
    shows_the_bot(&s);
}

#[test]
fn missing_cores_under_one_team_module_offer_to_stub_it_and_the_stub_runs() {
    let clone = clone_of("many_cores");
    let c = clone.path();
    let e = refused(c, &[".", "--param", "SIMULATE=1"]);
    assert!(e.starts_with("20 modules of the design are missing:"), "{e}");
    for k in 0..20 {
        assert!(e.contains(&format!("`icon_rom_{k:02}` (instance `R{k:02}` in `icon`)")), "{e}");
    }
    assert!(
        e.lines()
            .last()
            .unwrap()
            .contains("all 20 are instantiated in `icon` (icon.v:4): --stub icon ties off that module"),
        "{e}"
    );
    // The stub of the team's own module: the design runs, the icon blank.
    let (s, said) = run(c, &[".", "--param", "SIMULATE=1", "--stub", "icon", "--timing", "fast", "--seconds", "0.03"]);
    assert!(said.contains("replaced icon with a stub"), "{said}");
    shows_the_bot(&s);
}

#[test]
fn an_archive_with_two_copies_nothing_orders_asks_which_and_runs_with_it() {
    let clone = clone_of("archive");
    let c = clone.path();
    assert!(!c.join(".git").exists());
    let e = refused(c, &[".", "--param", "SIMULATE=1"]);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("`nexys4_bot_if` has 2 different definitions and nothing tells which the design uses"), "{e}");
    assert!(e.contains("hdl/nexys4_bot_if.v:5") && e.contains("hdl_backup/nexys4_bot_if.v:5"), "{e}");
    assert!(e.contains("--file"), "{e}");
    let (s, _) = run(
        c,
        &[".", "--param", "SIMULATE=1", "--file", "hdl/nexys4_bot_if.v", "--timing", "fast", "--seconds", "0.03"],
    );
    shows_the_bot(&s);
}

#[test]
fn a_file_cut_short_is_reported_where_its_module_begins() {
    let clone = clone_of("truncated");
    let c = clone.path();
    let e = refused(c, &[".", "--param", "SIMULATE=1"]);
    assert_eq!(e.lines().count(), 1, "{e}");
    let line = std::fs::read_to_string(c.join("src/sevensegment.v"))
        .unwrap()
        .lines()
        .position(|l| l.starts_with("module sevensegment"))
        .unwrap()
        + 1;
    assert!(
        e.starts_with(&format!("src/sevensegment.v:{line}:8: the module `sevensegment` does not end (no `endmodule`)")),
        "{e}"
    );
}

#[test]
fn a_program_that_does_not_assemble_shows_its_errors_and_counts_its_warnings() {
    let clone = clone_of("bad_psm");
    let c = clone.path();
    let e = refused(c, &[".", "--param", "SIMULATE=1"]);
    assert!(e.contains("does not assemble:") && e.contains("error:") && e.contains("wiat"), "{e}");
    assert!(!e.contains("warning:"), "{e}");
    assert!(e.contains("warnings)") || e.contains("warning)"), "{e}");
}

/// A final project's clone as committed (tests/board_designs/repos/final_project: a Vivado
/// project for the Nexys4 DDR, no bot, two PicoBlazes, the board's UART, keyboard,
/// accelerometer and audio on the DDR's pin names, an older top in backup/): `botsim board .`
/// finds the project, says each peripheral, and the design hears the keys, the text and the
/// tilt, and plays its note.
#[test]
fn a_final_projects_clone_runs_with_the_boards_peripherals() {
    let clone = clone_of("final_project");
    let c = clone.path();
    std::fs::write(c.join("typing.txt"), "0 switches 8005\n3ms uart \"hey\\r\"\n5ms key KeyA 3ms\n").unwrap();
    let args = ["--seconds", "0.03", "--stimulus", "typing.txt", "--tilt", "-0.5,0,0.87", "--uart", "u.bin"];
    let (s, said) = run(c, &[&["."], &args[..], &["--audio", "a.wav"]].concat());
    assert_eq!(s["top"], "final_top", "{said}");
    assert!(said.contains("botsim board: the project labyrinth/labyrinth.xpr"), "{said}");
    assert!(said.contains("no bot (the board alone)"), "{said}");
    for line in [
        "the board's USB-UART: UART_TXD_IN, UART_RXD_OUT",
        "the board's keyboard (PS/2): PS2_CLK, PS2_DATA",
        "the board's accelerometer (ADXL362): ACL_SCLK, ACL_MOSI, ACL_MISO, ACL_CSN",
        "the board's audio: AUD_PWM, AUD_SD",
    ] {
        assert!(said.contains(line), "{line}: {said}");
    }
    assert!(
        said.contains(
            "took labyrinth/labyrinth.srcs/sources_1/new/final_top.v:8 (the project's) over backup/final_top_old.v:8"
        ),
        "{said}"
    );
    assert_eq!(std::fs::read(c.join("u.bin")).unwrap(), b"botsim console\r\nhey\r");
    // LEDs 15-8: x = -0.5 g (-500 mg: 8-bit E0 at +-2 g); 7-0: A's break code, then A.
    assert_eq!(s["leds"].as_u64(), Some(0xE01C), "{s}");
    assert_eq!(s["display"], "    0001", "{s}");
    let wav = std::fs::read(c.join("a.wav")).unwrap();
    assert_eq!(wav.len(), 44 + 2 * 48 * 30);
    // The note: a square wave of 440 Hz changes sign 880 times a second (26 in 30 ms).
    let x: Vec<i16> = wav[44..].chunks(2).map(|b| i16::from_le_bytes([b[0], b[1]])).collect();
    let crossings = x[48 * 2..].windows(2).filter(|w| (w[0] < 0) != (w[1] < 0)).count();
    assert!((23..=26).contains(&crossings), "{crossings} sign changes");
}

#[test]
fn a_botsim31_bot_runs_from_the_teams_rtl_and_moves_as_botsim_20s_would() {
    // The same Project 2 with the team's BotSim 3.1 bot and with the course's 2.0 bot (both
    // unnamed): the 3.1 RTL runs the 2.0 program (it reads ports 0 and A only), so the two
    // traces are equal sample for sample, cycle for cycle.
    let team = clone_of("botsim31");
    let course = clone_of("unnamed_bot");
    let args = [".", "--param", "SIMULATE=1", "--seconds", "0.16", "--trace-csv", "trace.csv"];
    let (s, said) = run(team.path(), &args);
    let line = said.lines().find(|l| l.contains("the team's bot")).unwrap_or_else(|| panic!("{said}"));
    assert!(
        line.starts_with("  the team's bot `bot` (bot31/bot31.v:")
            && line.contains("port `Bot_Config_reg`; BotSim 3.1): simulated from its own RTL"),
        "{line}"
    );
    for m in ["kcpsm6", "world_map", "bot31_pgm"] {
        assert!(said.contains(&format!("replaced {m} (")), "{m}: {said}");
    }
    for m in ["world_if31", "map31", "replaced bot ", "replaced world_if ", "replaced map "] {
        assert!(!said.contains(&format!("replaced {m}")), "{m}: {said}");
    }
    let (c, _) = run(course.path(), &args);
    let samples = s["samples"].as_u64().unwrap();
    assert!(samples >= 4, "{s}");
    assert_eq!(s["samples"], c["samples"], "{s}\n{c}");

    let read = |d: &Path| std::fs::read_to_string(d.join("trace.csv")).unwrap();
    let (t, r) = (read(team.path()), read(course.path()));
    assert_eq!(t, r);
    // The team's bot, all RTL but its KCPSM6, is skipped too (no bot model's next write bounds
    // a skip: its state is the board's), and its samples come at the same cycles: its KCPSM6
    // runs apart in its firmware's four nested delay loops (its world interface's read mux
    // leaves ports 4 and 5 out, which Verilator writes as a tree of port_id's bits). 0.5 %
    // before; the course's bot model skips 99.6 %.
    let skipped = s["fast_forward"]["skipped_seconds"].as_f64().unwrap() / s["simulated_seconds"].as_f64().unwrap();
    assert!(skipped > 0.95, "skipped {:.1} %: {s}", skipped * 100.0);
    // Its motors turned (the example drives forward after reset): the distance counts.
    let dist: std::collections::BTreeSet<&str> = t.lines().skip(1).filter_map(|l| l.split(',').nth(6)).collect();
    assert!(dist.len() > 2, "{t}");
}

#[test]
fn a_note_about_a_vhdl_entity_points_at_its_vhd_file() {
    // Verilator's finding in GHDL's Verilog of an entity (a combinational loop) is said at
    // the entity's declaration in the .vhd, not at a converted file the user does not have.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("top.v"),
        "module top(input clk, input [15:0] sw, output [15:0] led);\n  loopy L (.a(sw[0]), .b(sw[1]), .q(led[0]));\n  assign led[15:1] = 0;\nendmodule\n",
    )
    .unwrap();
    std::fs::write(
        d.join("loopy.vhd"),
        "library ieee;\nuse ieee.std_logic_1164.all;\n\n-- x and y feed each other.\nentity loopy is\n  port (a : in std_logic; b : in std_logic; q : out std_logic);\nend loopy;\n\narchitecture rtl of loopy is\n  signal x, y : std_logic;\nbegin\n  x <= y and a;\n  y <= x or b;\n  q <= x;\nend rtl;\n",
    )
    .unwrap();
    let (_, said) = run(d, &[".", "--seconds", "0.0001"]);
    let note = said.lines().find(|l| l.contains("UNOPTFLAT")).unwrap_or_else(|| panic!("{said}"));
    assert!(note.starts_with("note: loopy.vhd:5: "), "{note}");
    assert!(!said.contains(".vhd.v"), "{said}");
}

#[test]
fn two_bots_of_two_kinds_each_traced_as_the_one_bot_of_project_2() {
    // A game's hero (the course's 2.0 `bot`) and monster (the team's BotSim 3.1 `bot31`),
    // both unnamed, given the same motor control: each one's trace equals the one bot's of
    // the same Project 2, sample for sample and cycle for cycle; each is reported, and the
    // picture draws both.
    let game = clone_of("two_bots");
    let course = clone_of("unnamed_bot");
    let args = [".", "--param", "SIMULATE=1", "--seconds", "0.16", "--trace-csv", "trace.csv", "--png", "path.png"];
    let (s, said, told) = run_told(game.path(), &args);
    let first = said.lines().find(|l| l.starts_with("botsim board: top")).unwrap();
    assert!(first.contains(", 2 bots: `nexys4fpga."), "{first}");
    assert!(said.contains("  the team's bot `bot31` (bot31/bot31.v:"), "{said}");
    let bots = s["bots"].as_array().unwrap_or_else(|| panic!("{s}"));
    assert_eq!(bots.len(), 2, "{s}");
    assert_eq!(bots[0]["module"], "bot");
    assert_eq!(bots[1]["module"], "bot31");
    let monster = bots[1]["path"].as_str().unwrap();
    assert!(told.contains(&format!("  the bot at `{monster}`: {} samples, ended at (", bots[1]["samples"])), "{told}");
    let (c, _) = run(course.path(), &args);
    let samples = c["samples"].as_u64().unwrap();
    assert!(samples >= 4, "{c}");
    assert_eq!(s["samples"], samples, "{s}");
    assert_eq!(bots[1]["samples"], samples, "{s}");
    let read = |d: &Path, f: &str| std::fs::read_to_string(d.join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
    let one = read(course.path(), "trace.csv");
    assert_eq!(read(game.path(), "trace.csv"), one);
    assert_eq!(read(game.path(), &format!("trace.{monster}.csv")), one);
    // The monster first: what options about the bot mean.
    let (m, said) = run(game.path(), &[&args[..], &["--bot-at", &format!("nexys4fpga.{monster}")]].concat());
    assert!(said.contains(&format!(", 2 bots: `nexys4fpga.{monster}` (the one options")), "{said}");
    assert_eq!((&m["bots"][0]["module"], &m["bots"][1]["module"]), (&"bot31".into(), &"bot".into()), "{m}");
    assert_eq!(read(game.path(), "trace.csv"), one);
    let o = board_in(game.path(), &[".", "--param", "SIMULATE=1", "--bot-at", "SYS.hero"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.trim_end().ends_with(&format!(
            "--bot-at SYS.hero: the design's bots are nexys4fpga.SYS.bot_64, nexys4fpga.{monster}"
        )),
        "{e}"
    );
    // The picture of both paths (each bot's colour: a unit test of render.rs; here they
    // share their cells).
    let (w, h, _) = common::decode_png(&game.path().join("path.png"));
    assert_eq!((w, h), (512, 512));
}

#[test]
fn of_several_projects_one_that_does_not_build_says_why() {
    // Project 2's top cut before its end (a bad merge): no project runs with the bot, and the
    // one line is Project 2's own error, naming the projects here, not "name the one to run".
    let clone = clone_of("two_projects");
    let top = clone.path().join("proj2/hdl/nexys4fpga.v");
    let text = std::fs::read_to_string(&top).unwrap();
    std::fs::write(&top, text.replace("endmodule", "")).unwrap();
    let o = board_in(clone.path(), &["."]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.starts_with("proj2/hdl/nexys4fpga.v:"), "{e}");
    assert!(e.trim_end().ends_with("(of the projects here: proj1/proj1.xpr, proj2/proj2.xpr)"), "{e}");
}

#[test]
fn a_read_mux_of_blocking_assignments_in_a_clocked_block_is_read_as_the_flip_flop_vivado_builds() {
    // The course's BotSim 3.1 world interface writes its read mux `DataOut = ...` in an
    // `always @(posedge clk)`: a flip-flop in Vivado, which the KCPSM6 reads as it was before
    // the edge; in Verilog a race with the CPU's own edge. botsim simulates the flip-flop, so
    // the ISS board and the RTL board read the same value at every cycle.
    let team = clone_of("botsim31");
    let file = team.path().join("bot31/world_if31.v");
    let text = std::fs::read_to_string(&file).unwrap();
    let blocking = text.replace("DataOut <= ", "DataOut = ");
    assert!(blocking.matches("DataOut = ").count() >= 8, "{blocking}");
    std::fs::write(&file, blocking).unwrap();
    let args = [".", "--param", "SIMULATE=1", "--seconds", "0.002", "--cpu", "lockstep"];
    let (s, said) = run(team.path(), &args);
    let note = said.lines().find(|l| l.contains("`DataOut`")).unwrap_or_else(|| panic!("{said}"));
    assert!(note.starts_with("note: bot31/world_if31.v:"), "{note}");
    assert!(s["samples"].as_u64().is_some(), "{s}");
    // And the default board still skips the bot's delays with the flip-flop, on a clock made
    // by a DCM as the Nexys3 designs' are. (In ddle_rojobotworld, of the corpus, Verilator
    // then keeps a delayed copy of the ISS model's outputs register, which the fast-forward
    // takes for the outputs again; this clean-room design gets no such copy.)
    let top = team.path().join("src/nexys4fpga.v");
    let text = std::fs::read_to_string(&top).unwrap();
    let dcm = "    wire clk0, clk_sys;\n    DCM_SP #(.CLKIN_PERIOD(10.0)) DCM (.CLKIN(clk), .CLKFB(clk_sys), .CLK0(clk0), .RST(1'b0));\n    BUFG BSYS (.I(clk0), .O(clk_sys));\n    proj2_system #(.SIMULATE(SIMULATE)) SYS (\n        .clk(clk_sys),";
    let text = text.replacen("    proj2_system #(.SIMULATE(SIMULATE)) SYS (\n        .clk(clk),", dcm, 1);
    assert!(text.contains("clk_sys"), "{text}");
    std::fs::write(&top, text).unwrap();
    let (s, _) = run(team.path(), &[".", "--param", "SIMULATE=1", "--seconds", "0.16"]);
    let skipped = s["fast_forward"]["skipped_seconds"].as_f64().unwrap() / s["simulated_seconds"].as_f64().unwrap();
    assert!(skipped > 0.95, "skipped {:.1} %: {s}", skipped * 100.0);
}
