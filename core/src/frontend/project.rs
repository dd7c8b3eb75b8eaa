//! Vendor project files (spec board.md §6): a Vivado project (`.xpr`) or an ISE project
//! (`.xise`), read with a real XML parser. What botsim takes from one is what the vendor tool
//! compiles: the design's files (Vivado's `DesignSrcs` and per-IP `BlockSrcs` file sets, not
//! simulation sources or constraints, not disabled files; ISE's files associated with
//! `Implementation`) and the top module.
//!
//! ```
//! use botsim_core::frontend::project::Project;
//! use std::path::{Path, PathBuf};
//! let xml = r#"<Project><FileSets><FileSet Name="sources_1" Type="DesignSrcs">
//!   <File Path="$PSRCDIR/sources_1/new/top.v"/>
//!   <Config><Option Name="TopModule" Val="top"/></Config></FileSet>
//!   <FileSet Name="sim_1" Type="SimulationSrcs"><File Path="$PSRCDIR/sim_1/tb.v"/></FileSet>
//! </FileSets></Project>"#;
//! let p = Project::parse(Path::new("/home/me/proj2/proj2.xpr"), xml).unwrap();
//! assert_eq!(p.top.as_deref(), Some("top"));
//! assert_eq!(p.files, [PathBuf::from("/home/me/proj2/proj2.srcs/sources_1/new/top.v")]);
//! ```

use std::path::{Path, PathBuf};

use roxmltree::{Document, Node};

use super::repo::tidy;
use super::BoardError;

/// Which tool made a project.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tool {
    Vivado,
    Ise,
}

impl Tool {
    /// The tool whose project file `path` is, by extension.
    pub fn of(path: &Path) -> Option<Tool> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "xpr" => Some(Tool::Vivado),
            "xise" => Some(Tool::Ise),
            _ => None,
        }
    }
}

/// What botsim takes from a project file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Project {
    pub path: PathBuf,
    pub tool: Tool,
    /// The design's files as listed (HDL, headers, IP configurations), paths resolved against
    /// the project; a listed file may not exist (a path from the authors' machine).
    pub files: Vec<PathBuf>,
    /// The top module the project names.
    pub top: Option<String>,
}

impl Project {
    /// Read a project file (`.xpr` or `.xise`).
    pub fn read(path: &Path) -> Result<Project, BoardError> {
        let bytes = std::fs::read(path).map_err(|e| BoardError::at(path, 0, 0, format!("cannot read: {e}")))?;
        let text = String::from_utf8_lossy(&bytes);
        Project::parse(path, text.trim_start_matches('\u{feff}'))
    }

    /// Parse a project's text; `path` says which tool made it (its extension) and resolves
    /// the relative paths in it.
    pub fn parse(path: &Path, text: &str) -> Result<Project, BoardError> {
        let tool = Tool::of(path)
            .ok_or_else(|| BoardError::at(path, 0, 0, "not a project file (.xpr for Vivado, .xise for ISE)"))?;
        let doc = Document::parse(text).map_err(|e| {
            let pos = e.pos();
            BoardError::at(path, pos.row, pos.col, format!("not a well-formed project file: {e}"))
        })?;
        let root = doc.root_element();
        let (files, top) = match tool {
            Tool::Vivado => {
                if root.tag_name().name() != "Project" {
                    return Err(BoardError::at(path, 1, 1, "not a Vivado project (no <Project> element)"));
                }
                vivado(path, root)
            }
            Tool::Ise => {
                if root.tag_name().name() != "project" {
                    return Err(BoardError::at(path, 1, 1, "not an ISE project (no <project> element)"));
                }
                ise(path, root)
            }
        };
        Ok(Project { path: path.to_path_buf(), tool, files, top })
    }
}

/// An attribute by its local name (ISE's are in the `xil_pn` namespace).
fn attr<'a>(n: Node<'a, '_>, name: &str) -> Option<&'a str> {
    n.attributes().find(|a| a.name() == name).map(|a| a.value())
}

fn children<'a, 'i>(n: Node<'a, 'i>, name: &'static str) -> impl Iterator<Item = Node<'a, 'i>> {
    n.children().filter(move |c| c.is_element() && c.tag_name().name() == name)
}

