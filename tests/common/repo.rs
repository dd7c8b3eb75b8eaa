//! Repository-shaped test designs (tests/board_designs/repos/<name>): each is built into a
//! fresh folder as a team's clone would be, a real git repository, from
//!
//! - the files under its folder (project files, IP configurations, release templates, stale
//!   copies, testbenches: whatever makes its shape), and
//! - its `tree.txt`: one line each,
//!   - `copy FROM TO`: a file of this repository (the examples) placed at TO, optionally
//!     followed by edits `| replace "OLD" "NEW"` (each must match: a stale copy differs from
//!     the live one by them) or `| cut "TEXT"` (the file ends right before TEXT: a file
//!     committed cut short);
//!   - `rom PSM TO`: the program ROM the KCPSM6 assembler writes for PSM in its development
//!     template (a block RAM's INIT strings and the JTAG loader module), at TO;
//!   - `older PATH...`: these paths (files or folders) are committed first, a month before
//!     the rest, as a team's stale copies are;
//!   - `archive`: no git at all, every file the same date (a downloaded archive);
//!   - `#` comments.

use std::path::Path;
use std::process::Command;

use super::root;

/// The clone of repository `name`.
pub fn clone_of(name: &str) -> tempfile::TempDir {
    clone_renamed(name, &[])
}

/// The clone of repository `name` with its top folders renamed (`("old", "backup")`): the
/// same repository as another team would name it, its history the same.
pub fn clone_renamed(name: &str, renames: &[(&str, &str)]) -> tempfile::TempDir {
    let src = root().join("tests/board_designs/repos").join(name);
    let dir = tempfile::Builder::new().prefix(&format!("{name}-")).tempdir().unwrap();
    let place = |p: &str| -> String {
        let (first, rest) = p.split_once('/').unwrap_or((p, ""));
        let first = renames.iter().find(|(from, _)| *from == first).map_or(first, |(_, to)| to);
        if rest.is_empty() {
            first.to_string()
        } else {
            format!("{first}/{rest}")
        }
    };
    copy_tree(&src, dir.path());
    for (from, to) in renames {
        if dir.path().join(from).exists() {
            std::fs::rename(dir.path().join(from), dir.path().join(to)).unwrap();
        }
    }
    let manifest = std::fs::read_to_string(src.join("tree.txt")).unwrap_or_default();
    let mut older = Vec::new();
    let mut archive = false;
    for (n, line) in manifest.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let at = format!("{}:{}", src.join("tree.txt").display(), n + 1);
        let (cmd, rest) = line.split_once(' ').unwrap_or((line, ""));
        match cmd {
            "copy" => {
                let mut parts = rest.split(" | ");
                let files: Vec<&str> = parts.next().unwrap().split_whitespace().collect();
                let mut text = std::fs::read_to_string(root().join(files[0])).unwrap_or_else(|e| panic!("{at}: {e}"));
                for edit in parts {
                    let q: Vec<&str> = edit.split('"').collect();
                    if q.len() == 3 && q[0].trim() == "cut" {
                        let cut = unescape(q[1]);
                        let end = text.find(&cut).unwrap_or_else(|| panic!("{at}: `{cut}` is not in {}", files[0]));
                        text.truncate(end);
                        continue;
                    }
                    assert!(q.len() == 5 && q[0].trim() == "replace", "{at}: expected | replace \"OLD\" \"NEW\"");
                    let (old, new) = (unescape(q[1]), unescape(q[3]));
                    assert!(text.contains(&old), "{at}: `{old}` is not in {}", files[0]);
                    text = text.replacen(&old, &new, 1);
                }
                write(&dir.path().join(place(files[1])), &text);
            }
            "rom" => {
                let files: Vec<&str> = rest.split_whitespace().collect();
                let psm = root().join(files[0]);
                let program = kcpsm6::asm::assemble_file(&psm, &Default::default()).unwrap();
                let module = Path::new(files[1]).file_stem().unwrap().to_string_lossy().into_owned();
                write(&dir.path().join(place(files[1])), &template_rom(&program.image, &module));
            }
            "older" => older.extend(rest.split_whitespace().map(place)),
            "archive" => archive = true,
            _ => panic!("{at}: unknown line"),
        }
    }
    if archive {
        same_date(dir.path());
        return dir;
    }
    git(dir.path(), &["init", "-q"], None);
    if !older.is_empty() {
        let mut args = vec!["add", "-f", "--"];
        args.extend(older.iter().map(String::as_str));
        git(dir.path(), &args, None);
        git(dir.path(), &["commit", "-q", "-m", "the older copies"], Some("2014-10-01T12:00:00"));
    }
    git(dir.path(), &["add", "-A", "-f"], None);
    git(dir.path(), &["commit", "-q", "-m", "the design", "--allow-empty"], Some("2014-11-01T12:00:00"));
    dir
}

/// Every file under `dir` modified at one moment, as an archive's files are once unpacked.
fn same_date(dir: &Path) {
    let when = std::time::UNIX_EPOCH + std::time::Duration::from_secs(1_414_843_200);
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        if e.path().is_dir() {
            same_date(&e.path());
        } else {
            std::fs::File::options().write(true).open(e.path()).unwrap().set_modified(when).unwrap();
        }
    }
}

