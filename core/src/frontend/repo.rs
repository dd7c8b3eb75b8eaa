//! A repository as a team committed it: every file under its folders, by kind, found by name
//! when a project or an IP names a path from another machine, with the time each was last
//! committed (git) or changed. [`super::resolve`] chooses the design from it.
//!
//! ```no_run
//! use botsim_core::frontend::repo::Repo;
//! let repo = Repo::walk(&[std::path::PathBuf::from("my_clone")]).unwrap();
//! println!("{} Verilog files, {} projects", repo.hdl.len(), repo.projects.len());
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use super::BoardError;

/// The files of a repository, by kind.
#[derive(Clone, Debug, Default)]
pub struct Repo {
    /// The folders walked.
    pub roots: Vec<PathBuf>,
    /// Verilog and SystemVerilog (`.v`, `.sv`).
    pub hdl: Vec<PathBuf>,
    /// Include files (`.vh`, `.svh`).
    pub headers: Vec<PathBuf>,
    /// VHDL (`.vhd`, `.vhdl`).
    pub vhdl: Vec<PathBuf>,
    /// IP configurations (`.xci`, `.xco`).
    pub ip: Vec<PathBuf>,
    /// Project files (`.xpr`, `.xise`).
    pub projects: Vec<PathBuf>,
    /// Constraint files (`.ucf`, `.xdc`).
    pub constraints: Vec<PathBuf>,
    /// Every file, by lower-case file name.
    by_name: BTreeMap<String, Vec<PathBuf>>,
    /// Every file's canonical path: a file named twice (by a folder and by a project) is
    /// one file.
    seen: std::collections::BTreeSet<PathBuf>,
}

/// What a file is, by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    Hdl,
    Header,
    Vhdl,
    Ip,
    Project,
    /// A constraint file (`.ucf`, `.xdc`).
    Constraints,
    Other,
}

impl FileKind {
    pub fn of(path: &Path) -> FileKind {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("v" | "sv") => FileKind::Hdl,
            Some("vh" | "svh") => FileKind::Header,
            Some("vhd" | "vhdl") => FileKind::Vhdl,
            Some("xci" | "xco") => FileKind::Ip,
            Some("xpr" | "xise") => FileKind::Project,
            Some("ucf" | "xdc") => FileKind::Constraints,
            _ => FileKind::Other,
        }
    }
}

impl Repo {
    /// Every file under `roots` (hidden folders such as `.git` and `.Xil`, and cache folders
    /// tagged as such with a `CACHEDIR.TAG`, as Cargo's `target` and botsim's own cache are,
    /// skipped; links to folders not followed), in a stable order.
    pub fn walk(roots: &[PathBuf]) -> Result<Repo, BoardError> {
        let mut repo = Repo { roots: roots.to_vec(), ..Repo::default() };
        let mut files = Vec::new();
        for root in roots {
            let mut stack = vec![root.clone()];
            while let Some(d) = stack.pop() {
                let entries =
                    std::fs::read_dir(&d).map_err(|e| BoardError::at(&d, 0, 0, format!("cannot read folder: {e}")))?;
                for e in entries.flatten() {
                    if e.file_name().to_string_lossy().starts_with('.') {
                        continue;
                    }
                    let Ok(t) = e.file_type() else { continue };
                    if t.is_dir() {
                        if !e.path().join("CACHEDIR.TAG").exists() {
                            stack.push(e.path());
                        }
                    } else if t.is_file() || (t.is_symlink() && e.path().is_file()) {
                        files.push(e.path());
                    }
                }
            }
        }
        files.sort();
        files.dedup();
        for f in files {
            repo.add(f);
        }
        Ok(repo)
    }

    /// Add a file (one named outside the folders walked, e.g. by a project).
    pub fn add(&mut self, f: PathBuf) {
        let f = tidy(&f);
        if !self.seen.insert(canonical(&f)) {
            return;
        }
        let name = f.file_name().map(|n| n.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
        self.by_name.entry(name).or_default().push(f.clone());
        match FileKind::of(&f) {
            FileKind::Hdl => self.hdl.push(f),
            FileKind::Header => self.headers.push(f),
            FileKind::Vhdl => self.vhdl.push(f),
            FileKind::Ip => self.ip.push(f),
            FileKind::Project => self.projects.push(f),
            FileKind::Constraints => self.constraints.push(f),
            FileKind::Other => {}
        }
    }

    /// Every file whose extension is `ext` (any case), in path order.
    pub fn files_with_extension(&self, ext: &str) -> Vec<PathBuf> {
        let mut out: Vec<PathBuf> = self
            .by_name
            .values()
            .flatten()
            .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case(ext)))
            .cloned()
            .collect();
        out.sort();
        out
    }

    /// The one file named `name` in the repository (exactly, else without regard to case, as
    /// on the Windows machines the projects were made on); `None` when none or several are.
    pub fn find(&self, name: &str) -> Option<PathBuf> {
        self.find_near(name, Path::new("/nowhere/at/all"))
    }

    /// The file named `name` nearest to the folder `near` (the one that shares the longest
    /// path with it, when only one does); exact names before names in another case.
    pub fn find_near(&self, name: &str, near: &Path) -> Option<PathBuf> {
        let all = self.by_name.get(&name.to_ascii_lowercase())?;
        let exact: Vec<&PathBuf> = all.iter().filter(|p| p.file_name().is_some_and(|n| n == name)).collect();
        let near = std::path::absolute(near).unwrap_or(near.to_path_buf());
        let nearest = |cands: Vec<&PathBuf>| -> Option<PathBuf> {
            let depth = |p: &PathBuf| {
                let p = std::path::absolute(p).unwrap_or(p.clone());
                p.components().zip(near.components()).take_while(|(a, b)| a == b).count()
            };
            let best = cands.iter().map(|p| depth(p)).max()?;
            let at_best: Vec<&&PathBuf> = cands.iter().filter(|p| depth(p) == best).collect();
            (at_best.len() == 1).then(|| at_best[0].to_path_buf())
        };
        if exact.is_empty() {
            nearest(all.iter().collect())
        } else {
            nearest(exact)
        }
    }
}

