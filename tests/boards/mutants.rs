//! Mistakes shown where they are: single edits of a test design (a line deleted, duplicated
//! or cut off with the rest of its file, a `;` removed, an identifier misspelt, a number
//! changed, `<=` for `=` and back, a stray keyword), each run through `botsim board` as a
//! user would. Every outcome must be a run, or an error that points at the edit: a location
//! within a few lines of it in the edited file, or a name the edit removed or misspelt. No
//! panic, no hang, and never "please report" (the mistake is the user's, not botsim's).
//!
//! CI runs `BOTSIM_MUTANTS` (default 3) mutants of each design; locally, for thousands:
//! `BOTSIM_MUTANTS=500 BOTSIM_MUTANT_SEED=7 cargo test --release --test mutants -- --nocapture`
//! (a mutant that reaches Verilator builds: seconds each). Another design, a restored corpus
//! repository's for one: `BOTSIM_MUTANT_DESIGN=FOLDER:FILE` (FILE below FOLDER; the run is
//! `botsim board FOLDER --seconds 0.001`, with `BOTSIM_MUTANT_ARGS` more, space-separated).

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::random_design::Rng;
use common::{board_cache, root};

/// The designs mutated: (folder, the file edited, the arguments of the run).
const DESIGNS: [(&str, &str, &[&str]); 2] = [
    ("tests/board_designs/tilt", "nexys4fpga.v", &["--seconds", "0.001"]),
    ("tests/board_designs/console", "nexys4fpga.v", &["--seconds", "0.001"]),
];

/// One edit: the 1-based line it is at, what it did, the names it removed or changed.
struct Edit {
    line: usize,
    what: String,
    names: Vec<String>,
    text: String,
}

fn identifiers(line: &str) -> Vec<String> {
    line.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| w.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_'))
        .map(str::to_string)
        .collect()
}

/// A random single edit of `text`.
fn mutate(text: &str, r: &mut Rng) -> Edit {
    let lines: Vec<&str> = text.lines().collect();
    let k = r.range(0, lines.len() as u64 - 1) as usize;
    let line = lines[k];
    let join = |ls: Vec<String>| ls.join("\n") + "\n";
    let owned: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    let with_line = |new: String| {
        let mut v = owned.clone();
        v[k] = new;
        join(v)
    };
    match r.range(0, 7) {
        0 => {
            let mut v = owned.clone();
            v.remove(k);
            Edit { line: k + 1, what: format!("deleted line {}", k + 1), names: identifiers(line), text: join(v) }
        }
        1 => {
            let mut v = owned.clone();
            v.insert(k, line.to_string());
            Edit { line: k + 2, what: format!("duplicated line {}", k + 1), names: identifiers(line), text: join(v) }
        }
        2 => {
            let names = lines[k..].iter().flat_map(|l| identifiers(l)).collect();
            Edit { line: k + 1, what: format!("cut before line {}", k + 1), names, text: join(owned[..k].to_vec()) }
        }
        3 if line.contains(';') => Edit {
            line: k + 1,
            what: format!("removed a `;` on line {}", k + 1),
            names: identifiers(line),
            text: with_line(line.replacen(';', "", 1)),
        },
        4 if !identifiers(line).is_empty() => {
            let ids = identifiers(line);
            let id = r.pick(&ids).clone();
            let typo = format!("{id}x");
            Edit {
                line: k + 1,
                what: format!("misspelt `{id}` on line {}", k + 1),
                text: with_line(line.replacen(&id, &typo, 1)),
                names: vec![id, typo],
            }
        }
        5 if line.bytes().any(|b| b.is_ascii_digit()) => {
            let at = line.bytes().position(|b| b.is_ascii_digit()).unwrap();
            let digit = (line.as_bytes()[at] - b'0' + 1) % 10;
            let mut new = line.to_string();
            new.replace_range(at..at + 1, &digit.to_string());
            Edit {
                line: k + 1,
                what: format!("changed a digit on line {}", k + 1),
                names: identifiers(line),
                text: with_line(new),
            }
        }
        6 if line.contains("<=") || line.contains(" = ") => {
            let new = if line.contains("<=") { line.replacen("<=", "=", 1) } else { line.replacen(" = ", " <= ", 1) };
            Edit {
                line: k + 1,
                what: format!("swapped `<=` and `=` on line {}", k + 1),
                names: identifiers(line),
                text: with_line(new),
            }
        }
        _ => {
            let word = *r.pick(&["endmodule", "begin", "end", "wire", "assign"]);
            let mut v = owned.clone();
            v.insert(k, word.to_string());
            Edit {
                line: k + 1,
                what: format!("a stray `{word}` before line {}", k + 1),
                names: vec![word.into()],
                text: join(v),
            }
        }
    }
}

