//! A Vivado project (`.xpr`): its design sources and its top module. The project is XML; the
//! parts read here are the `DesignSrcs` file sets' `<File Path="...">` entries (paths may use
//! `$PPRDIR`, the project's folder, and `$PSRCDIR`, its `<name>.srcs` folder) and the
//! `TopModule` option. A listed IP (`.xci`) contributes the Verilog Vivado generated beside it
//! (its wrappers, not the stub or the simulation netlist).
//!
//! ```
//! use botsim_core::board::xpr::Project;
//! let xml = r#"<Project><FileSets><FileSet Name="sources_1" Type="DesignSrcs">
//!   <File Path="$PSRCDIR/sources_1/new/top.v"/>
//!   <Config><Option Name="TopModule" Val="top"/></Config></FileSet>
//!   <FileSet Name="sim_1" Type="SimulationSrcs"><File Path="$PSRCDIR/sim_1/tb.v"/></FileSet>
//! </FileSets></Project>"#;
//! let p = Project::parse(std::path::Path::new("/home/me/proj2/proj2.xpr"), xml);
//! assert_eq!(p.top.as_deref(), Some("top"));
//! assert_eq!(p.files, [std::path::PathBuf::from("/home/me/proj2/proj2.srcs/sources_1/new/top.v")]);
//! ```

use std::path::{Path, PathBuf};

use super::BoardError;

/// What botsim takes from a Vivado project.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Project {
    /// Design sources (Verilog, headers and IP `.xci` files), resolved.
    pub files: Vec<PathBuf>,
    /// The `TopModule` option of the design sources.
    pub top: Option<String>,
}

impl Project {
    /// Read a project file.
    pub fn read(path: &Path) -> Result<Project, BoardError> {
        let text =
            std::fs::read_to_string(path).map_err(|e| BoardError::at(path, 0, 0, format!("cannot read: {e}")))?;
        if !text.contains("<Project") {
            return Err(BoardError::at(path, 1, 1, "not a Vivado project (no <Project> element)"));
        }
        Ok(Project::parse(path, &text))
    }

    /// Parse a project's text; `path` resolves `$PPRDIR` and `$PSRCDIR`.
    pub fn parse(path: &Path, text: &str) -> Project {
        let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let srcs = dir.join(format!("{stem}.srcs"));
        let mut files = Vec::new();
        let mut top = None;
        let mut in_design = false;
        for tag in tags(text) {
            match tag.name {
                "FileSet" if !tag.closing => in_design = tag.attr("Type") == Some("DesignSrcs"),
                "FileSet" => in_design = false,
                "File" if in_design && !tag.closing => {
                    if let Some(p) = tag.attr("Path") {
                        let p = p.replace('\\', "/");
                        let resolved = if let Some(rest) = p.strip_prefix("$PSRCDIR/") {
                            srcs.join(rest)
                        } else if let Some(rest) = p.strip_prefix("$PPRDIR/") {
                            dir.join(rest)
                        } else if Path::new(&p).is_absolute() || is_drive_path(&p) {
                            PathBuf::from(&p)
                        } else {
                            dir.join(&p)
                        };
                        files.push(resolved);
                    }
                }
                "Option" if in_design && tag.attr("Name") == Some("TopModule") => {
                    top = tag.attr("Val").map(str::to_string);
                }
                _ => {}
            }
        }
        Project { files, top }
    }

    /// The Verilog this project gives botsim: its `.v`/`.sv` files, and for each `.xci` the
    /// Verilog beside it except stubs and simulation netlists; and notes for the user. A
    /// listed file that does not exist (a path from the machine the project was made on) is
    /// looked for by name in the project's folder; when no single file has that name, it is
    /// an error naming it.
    pub fn sources(&self, xpr: &Path) -> Result<(Vec<PathBuf>, Vec<String>), BoardError> {
        let mut out = Vec::new();
        let mut notes = Vec::new();
        let project_dir = xpr.parent().unwrap_or(Path::new("."));
        for listed in &self.files {
            let ext = listed.extension().and_then(|e| e.to_str()).unwrap_or("");
            if !matches!(ext, "v" | "sv" | "vh" | "svh" | "xci") {
                continue;
            }
            let mut f = listed.clone();
            if !f.exists() {
                match listed.file_name().and_then(|n| find_by_name(project_dir, n)) {
                    Some(found) => {
                        notes.push(format!(
                            "{}: lists {}, which is not here; using {}",
                            xpr.display(),
                            listed.display(),
                            found.display()
                        ));
                        f = found;
                    }
                    None => {
                        return Err(BoardError::at(
                            xpr,
                            0,
                            0,
                            format!(
                                "lists {}, which does not exist (a path from another machine? copy the file into the project folder)",
                                listed.display()
                            ),
                        ))
                    }
                }
            }
            if ext == "xci" {
                let dir = f.parent().unwrap_or(Path::new("."));
                let mut beside: Vec<PathBuf> = std::fs::read_dir(dir)
                    .map_err(|e| BoardError::at(dir, 0, 0, format!("cannot read folder: {e}")))?
                    .flatten()
                    .map(|e| e.path())
                    .filter(|p| {
                        let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                        p.extension().is_some_and(|e| e == "v")
                            && !name.ends_with("_stub.v")
                            && !name.contains("_sim_netlist")
                            && !name.contains("_funcsim")
                    })
                    .collect();
                beside.sort();
                out.extend(beside);
            } else {
                out.push(f);
            }
        }
        Ok((out, notes))
    }
}

