//! Modules that exist only as VHDL (a Digilent controller in a final project): the entities a
//! VHDL file declares, and GHDL's synthesis of one to Verilog (`ghdl synth --out=verilog`,
//! Debian's `ghdl` package), which then builds like the rest of the design.
//!
//! ```
//! use botsim_core::frontend::vhdl::entities;
//! let vhd = "-- entity Old is\nlibrary ieee;\nENTITY AccelCtl IS\n  port (clk : in std_logic);\nend AccelCtl;\n";
//! assert_eq!(entities(vhd), [("AccelCtl".to_string(), 3)]);
//! ```

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The entities a VHDL text declares, with their lines (comments skipped).
pub fn entities(text: &str) -> Vec<(String, u32)> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let code = line.split("--").next().unwrap_or("");
        let words: Vec<&str> = code.split_whitespace().collect();
        for w in words.windows(3) {
            if w[0].eq_ignore_ascii_case("entity") && w[2].eq_ignore_ascii_case("is") {
                out.push((w[1].to_string(), n as u32 + 1));
            }
        }
    }
    out
}

/// How long one GHDL synthesis may take.
const BUDGET: Duration = Duration::from_secs(120);

/// The Verilog GHDL makes of `entity` (declared in `file`; `others` are the VHDL files beside
/// it, analysed too when the entity needs them) with `generics` set, the module named `name`
/// as the design spells it. Errors are one line.
pub fn to_verilog(
    file: &Path,
    others: &[PathBuf],
    entity: &str,
    name: &str,
    generics: &[(String, String)],
) -> Result<String, String> {
    let mut last = String::new();
    // The entity's file alone, then with the files beside it; VHDL-2008, then VHDL-93 (each
    // with Synopsys's packages, which Vivado and ISE accept).
    let alone = [file.to_path_buf()];
    let mut with_others = vec![file.to_path_buf()];
    with_others.extend(others.iter().filter(|p| *p != file).cloned());
    for files in [&alone[..], &with_others[..]] {
        for std in [&["--std=08", "-fsynopsys"][..], &["--std=93c", "-fsynopsys", "-fexplicit"][..]] {
            match synth(files, std, entity, generics) {
                Ok(v) => return Ok(rename(&v, entity, name, generics)),
                Err(e) => last = e,
            }
        }
    }
    Err(last)
}

fn synth(files: &[PathBuf], std: &[&str], entity: &str, generics: &[(String, String)]) -> Result<String, String> {
    let work = std::env::temp_dir().join(format!("botsim-ghdl-{}-{}", std::process::id(), entity));
    let _ = std::fs::create_dir_all(&work);
    let mut cmd = Command::new(std::env::var_os("GHDL").unwrap_or_else(|| "ghdl".into()));
    cmd.arg("synth").args(std).arg(format!("--workdir={}", work.display())).arg("--out=verilog");
    for (g, v) in generics {
        cmd.arg(format!("-g{g}={v}"));
    }
    cmd.args(files).arg("-e").arg(entity).stdout(Stdio::piped()).stderr(Stdio::piped());
    let result = run(&mut cmd);
    let _ = std::fs::remove_dir_all(&work);
    let (ok, stdout, stderr) = result?;
    if ok && stdout.contains("module ") {
        Ok(stdout)
    } else {
        let first = stderr.lines().find(|l| !l.trim().is_empty()).unwrap_or("no Verilog from GHDL").to_string();
        Err(format!("GHDL could not synthesize `{entity}`: {first}"))
    }
}

fn run(cmd: &mut Command) -> Result<(bool, String, String), String> {
    let mut child = cmd.spawn().map_err(|e| format!("cannot run ghdl: {e} (install it: scripts/setup.sh)"))?;
    let read = |r: Option<Box<dyn std::io::Read + Send>>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            if let Some(mut r) = r {
                let _ = r.read_to_string(&mut s);
            }
            s
        })
    };
    let out = read(child.stdout.take().map(|s| Box::new(s) as Box<dyn std::io::Read + Send>));
    let err = read(child.stderr.take().map(|s| Box::new(s) as Box<dyn std::io::Read + Send>));
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break s,
            Ok(None) if start.elapsed() < BUDGET => std::thread::sleep(Duration::from_millis(20)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!("GHDL took longer than {} s and was stopped", BUDGET.as_secs()));
            }
        }
    };
    Ok((status.success(), out.join().unwrap_or_default(), err.join().unwrap_or_default()))
}

/// GHDL's module for the entity renamed as the design instantiates it (VHDL names have no
/// case; Verilog's do), with the generics the instance sets declared as parameters (their
/// values are already in the logic) so that the instance's overrides find them.
fn rename(verilog: &str, entity: &str, name: &str, generics: &[(String, String)]) -> String {
    let mut out = String::new();
    let mut in_top = false;
    for line in verilog.lines() {
        let trimmed = line.trim_start();
        if let Some(rest) = trimmed.strip_prefix("module ") {
            let m = rest.split(|c: char| c.is_whitespace() || c == '(' || c == '#').next().unwrap_or("");
            in_top = m.eq_ignore_ascii_case(entity);
            if in_top {
                out.push_str(&line.replacen(m, name, 1));
                out.push('\n');
                continue;
            }
        }
        out.push_str(line);
        out.push('\n');
        if in_top && trimmed.ends_with(");") && !generics.is_empty() {
            for (g, _) in generics {
                out.push_str(&format!("  parameter {g} = 0; // set by the instance, applied by GHDL\n"));
            }
            in_top = false;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_module_takes_the_designs_spelling_and_declares_the_generics_it_sets() {
        let v = "module accelctl\n  (input  clk,\n   output q);\n  assign q = clk;\nendmodule\n";
        let r = rename(v, "AccelCtl", "AccelCtl", &[("FREQ".into(), "100".into())]);
        assert_eq!(r, "module AccelCtl\n  (input  clk,\n   output q);\n  parameter FREQ = 0; // set by the instance, applied by GHDL\n  assign q = clk;\nendmodule\n");
    }
}