/// Vivado: the `DesignSrcs` and `BlockSrcs` file sets' enabled files, and the design file
/// set's `TopModule`. Paths use `$PPRDIR` (the project's folder) and `$PSRCDIR`
/// (`<name>.srcs`); relative ones are relative to the project's folder.
fn vivado(path: &Path, root: Node) -> (Vec<PathBuf>, Option<String>) {
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let srcs = dir.join(format!("{stem}.srcs"));
    let resolve = |p: &str| {
        let p = p.replace('\\', "/");
        tidy(&if let Some(rest) = p.strip_prefix("$PSRCDIR/") {
            srcs.join(rest)
        } else if let Some(rest) = p.strip_prefix("$PPRDIR/") {
            dir.join(rest)
        } else if Path::new(&p).is_absolute() || is_drive_path(&p) {
            PathBuf::from(&p)
        } else {
            dir.join(&p)
        })
    };
    let mut files = Vec::new();
    let mut top = None;
    for set in root.descendants().filter(|n| n.has_tag_name("FileSet")) {
        let kind = attr(set, "Type").unwrap_or("");
        if kind != "DesignSrcs" && kind != "BlockSrcs" {
            continue;
        }
        for file in children(set, "File") {
            let Some(p) = attr(file, "Path") else { continue };
            let info: Vec<(&str, &str)> = file
                .descendants()
                .filter(|n| n.has_tag_name("Attr"))
                .filter_map(|a| Some((attr(a, "Name")?, attr(a, "Val")?)))
                .collect();
            let disabled =
                info.iter().any(|(n, v)| (*n == "IsEnabled" && *v == "0") || (*n == "AutoDisabled" && *v == "1"));
            let used_in: Vec<&str> = info.iter().filter(|(n, _)| *n == "UsedIn").map(|(_, v)| *v).collect();
            let simulation_only = !used_in.is_empty() && used_in.iter().all(|u| *u == "simulation");
            if !disabled && !simulation_only {
                files.push(resolve(p));
            }
        }
        if kind == "DesignSrcs" {
            let option = set.descendants().find(|n| n.has_tag_name("Option") && attr(*n, "Name") == Some("TopModule"));
            if let Some(v) = option.and_then(|o| attr(o, "Val")).filter(|v| !v.is_empty()) {
                top = Some(v.to_string());
            }
        }
    }
    (files, top)
}

/// ISE: the files associated with `Implementation` (paths relative to the `.xise`), and the
/// `Implementation Top` property (`Module|name`, or `Architecture|entity|arch` for VHDL).
fn ise(path: &Path, root: Node) -> (Vec<PathBuf>, Option<String>) {
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let mut files = Vec::new();
    for file in root.descendants().filter(|n| n.is_element() && n.tag_name().name() == "file") {
        let Some(name) = attr(file, "name") else { continue };
        let implementation = children(file, "association").any(|a| attr(a, "name") == Some("Implementation"));
        if implementation {
            let p = name.replace('\\', "/");
            files.push(if Path::new(&p).is_absolute() || is_drive_path(&p) {
                PathBuf::from(p)
            } else {
                tidy(&dir.join(p))
            });
        }
    }
    let top = root
        .descendants()
        .filter(|n| n.is_element() && n.tag_name().name() == "property")
        .find(|p| attr(*p, "name") == Some("Implementation Top"))
        .and_then(|p| attr(p, "value"))
        .and_then(|v| {
            let mut parts = v.split('|');
            match (parts.next(), parts.next()) {
                (Some(_), Some(name)) if !name.is_empty() => Some(name.to_string()),
                _ => None,
            }
        });
    (files, top)
}