/// `C:/...`: a Windows absolute path (from the machine the project was made on).
fn is_drive_path(p: &str) -> bool {
    let b = p.as_bytes();
    b.len() > 2 && b[0].is_ascii_alphabetic() && b[1] == b':' && b[2] == b'/'
}

/// A file found by name under `dir` when exactly one has that name.
fn find_by_name(dir: &Path, name: &std::ffi::OsStr) -> Option<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.file_name() == Some(name) {
                found.push(p);
            }
        }
    }
    (found.len() == 1).then(|| found.remove(0))
}

/// One XML tag: its name, whether it closes, its attributes.
struct Tag<'a> {
    name: &'a str,
    closing: bool,
    body: &'a str,
}

impl<'a> Tag<'a> {
    fn attr(&self, key: &str) -> Option<&'a str> {
        let mut rest = self.body;
        while let Some(i) = rest.find(key) {
            let after = &rest[i + key.len()..];
            let before_ok = i == 0 || rest.as_bytes()[i - 1].is_ascii_whitespace();
            if before_ok {
                if let Some(v) = after.trim_start().strip_prefix('=') {
                    let v = v.trim_start();
                    if let Some(q) = v.chars().next().filter(|c| *c == '"' || *c == '\'') {
                        let end = v[1..].find(q)?;
                        return Some(&v[1..1 + end]);
                    }
                }
            }
            rest = after;
        }
        None
    }
}

/// The tags of an XML text, in order (comments, declarations and text skipped).
fn tags(text: &str) -> impl Iterator<Item = Tag<'_>> {
    let mut rest = text;
    std::iter::from_fn(move || loop {
        let start = rest.find('<')?;
        rest = &rest[start + 1..];
        if let Some(r) = rest.strip_prefix("!--") {
            let end = r.find("-->")?;
            rest = &r[end + 3..];
            continue;
        }
        let end = rest.find('>')?;
        let inner = &rest[..end];
        rest = &rest[end + 1..];
        if inner.starts_with('?') || inner.starts_with('!') {
            continue;
        }
        let closing = inner.starts_with('/');
        let inner = inner.trim_start_matches('/').trim_end_matches('/');
        let name_end = inner.find(|c: char| c.is_whitespace()).unwrap_or(inner.len());
        return Some(Tag { name: &inner[..name_end], closing, body: &inner[name_end..] });
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_relative_absolute_and_backslashed_and_only_design_sources() {
        let xml = r#"<?xml version="1.0"?>
<!-- Product Version: Vivado v2016.2 -->
<Project Version="7" Path="C:/x/proj.xpr">
  <FileSets Version="1">
    <FileSet Name="sources_1" Type="DesignSrcs" RelSrcDir="$PSRCDIR/sources_1">
      <File Path="$PPRDIR/../hdl/kcpsm6.v"><FileInfo><Attr Name="UsedIn" Val="synthesis"/></FileInfo></File>
      <File Path="$PSRCDIR\sources_1\new\top.v"/>
      <File Path="/abs/bot.v"/>
      <Config><Option Name="DesignMode" Val="RTL"/><Option Name="TopModule" Val="nexys4fpga"/></Config>
    </FileSet>
    <FileSet Name="constrs_1" Type="Constrs"><File Path="$PSRCDIR/constrs_1/n4.xdc"/></FileSet>
  </FileSets>
</Project>"#;
        let p = Project::parse(Path::new("/p/proj.xpr"), xml);
        assert_eq!(
            p.files,
            [
                PathBuf::from("/p/../hdl/kcpsm6.v"),
                PathBuf::from("/p/proj.srcs/sources_1/new/top.v"),
                PathBuf::from("/abs/bot.v")
            ]
        );
        assert_eq!(p.top.as_deref(), Some("nexys4fpga"));
    }

    #[test]
    fn an_ip_brings_its_wrappers_not_its_stub_or_netlist_and_a_missing_file_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let ip = dir.path().join("p.srcs/sources_1/ip/clk_wiz_0");
        std::fs::create_dir_all(&ip).unwrap();
        for f in ["clk_wiz_0.xci", "clk_wiz_0.v", "clk_wiz_0_clk_wiz.v", "clk_wiz_0_stub.v", "clk_wiz_0_sim_netlist.v"]
        {
            std::fs::write(ip.join(f), "").unwrap();
        }
        let xpr = dir.path().join("p.xpr");
        let xml = r#"<Project><FileSets><FileSet Type="DesignSrcs">
            <File Path="$PSRCDIR/sources_1/ip/clk_wiz_0/clk_wiz_0.xci"/></FileSet></FileSets></Project>"#;
        let (got, notes) = Project::parse(&xpr, xml).sources(&xpr).unwrap();
        assert_eq!(got, [ip.join("clk_wiz_0.v"), ip.join("clk_wiz_0_clk_wiz.v")]);
        assert!(notes.is_empty());
        let xml = r#"<Project><FileSets><FileSet Type="DesignSrcs"><File Path="C:/elsewhere/top.v"/></FileSet></FileSets></Project>"#;
        let e = Project::parse(&xpr, xml).sources(&xpr).unwrap_err().to_string();
        assert!(e.contains("lists C:/elsewhere/top.v, which does not exist"), "{e}");
        // Found by name in the project folder: used, with a note.
        std::fs::create_dir_all(dir.path().join("hdl")).unwrap();
        std::fs::write(dir.path().join("hdl/top.v"), "").unwrap();
        let (got, notes) = Project::parse(&xpr, xml).sources(&xpr).unwrap();
        assert_eq!(got, [dir.path().join("hdl/top.v")]);
        assert!(notes[0].contains("lists C:/elsewhere/top.v, which is not here; using"), "{notes:?}");
    }
}