/// When each file was last committed (seconds since 1970), from `git log` in the repository
/// holding `root`; files git does not know (and folders outside git) get their modification
/// time.
#[derive(Debug, Default)]
pub struct Ages {
    committed: BTreeMap<PathBuf, i64>,
}

impl Ages {
    /// Ask git once for the whole history under `root`.
    pub fn of(root: &Path) -> Ages {
        let mut committed = BTreeMap::new();
        let top = Command::new("git").arg("-C").arg(root).args(["rev-parse", "--show-toplevel"]).output();
        let Some(top) = top.ok().filter(|o| o.status.success()) else { return Ages { committed } };
        let top = PathBuf::from(String::from_utf8_lossy(&top.stdout).trim());
        let log = Command::new("git")
            .arg("-C")
            .arg(&top)
            .args(["log", "--no-renames", "--format=@%ct", "--name-only", "--", "."])
            .output();
        if let Some(log) = log.ok().filter(|o| o.status.success()) {
            let mut time = 0i64;
            for line in String::from_utf8_lossy(&log.stdout).lines() {
                if let Some(t) = line.strip_prefix('@') {
                    time = t.parse().unwrap_or(0);
                } else if !line.is_empty() {
                    // Newest first: the first time a file appears is its last commit.
                    committed.entry(canonical(&top.join(line))).or_insert(time);
                }
            }
        }
        Ages { committed }
    }

    /// When `path` was last committed, if git knows it.
    pub fn committed(&self, path: &Path) -> Option<i64> {
        self.committed.get(&canonical(path)).copied()
    }

    /// When `path` was last committed, or else last modified.
    pub fn of_file(&self, path: &Path) -> i64 {
        if let Some(t) = self.committed.get(&canonical(path)) {
            return *t;
        }
        std::fs::metadata(path)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
            .map_or(0, |d| d.as_secs() as i64)
    }
}

/// How many leading components two paths share (the nearer of two files to a third).
pub fn common_depth(a: &Path, b: &Path) -> usize {
    a.components().zip(b.components()).take_while(|(x, y)| x == y).count()
}

/// `a/b/../c` as `a/c`, `./x` as `x`: a path as a person writes it, without asking the file
/// system (a `..` after a link would differ, which the repositories here do not have).
///
/// ```
/// use botsim_core::frontend::repo::tidy;
/// use std::path::Path;
/// assert_eq!(tidy(Path::new("p/ip/x/../../../coe/a.coe")), Path::new("coe/a.coe"));
/// assert_eq!(tidy(Path::new("p/..")), Path::new("."));
/// assert_eq!(tidy(Path::new("../up/./f.v")), Path::new("../up/f.v"));
/// ```
pub fn tidy(path: &Path) -> PathBuf {
    use std::path::Component;
    let mut out: Vec<Component> = Vec::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => match out.last() {
                Some(Component::Normal(_)) => {
                    out.pop();
                }
                Some(Component::RootDir | Component::Prefix(_)) => {}
                _ => out.push(c),
            },
            _ => out.push(c),
        }
    }
    if out.is_empty() {
        PathBuf::from(".")
    } else {
        out.iter().collect()
    }
}

fn canonical(p: &Path) -> PathBuf {
    std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_by_kind_and_by_name_in_any_case() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for f in ["src/top.v", "src/defs.vh", "ip/c/c.xci", "old/top.v", ".git/x.v", "p.xpr", "hdl/Icons.COE"] {
            std::fs::create_dir_all(d.join(f).parent().unwrap()).unwrap();
            std::fs::write(d.join(f), "").unwrap();
        }
        let r = Repo::walk(&[d.to_path_buf()]).unwrap();
        assert_eq!(r.hdl, [d.join("old/top.v"), d.join("src/top.v")]);
        assert_eq!((r.headers.len(), r.ip.len(), r.projects.len()), (1, 1, 1));
        assert_eq!(r.find("top.v"), None); // two of them
        assert_eq!(r.find("icons.coe"), Some(d.join("hdl/Icons.COE")));
        assert_eq!(r.find("defs.vh"), Some(d.join("src/defs.vh")));
    }
}
