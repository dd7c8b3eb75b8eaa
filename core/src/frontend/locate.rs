//! Where a variable of the simulated design is in the user's sources: from the name Verilator
//! gives it (`botsim_board__DOT__user__DOT__SSB__DOT__refresh`) to the instance path
//! (`SSB.refresh`), the module that declares it and the line.
//!
//! ```
//! use botsim_core::frontend::locate::design_path;
//! assert_eq!(design_path("botsim_board__DOT__user__DOT__SSB__DOT__refresh").as_deref(), Some("SSB.refresh"));
//! assert_eq!(design_path("botsim_board__DOT__user__DOT__gen__BRA__1__KET____DOT__q").as_deref(), Some("gen[1].q"));
//! assert_eq!(design_path("__VactIterCount"), None);
//! ```

use std::path::PathBuf;

use super::resolve::Design;

/// The prefix of the user's design in the wrapper (`botsim_board.user`).
const USER: &str = "botsim_board__DOT__user__DOT__";

/// The path of a variable of the user's design below its top, from Verilator's name; `None`
/// for the wrapper's and Verilator's own variables.
pub fn design_path(verilator_name: &str) -> Option<String> {
    // A delayed copy kept in the root (`__Vdly__x`) is its variable's.
    let name = verilator_name.strip_prefix("__Vdly__").unwrap_or(verilator_name);
    let rest = name.strip_prefix(USER)?;
    let dotted = rest.replace("__DOT__", ".").replace("__BRA__", "[").replace("__KET__", "]");
    // Verilator's temporaries for an instance's port (`__Vcellout__div0_flop__Q`, an output
    // it connects; `__Vcellinp__`, an input): the port of that instance, as the user knows it.
    let named: Vec<String> = dotted
        .split('.')
        .map(|part| {
            let port = part.strip_prefix("__Vcellout__").or_else(|| part.strip_prefix("__Vcellinp__"));
            match port.and_then(|p| p.rsplit_once("__")) {
                Some((instance, port)) if !instance.is_empty() && !port.is_empty() => format!("{instance}.{port}"),
                _ => part.to_string(),
            }
        })
        .collect();
    Some(unescape(&named.join(".")))
}

/// Verilator's `__0XX` escapes of characters a C++ name cannot hold.
fn unescape(s: &str) -> String {
    let mut out = String::new();
    let mut rest = s;
    while let Some(i) = rest.find("__0") {
        let hex = rest.get(i + 3..i + 5).and_then(|h| u8::from_str_radix(h, 16).ok());
        match hex {
            Some(b) if b.is_ascii() && !b.is_ascii_control() => {
                out.push_str(&rest[..i]);
                out.push(b as char);
                rest = &rest[i + 5..];
            }
            _ => {
                out.push_str(&rest[..i + 3]);
                rest = &rest[i + 3..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// Where a variable is declared.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Declared {
    /// Its path below the top (`SSB.refresh`).
    pub path: String,
    pub module: String,
    pub file: PathBuf,
    pub line: u32,
}

/// Where the variable at `path` (below the top `top`) is declared: the instances followed
/// from the top (a generate block's name stays in the module it is in), then the first line
/// of that module that declares the name; the module's own line when none does.
pub fn declared(design: &Design, top: &str, path: &str) -> Option<Declared> {
    let parts: Vec<&str> = path.split('.').collect();
    let (name, scopes) = parts.split_last()?;
    let find = |module: &str| design.sources.iter().find_map(|s| s.module(module).map(|m| (s, m)));
    let (mut src, mut module) = find(top)?;
    for scope in scopes {
        let base = scope.split('[').next().unwrap_or(scope);
        if let Some(i) = module.instances.iter().find(|i| i.name == base) {
            if let Some(next) = find(&i.module) {
                (src, module) = next;
            } else {
                // Not the user's module (a Xilinx primitive, a core botsim made): the instance
                // where the user wrote it.
                return Some(Declared {
                    path: path.to_string(),
                    module: module.name.clone(),
                    file: src.path.clone(),
                    line: i.line,
                });
            }
        }
    }
    let name = name.split('[').next().unwrap_or(name);
    let text = src.text.get(module.span.clone())?;
    let mut line = module.line;
    let base_line = src.text[..module.span.start].matches('\n').count() as u32 + 1;
    for (i, l) in text.lines().enumerate() {
        let code = l.split("//").next().unwrap_or("");
        let declares = ["reg", "wire", "logic", "integer", "output", "input", "bit", "int"]
            .iter()
            .any(|k| code.split(|c: char| !(c.is_alphanumeric() || c == '_')).any(|w| w == *k));
        if declares && code.split(|c: char| !(c.is_alphanumeric() || c == '_' || c == '$')).any(|w| w == name) {
            line = base_line + i as u32;
            break;
        }
    }
    Some(Declared { path: path.to_string(), module: module.name.clone(), file: src.path.clone(), line })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend::source::Source;

    #[test]
    fn a_variable_is_found_through_the_instances_and_generate_blocks() {
        let top = "module top(input clk);\n  generate if (1) begin : disp\n    sevenseg SSB (.clk(clk));\n  end endgenerate\n  reg [3:0] mine;\nendmodule\n";
        let ssb = "// the display\nmodule sevenseg(input clk);\n  wire a;\n  reg [17:0] refresh = 0; // counts\n  always @(posedge clk) refresh <= refresh + 1;\nendmodule\n";
        let design = Design {
            top: "top".into(),
            project: None,
            sources: vec![Source::new("top.v", top), Source::new("ssb.v", ssb)],
            include_dirs: vec![],
            notes: vec![],
            generated: vec![],
            placed: None,
        };
        let d = declared(&design, "top", "disp.SSB.refresh").unwrap();
        assert_eq!((d.module.as_str(), d.file, d.line), ("sevenseg", PathBuf::from("ssb.v"), 4));
        let d = declared(&design, "top", "mine").unwrap();
        assert_eq!((d.module.as_str(), d.line), ("top", 5));
        assert!(declared(&design, "top", "nosuch.x").is_some_and(|d| d.module == "top"));
        // A port of an instance of a module not the user's (a primitive): that instance.
        let top = "module top(input clk);\n  reg d;\n  FD div0_flop (.C(clk), .D(d), .Q());\nendmodule\n";
        let design = Design { sources: vec![Source::new("top.v", top)], ..design };
        let d = declared(&design, "top", "div0_flop.Q").unwrap();
        assert_eq!((d.module.as_str(), d.file, d.line), ("top", PathBuf::from("top.v"), 3));
    }
}