/// `C:/...`: a Windows absolute path (from the machine the project was made on).
pub fn is_drive_path(p: &str) -> bool {
    let b = p.as_bytes();
    b.len() > 2 && b[0].is_ascii_alphabetic() && b[1] == b':' && (b[2] == b'/' || b[2] == b'\\')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vivado_design_and_block_sources_not_simulation_constraints_or_disabled_files() {
        let xml = r#"<?xml version="1.0"?>
<!-- Product Version: Vivado v2016.2 -->
<Project Version="7" Path="C:/x/proj.xpr">
  <FileSets Version="1">
    <FileSet Name="sources_1" Type="DesignSrcs" RelSrcDir="$PSRCDIR/sources_1">
      <File Path="$PPRDIR/../hdl/kcpsm6.v"><FileInfo><Attr Name="UsedIn" Val="synthesis"/></FileInfo></File>
      <File Path="$PSRCDIR\sources_1\new\top.v"/>
      <File Path="/abs/bot.v"/>
      <File Path="$PSRCDIR/sources_1/new/old_top.v"><FileInfo><Attr Name="IsEnabled" Val="0"/></FileInfo></File>
      <File Path="$PSRCDIR/sources_1/new/gone.v"><FileInfo><Attr Name="AutoDisabled" Val="1"/></FileInfo></File>
      <File Path="$PSRCDIR/sources_1/new/tb.v"><FileInfo><Attr Name="UsedIn" Val="simulation"/></FileInfo></File>
      <Config><Option Name="DesignMode" Val="RTL"/><Option Name="TopModule" Val="nexys4fpga"/></Config>
    </FileSet>
    <FileSet Name="clk_wiz_0" Type="BlockSrcs" RelSrcDir="$PSRCDIR/clk_wiz_0">
      <File Path="$PSRCDIR/sources_1/ip/clk_wiz_0/clk_wiz_0.xci"/>
      <Config><Option Name="TopModule" Val="clk_wiz_0"/></Config>
    </FileSet>
    <FileSet Name="constrs_1" Type="Constrs"><File Path="$PSRCDIR/constrs_1/n4.xdc"/></FileSet>
    <FileSet Name="sim_1" Type="SimulationSrcs"><File Path="$PSRCDIR/sim_1/tb.v"/>
      <Config><Option Name="TopModule" Val="tb"/></Config></FileSet>
  </FileSets>
</Project>"#;
        let p = Project::parse(Path::new("/p/proj.xpr"), xml).unwrap();
        assert_eq!(
            p.files,
            [
                PathBuf::from("/hdl/kcpsm6.v"),
                PathBuf::from("/p/proj.srcs/sources_1/new/top.v"),
                PathBuf::from("/abs/bot.v"),
                PathBuf::from("/p/proj.srcs/sources_1/ip/clk_wiz_0/clk_wiz_0.xci"),
            ]
        );
        assert_eq!(p.top.as_deref(), Some("nexys4fpga"));
    }

    #[test]
    fn ise_implementation_files_and_top() {
        let xml = r#"<?xml version="1.0" encoding="UTF-8" standalone="no" ?>
<project xmlns="http://www.xilinx.com/XMLSchema" xmlns:xil_pn="http://www.xilinx.com/XMLSchema">
  <files>
    <file xil_pn:name="../src/nexys3fpga.v" xil_pn:type="FILE_VERILOG">
      <association xil_pn:name="BehavioralSimulation" xil_pn:seqID="3"/>
      <association xil_pn:name="Implementation" xil_pn:seqID="3"/>
    </file>
    <file xil_pn:name="ipcore_dir\clk25.xco" xil_pn:type="FILE_COREGEN">
      <association xil_pn:name="Implementation" xil_pn:seqID="1"/>
    </file>
    <file xil_pn:name="tb.v" xil_pn:type="FILE_VERILOG">
      <association xil_pn:name="BehavioralSimulation" xil_pn:seqID="4"/>
    </file>
  </files>
  <properties>
    <property xil_pn:name="Implementation Top" xil_pn:value="Module|Nexys3fpga" xil_pn:valueState="non-default"/>
  </properties>
</project>"#;
        let p = Project::parse(Path::new("/r/ise/p.xise"), xml).unwrap();
        assert_eq!(p.tool, Tool::Ise);
        assert_eq!(p.files, [PathBuf::from("/r/src/nexys3fpga.v"), PathBuf::from("/r/ise/ipcore_dir/clk25.xco")]);
        assert_eq!(p.top.as_deref(), Some("Nexys3fpga"));
    }

    #[test]
    fn a_malformed_project_is_named_with_its_line_and_column() {
        let e = Project::parse(Path::new("p.xpr"), "<Project>\n  <FileSets>\n</Project>").unwrap_err();
        let e = e.to_string();
        assert!(e.starts_with("p.xpr:3:1: not a well-formed project file"), "{e}");
        let e = Project::parse(Path::new("p.xpr"), "<project/>").unwrap_err().to_string();
        assert!(e.contains("not a Vivado project"), "{e}");
    }
}