/// Why an outcome misleads, if it does.
fn misleads(edit: &Edit, file: &str, code: Option<i32>, err: &str) -> Option<String> {
    match code {
        Some(0) => return None,
        None => return Some("killed (a hang?)".into()),
        Some(124) => return Some("ran past its budget (a hang)".into()),
        Some(1) => {}
        Some(c) => return Some(format!("exit {c}")),
    }
    if err.contains("panicked") || err.contains("RUST_BACKTRACE") {
        return Some("a panic".into());
    }
    if err.contains("please report") {
        return Some("blames botsim for the user's edit".into());
    }
    let first = err.lines().find(|l| {
        !l.starts_with("note:") && !l.starts_with("warning:") && !l.starts_with("botsim board") && !l.starts_with("  ")
    });
    let text = err;
    // A location in the edited file near the edit.
    let near = text.lines().any(|l| {
        l.split_once(&format!("{file}:"))
            .and_then(|(_, r)| r.split(':').next()?.parse::<usize>().ok())
            .is_some_and(|n| n + 3 >= edit.line && n <= edit.line + 3)
    });
    // Or a line near the edit named in the message (`does not close before the `;` at line 37`).
    let near = near
        || (edit.line.saturating_sub(3)..=edit.line + 3)
            .any(|n| text.contains(&format!("at line {n}:")) || text.contains(&format!("at line {n} ")));
    // A name the edit removed or misspelt, in quotes as botsim and Verilator quote them.
    let named = edit.names.iter().any(|n| text.contains(&format!("`{n}`")) || text.contains(&format!("'{n}'")));
    // A cut file: the module it no longer ends, or its end.
    let cut = edit.what.starts_with("cut") && (text.contains("endmodule") || text.contains("ends"));
    if near || named || cut {
        None
    } else {
        Some(format!("points elsewhere: {}", first.unwrap_or("(no line)")))
    }
}

#[test]
fn every_mutant_runs_or_is_told_where_its_edit_is() {
    let count: usize = std::env::var("BOTSIM_MUTANTS").ok().and_then(|v| v.parse().ok()).unwrap_or(3);
    let seed: u64 = std::env::var("BOTSIM_MUTANT_SEED").ok().and_then(|v| v.parse().ok()).unwrap_or(1);
    let mut r = Rng::new(seed);
    let mut bad = Vec::new();
    let mut outcomes = [0usize; 2];
    let given = std::env::var("BOTSIM_MUTANT_DESIGN").ok();
    let extra = std::env::var("BOTSIM_MUTANT_ARGS").unwrap_or_default();
    let designs: Vec<(PathBuf, String, Vec<String>)> = match &given {
        Some(g) => {
            let (folder, file) = g.split_once(':').expect("BOTSIM_MUTANT_DESIGN=FOLDER:FILE");
            let mut args = vec!["--seconds".to_string(), "0.001".into()];
            args.extend(extra.split_whitespace().map(str::to_string));
            vec![(PathBuf::from(folder), file.to_string(), args)]
        }
        None => DESIGNS
            .iter()
            .map(|(d, f, a)| (root().join(d), f.to_string(), a.iter().map(|s| s.to_string()).collect()))
            .collect(),
    };
    for (folder, file, args) in &designs {
        let design = folder.display().to_string();
        let original = std::fs::read_to_string(folder.join(file)).unwrap();
        for n in 0..count {
            let edit = mutate(&original, &mut r);
            let dir = tempfile::tempdir().unwrap();
            let copy = dir.path().join("design");
            copy_dir(folder, &copy);
            std::fs::write(copy.join(file), &edit.text).unwrap();
            let out = Command::new("timeout")
                .arg("300")
                .arg(env!("CARGO_BIN_EXE_botsim"))
                .arg("board")
                .arg("design")
                .args(args)
                .current_dir(dir.path())
                .env("BOTSIM_CACHE", board_cache())
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&out.stderr).into_owned();
            outcomes[(out.status.code() == Some(0)) as usize] += 1;
            if let Some(why) = misleads(&edit, &format!("design/{file}"), out.status.code(), &err) {
                bad.push(format!("{design} mutant {n} ({}): {why}\n{err}", edit.what));
            }
        }
    }
    eprintln!("mutants: {} ran, {} stopped with botsim's line, {} misleading", outcomes[1], outcomes[0], bad.len());
    assert!(bad.is_empty(), "{}", bad.join("\n---\n"));
}

/// The folder's files and folders (not `.git`).
fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let p: PathBuf = e.path();
        if p.is_file() {
            std::fs::copy(&p, to.join(e.file_name())).unwrap();
        } else if p.is_dir() && e.file_name() != ".git" {
            copy_dir(&p, &to.join(e.file_name()));
        }
    }
}
