//! Which Verilator is installed, and whether botsim can use it: botsim supports Verilator
//! 5.006 (Debian 12's) and every later 5.x release. Shared by build.rs (the bot and CPU
//! models) and `botsim board` (which builds designs at run time and says which Verilator
//! built each).

use std::path::PathBuf;
use std::process::Command;

/// The oldest Verilator botsim builds with (major, minor): 5.006.
pub const OLDEST: (u32, u32) = (5, 6);

/// An installed Verilator: its version and its root (the runtime's sources and includes).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Verilator {
    /// As `verilated_config.h` gives it, e.g. "5.006 2023-01-22".
    pub version: String,
    pub major: u32,
    pub minor: u32,
    pub root: PathBuf,
}

/// Find the Verilator that `program` runs, and check it is one botsim supports; the error is
/// one line saying what is needed.
pub fn find(program: &str) -> Result<Verilator, String> {
    let o = Command::new(program).args(["--getenv", "VERILATOR_ROOT"]).output().map_err(|_| {
        format!("{program} not found: run `bash scripts/setup.sh` (installs Verilator 5.006 from Debian)")
    })?;
    let root = PathBuf::from(String::from_utf8_lossy(&o.stdout).trim());
    if !root.join("include/verilated.h").exists() {
        return Err(format!(
            "{program}: verilated.h not found under `{}`: run `bash scripts/setup.sh`",
            root.display()
        ));
    }
    // The runtime's own header says its version; `verilator --version` does not always (a
    // build from a source tree says `rev vUNKNOWN`).
    let config = std::fs::read_to_string(root.join("include/verilated_config.h")).unwrap_or_default();
    let from_config = config.lines().find_map(|l| {
        l.trim().strip_prefix("#define VERILATOR_VERSION ").map(|v| v.trim().trim_matches('"').to_string())
    });
    let version = match from_config {
        Some(v) => v,
        None => {
            let o =
                Command::new(program).arg("--version").output().map_err(|e| format!("cannot run {program}: {e}"))?;
            let text = String::from_utf8_lossy(&o.stdout).into_owned();
            text.split_whitespace().nth(1).unwrap_or("").to_string()
        }
    };
    let (major, minor) =
        parse(&version).ok_or_else(|| format!("{program}: cannot tell its version from `{version}`"))?;
    if (major, minor) < OLDEST || major > 5 {
        return Err(format!(
            "Verilator {version} found; botsim needs 5.{:03} or a later 5.x (run `bash scripts/setup.sh`, or set VERILATOR to one)",
            OLDEST.1
        ));
    }
    Ok(Verilator { version, major, minor, root })
}

/// `5.006 2023-01-22` -> (5, 6); `5.49` -> (5, 49).
pub fn parse(version: &str) -> Option<(u32, u32)> {
    let v = version.split_whitespace().next()?;
    let (major, minor) = v.split_once('.')?;
    let minor: String = minor.chars().take_while(|c| c.is_ascii_digit()).collect();
    Some((major.parse().ok()?, minor.parse().ok()?))
}

#[cfg(test)]
mod tests {
    #[test]
    fn versions_as_the_runtime_and_the_command_give_them() {
        assert_eq!(super::parse("5.006 2023-01-22"), Some((5, 6)));
        assert_eq!(super::parse("5.49"), Some((5, 49)));
        assert_eq!(super::parse("4.228"), Some((4, 228)));
        assert_eq!(super::parse("rev"), None);
    }
}