fn unescape(s: &str) -> String {
    s.replace("\\n", "\n")
}

fn write(path: &Path, text: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

fn copy_tree(from: &Path, to: &Path) {
    for e in std::fs::read_dir(from).unwrap().flatten() {
        let (src, dst) = (e.path(), to.join(e.file_name()));
        if src.is_dir() {
            std::fs::create_dir_all(&dst).unwrap();
            copy_tree(&src, &dst);
        } else if e.file_name() != "tree.txt" {
            std::fs::copy(&src, &dst).unwrap();
        }
    }
}

fn git(dir: &Path, args: &[&str], date: Option<&str>) {
    let mut cmd = Command::new("git");
    cmd.current_dir(dir)
        .args(["-c", "user.name=team", "-c", "user.email=team@example.com", "-c", "commit.gpgsign=false"])
        .args(args);
    if let Some(d) = date {
        cmd.env("GIT_AUTHOR_DATE", d).env("GIT_COMMITTER_DATE", d);
    }
    let o = cmd.output().expect("git");
    assert!(o.status.success(), "git {args:?}: {}", String::from_utf8_lossy(&o.stderr));
}

/// A program ROM in the shape of the KCPSM6 assembler's development template (kcpsm6.md §3):
/// the program in a block RAM's INIT strings, and the JTAG loader module in the same file.
/// Written for botsim's tests; botsim replaces the ROM and never compiles the loader (it
/// instantiates BSCANE2, which botsim does not model).
pub fn template_rom(image: &kcpsm6::Image, module: &str) -> String {
    let (init, initp) = image.init_strings(1024);
    let mut v = format!(
        "// {module}.v: KCPSM6 program ROM, development template (1K, 7-series).\n\
         `timescale 1ps / 1ps\n\
         module {module} #(parameter C_FAMILY = \"7S\", parameter C_RAM_SIZE_KWORDS = 1, parameter C_JTAG_LOADER_ENABLE = 1) (\n\
         \x20 input [11:0] address,\n  output [17:0] instruction,\n  input enable,\n  output rdl,\n  input clk);\n\
         \x20 wire [15:0] data_out;\n  wire [1:0] data_out_p;\n  wire [11:0] jtag_addr;\n  wire jtag_we, jtag_clk, jtag_en;\n\
         \x20 assign instruction = {{data_out_p, data_out}};\n\
         \x20 RAMB18E1 #(.READ_MODE(\"WRITE_FIRST\"), .READ_WIDTH_A(18), .WRITE_WIDTH_B(18),\n"
    );
    for (n, s) in init.iter().enumerate() {
        v.push_str(&format!("    .INIT_{n:02X}(256'h{s}),\n"));
    }
    for (n, s) in initp.iter().enumerate() {
        v.push_str(&format!("    .INITP_{n:02X}(256'h{s}),\n"));
    }
    v.push_str(
        "    .SRVAL_A(18'h00000)) kcpsm6_rom (.ADDRARDADDR({address[9:0], 4'b1111}), .ENARDEN(enable), .CLKARDCLK(clk),\n\
         \x20   .DOADO(data_out), .DOPADOP(data_out_p), .ADDRBWRADDR({jtag_addr[9:0], 4'b1111}), .WEBWE({4{jtag_we}}), .CLKBWRCLK(jtag_clk));\n\
         \x20 jtag_loader_6 #(.C_JTAG_LOADER_ENABLE(C_JTAG_LOADER_ENABLE), .C_FAMILY(C_FAMILY))\n\
         \x20   instantiate_loader (.picoblaze_reset(rdl), .jtag_en(jtag_en), .jtag_addr(jtag_addr), .jtag_clk(jtag_clk), .jtag_we(jtag_we),\n\
         \x20   .jtag_dout_0(instruction));\n\
         endmodule\n\n\
         // The JTAG loader: a BSCANE2 chain that writes the ROM from the PC.\n\
         module jtag_loader_6 #(parameter integer C_JTAG_LOADER_ENABLE = 1, parameter C_FAMILY = \"7S\") (\n\
         \x20 output picoblaze_reset, output jtag_en, output [11:0] jtag_addr, output jtag_clk, output jtag_we,\n\
         \x20 input [17:0] jtag_dout_0);\n\
         \x20 wire capture, drck, sel, shift, tdi, update;\n\
         \x20 BSCANE2 #(.JTAG_CHAIN(2)) BSCAN_BLOCK_inst (.CAPTURE(capture), .DRCK(drck), .SEL(sel), .SHIFT(shift),\n\
         \x20   .TDI(tdi), .UPDATE(update), .TDO(jtag_dout_0[0]));\n\
         \x20 assign {picoblaze_reset, jtag_en, jtag_clk, jtag_we} = {sel & update, sel, drck, shift};\n\
         \x20 assign jtag_addr = {12{tdi}};\n\
         endmodule\n",
    );
    v
}
