//! Every command of the README and of docs/guide.md runs as written, so they never go stale:
//! the `sh` blocks are read, and each `botsim ...` (or `cargo run --release -- ...`) command
//! runs in a folder holding `my_clone`, a repository of the guide's shape (a Vivado project
//! with a VGA display and its IP as configurations: tests/board_designs/repos/vivado_ip),
//! `my_game`, a final project without a bot (examples/nexys4_game), `my_console`, one with
//! the board's UART and keyboard (tests/board_designs/console), and the examples;
//! the README's own picture is what its first command draws.

use std::path::Path;
use std::process::Command;

use crate::common;

use common::root;

/// The commands of the `sh` blocks of a Markdown file, continuation lines joined.
fn commands(markdown: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_sh = false;
    let mut pending = String::new();
    for line in markdown.lines() {
        let t = line.trim();
        if t.starts_with("```") {
            in_sh = t == "```sh";
            continue;
        }
        if !in_sh || t.is_empty() || t.starts_with('#') {
            continue;
        }
        match t.strip_suffix('\\') {
            Some(part) => pending.push_str(part),
            None => {
                pending.push_str(t);
                out.push(std::mem::take(&mut pending));
            }
        }
    }
    out
}

/// What to run for a command: the botsim arguments, or `None` for what the test cannot or
/// need not run (setting up, the tests themselves, GTKWave's window).
fn botsim_args(command: &str) -> Option<Vec<String>> {
    let c = command.trim_start_matches("bash scripts/setup.sh && ");
    let rest = c.strip_prefix("cargo run --release -- ").or_else(|| c.strip_prefix("botsim "))?;
    Some(rest.split_whitespace().map(str::to_string).collect())
}

/// Run one command; `.` as the design means "in your clone".
fn run(command: &str, dir: &Path) {
    let Some(args) = botsim_args(command) else { return };
    let cwd = if args.get(1).map(String::as_str) == Some(".") { dir.join("my_clone") } else { dir.to_path_buf() };
    if args.iter().any(|a| a == "--live") {
        // A live run: on any free port, a page that gets the hello and stops it.
        let rest: Vec<&str> = args[1..].iter().map(String::as_str).filter(|a| *a != "--live").collect();
        let mut live = common::live::Live::start_in(&cwd, &args[0], &rest);
        let mut page = live.client("/");
        let hello = page.next(common::live::BUDGET).unwrap_or_default();
        assert_eq!(hello["type"], "hello", "{command}: {hello}");
        page.send(serde_json::json!({"type": "stop"}));
        assert!(live.wait().success(), "{command}");
        return;
    }
    let o = Command::new(env!("CARGO_BIN_EXE_botsim"))
        .args(&args)
        .current_dir(&cwd)
        .env("BOTSIM_CACHE", common::board_cache())
        .output()
        .unwrap();
    assert!(o.status.success(), "{command}\n{}", String::from_utf8_lossy(&o.stderr));
}

/// A folder with the guide's repository and the examples.
fn workspace() -> (tempfile::TempDir, tempfile::TempDir) {
    let clone = common::repo::clone_of("vivado_ip");
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(clone.path(), dir.path().join("my_clone")).unwrap();
    std::os::unix::fs::symlink(root().join("examples"), dir.path().join("examples")).unwrap();
    std::os::unix::fs::symlink(root().join(common::game::GAME), dir.path().join("my_game")).unwrap();
    std::os::unix::fs::symlink(root().join("tests/board_designs/console"), dir.path().join("my_console")).unwrap();
    (dir, clone)
}

#[test]
fn the_readme_commands_run_and_its_pictures_are_what_the_first_one_draws() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let cmds = commands(&readme);
    assert!(cmds.len() >= 5, "{cmds:?}");
    let (dir, _clone) = workspace();
    for c in &cmds {
        run(c, dir.path());
    }
    // The pictures the README shows are the first command's.
    let d = dir.path();
    assert_eq!(
        common::rgb(&std::fs::read(d.join("path.png")).unwrap()),
        common::rgb(&std::fs::read(root().join("docs/images/path.png")).unwrap())
    );
    assert_eq!(
        common::rgb(&std::fs::read(d.join("frames/frame_00002.png")).unwrap()),
        common::rgb(&std::fs::read(root().join("docs/images/frame.png")).unwrap())
    );
}

#[test]
fn the_guides_commands_run_on_a_repository_of_its_shape() {
    let guide = std::fs::read_to_string(root().join("docs/guide.md")).unwrap();
    let cmds = commands(&guide);
    assert!(cmds.iter().filter(|c| botsim_args(c).is_some()).count() >= 8, "{cmds:?}");
    let (dir, _clone) = workspace();
    for c in &cmds {
        run(c, dir.path());
    }
    // What the guide says the breakpoint prints, it prints.
    assert!(guide.contains("stopped by --break bot=off-line: sample 337 at 7.654810 ms, the bot at (85, 64) facing E"));
    let d = dir.path();
    for f in [
        "display.txt",
        "bot.csv",
        "path.png",
        "frames/frame_00000.png",
        "w.vcd",
        "w.gtkw",
        "stop.vcd",
        "firmware.txt",
        "firmware.profile.txt",
        "game_frames/frame_00005.png",
        "console.txt",
    ] {
        assert!(d.join(f).exists(), "{f}");
    }
    assert!(d.join("trace/SYS.APPCPU.trace.txt").exists());
}
