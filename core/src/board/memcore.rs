//! Xilinx memory cores (spec board.md 4) as behavioural Verilog: a Block Memory Generator or
//! Distributed Memory Generator core configured in an IP file (`.xci`) becomes a module of
//! the core's name with the core's ports, width, depth, read latency and contents (`.coe` or
//! `.mif`). The library models the cores' own wrappers instantiate are Xilinx's; these take
//! their place.
//!
//! ```
//! use botsim_core::board::memcore::parse_coe;
//! let words = parse_coe("memory_initialization_radix=16;\nmemory_initialization_vector=\n0A, 1f 3,\n;").unwrap();
//! assert_eq!(words, [0x0A, 0x1F, 0x3]);
//! ```

use std::path::{Path, PathBuf};

use super::BoardError;

/// Which generator, with what it decides about the ports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Block Memory Generator, port A: `clka`, `addra`, `douta`; `ena` unless always
    /// enabled; `wea`, `dina` for RAMs. Read latency 1, plus 1 for each output register.
    Block { has_enable: bool, writable: bool, latency: u32 },
    /// Distributed Memory Generator: `a`, `spo` (asynchronous read) or `clk` + `qspo`
    /// (registered); `d`, `we` for RAMs.
    Distributed { registered: bool, writable: bool },
}

/// A memory core to model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MemCore {
    pub name: String,
    pub kind: Kind,
    pub width: u32,
    pub depth: u32,
    pub init: Vec<u64>,
}

/// The `(referenceId, value)` pairs of an `.xci`'s configurable element values.
fn xci_values(text: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let key = "referenceId=\"";
    let mut rest = text;
    while let Some(i) = rest.find(key) {
        rest = &rest[i + key.len()..];
        let Some(end) = rest.find('"') else { break };
        let id = rest[..end].to_string();
        let after = &rest[end..];
        let (Some(gt), Some(lt)) = (after.find('>'), after.find('<')) else { break };
        if gt < lt && !after[..gt].ends_with('/') {
            out.push((id, after[gt + 1..lt].trim().to_string()));
        }
        rest = after;
    }
    out
}

impl MemCore {
    /// The core configured by the `.xci` at `path`, or `None` when it is not a memory core.
    pub fn from_xci(path: &Path) -> Result<Option<MemCore>, BoardError> {
        let text =
            std::fs::read_to_string(path).map_err(|e| BoardError::at(path, 0, 0, format!("cannot read: {e}")))?;
        let values = xci_values(&text);
        let get = |id: &str| {
            values.iter().find(|(k, _)| k.eq_ignore_ascii_case(&format!("PARAM_VALUE.{id}"))).map(|(_, v)| v.as_str())
        };
        let num = |id: &str| -> Result<u32, BoardError> {
            get(id)
                .and_then(|v| v.parse().ok())
                .ok_or_else(|| BoardError::at(path, 0, 0, format!("the core has no numeric {id}")))
        };
        let name = get("Component_Name")
            .map(str::to_string)
            .unwrap_or_else(|| path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default());
        let init_file = |id: &str| {
            get(id).filter(|v| !v.is_empty() && !v.eq_ignore_ascii_case("no_coe_file_loaded")).map(|v| resolve(path, v))
        };
        let is_true = |id: &str| get(id).is_some_and(|v| v.eq_ignore_ascii_case("true"));
        let (kind, width, depth, init) = if text.contains("spirit:name=\"blk_mem_gen\"") {
            let memory_type = get("Memory_Type").unwrap_or("Single_Port_RAM");
            let writable = !memory_type.contains("ROM");
            let latency = 1
                + is_true("Register_PortA_Output_of_Memory_Primitives") as u32
                + is_true("Register_PortA_Output_of_Memory_Core") as u32;
            let has_enable = get("Enable_A") != Some("Always_Enabled");
            let load = is_true("Load_Init_File") || !writable;
            let init = match init_file("Coe_File").filter(|_| load) {
                Some(f) => read_init(&f)?,
                None => vec![],
            };
            (Kind::Block { has_enable, writable, latency }, num("Read_Width_A")?, num("Write_Depth_A")?, init)
        } else if text.contains("spirit:name=\"dist_mem_gen\"") {
            let memory_type = get("memory_type").unwrap_or("rom");
            let registered = get("output_options").is_some_and(|v| v.eq_ignore_ascii_case("registered"));
            let init = match init_file("coefficient_file") {
                Some(f) => read_init(&f)?,
                None => vec![],
            };
            let kind = Kind::Distributed { registered, writable: memory_type != "rom" };
            (kind, num("data_width")?, num("depth")?, init)
        } else {
            return Ok(None);
        };
        if width == 0 || width > 64 || depth == 0 || depth > 1 << 20 {
            return Err(BoardError::at(path, 0, 0, format!("a {width}-bit x {depth} memory is not supported")));
        }
        if init.len() > depth as usize {
            return Err(BoardError::at(path, 0, 0, format!("{} initial words for a depth of {depth}", init.len())));
        }
        Ok(Some(MemCore { name, kind, width, depth, init }))
    }

    /// The core as behavioural Verilog.
    pub fn verilog(&self) -> String {
        let aw = (32 - (self.depth - 1).leading_zeros()).max(1);
        let (w, d) = (self.width, self.depth);
        let mut init = String::new();
        for (i, v) in self.init.iter().enumerate() {
            if *v != 0 {
                init.push_str(&format!("        mem[{i}] = {w}'h{v:X};\n"));
            }
        }
        let body = match &self.kind {
            Kind::Block { has_enable, writable, latency } => {
                let mut ports = vec!["input wire clka".to_string()];
                if *has_enable {
                    ports.push("input wire ena".into());
                }
                if *writable {
                    ports.push("input wire [0:0] wea".into());
                }
                ports.push(format!("input wire [{}:0] addra", aw - 1));
                if *writable {
                    ports.push(format!("input wire [{}:0] dina", w - 1));
                }
                ports.push(format!("output wire [{}:0] douta", w - 1));
                let en = if *has_enable { "ena" } else { "1'b1" };
                let write =
                    if *writable { "            if (wea[0]) mem[addra] <= dina;\n".to_string() } else { String::new() };
                // The read register, then one register per output-register option.
                let mut regs = format!("    reg [{}:0] q [0:{}];\n    integer k;\n", w - 1, latency - 1);
                regs.push_str(&format!(
                    "    initial for (k = 0; k < {latency}; k = k + 1) q[k] = {w}'d0;\n\
                     \x20   always @(posedge clka) begin\n\
                     \x20       if ({en}) begin\n{write}\
                     \x20           q[0] <= mem[addra];\n\
                     \x20       end\n\
                     \x20       for (k = 1; k < {latency}; k = k + 1) q[k] <= q[k - 1];\n\
                     \x20   end\n\
                     \x20   assign douta = q[{}];\n",
                    latency - 1
                ));
                (ports, regs)
            }
            Kind::Distributed { registered, writable } => {
                let mut ports = vec![format!("input wire [{}:0] a", aw - 1)];
                if *registered || *writable {
                    ports.push("input wire clk".into());
                }
                if *writable {
                    ports.push(format!("input wire [{}:0] d", w - 1));
                    ports.push("input wire we".into());
                }
                let mut body = String::new();
                if *writable {
                    body.push_str("    always @(posedge clk) if (we) mem[a] <= d;\n");
                }
                if *registered {
                    ports.push(format!("output reg [{}:0] qspo = {w}'d0", w - 1));
                    body.push_str("    always @(posedge clk) qspo <= mem[a];\n");
                } else {
                    ports.push(format!("output wire [{}:0] spo", w - 1));
                    body.push_str("    assign spo = mem[a];\n");
                }
                (ports, body)
            }
        };
        let what = match self.kind {
            Kind::Block { latency, .. } => format!("Block Memory Generator core, read latency {latency}"),
            Kind::Distributed { registered: true, .. } => "Distributed Memory Generator core, registered output".into(),
            Kind::Distributed { .. } => "Distributed Memory Generator core, asynchronous read".into(),
        };
        format!(
            "// Generated by botsim board: `{name}`, a {what}, {w} x {d}, from its .xci.\n\
             `timescale 1ns / 1ps\n\
             /* verilator lint_off WIDTH */\n\
             module {name} (\n    {ports}\n);\n\
             \x20   reg [{wm}:0] mem [0:{dm}];\n\
             \x20   integer i;\n\
             \x20   initial begin\n\
             \x20       for (i = 0; i < {d}; i = i + 1) mem[i] = {w}'d0;\n{init}\
             \x20   end\n{body}endmodule\n",
            name = self.name,
            ports = body.0.join(",\n    "),
            wm = w - 1,
            dm = d - 1,
            body = body.1,
        )
    }
}

/// A path in an `.xci`, relative to its folder.
fn resolve(xci: &Path, value: &str) -> PathBuf {
    let v = value.replace('\\', "/");
    let p = Path::new(&v);
    if p.is_absolute() {
        p.to_path_buf()
    } else {
        xci.parent().unwrap_or(Path::new(".")).join(p)
    }
}

/// The words of a `.coe` or a Xilinx `.mif` file.
fn read_init(path: &Path) -> Result<Vec<u64>, BoardError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| BoardError::at(path, 0, 0, format!("cannot read the memory's initial contents: {e}")))?;
    let r = if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("mif")) {
        parse_mif(&text)
    } else {
        parse_coe(&text)
    };
    r.map_err(|(line, m)| BoardError::at(path, line, 0, m))
}

/// `.coe`: `memory_initialization_radix = 2|10|16;` and `memory_initialization_vector =`
/// values separated by commas and/or white space, ending with `;` (`;` comments too).
pub fn parse_coe(text: &str) -> Result<Vec<u64>, (u32, String)> {
    let mut radix = None;
    let mut words = Vec::new();
    let mut in_vector = false;
    for (n, raw) in text.lines().enumerate() {
        let line_no = n as u32 + 1;
        let mut line = raw.trim();
        if line.starts_with(';') && !in_vector {
            continue; // a comment line (inside the vector, `;` ends it)
        }
        if !in_vector {
            let lower = line.to_ascii_lowercase();
            if let Some(rest) = lower.strip_prefix("memory_initialization_radix") {
                let v = rest.trim_start().trim_start_matches('=').trim().trim_end_matches(';').trim();
                radix = Some(
                    v.parse::<u32>()
                        .ok()
                        .filter(|r| matches!(r, 2 | 10 | 16))
                        .ok_or((line_no, format!("radix {v}: expected 2, 10 or 16")))?,
                );
                continue;
            }
            if let Some(i) = lower.find("memory_initialization_vector") {
                let after = &line[i + "memory_initialization_vector".len()..];
                line = after.trim_start().trim_start_matches('=');
                in_vector = true;
            } else {
                continue;
            }
        }
        let radix = radix.ok_or((line_no, "the vector comes before memory_initialization_radix".to_string()))?;
        let (values, done) = match line.find(';') {
            Some(i) => (&line[..i], true),
            None => (line, false),
        };
        for tok in values.split(|c: char| c == ',' || c.is_whitespace()).filter(|t| !t.is_empty()) {
            let v = u64::from_str_radix(tok, radix)
                .map_err(|_| (line_no, format!("`{tok}` is not a radix-{radix} number")))?;
            words.push(v);
        }
        if done {
            return Ok(words);
        }
    }
    if in_vector {
        Err((text.lines().count() as u32, "the vector does not end with `;`".into()))
    } else {
        Err((1, "no memory_initialization_vector".into()))
    }
}

/// Xilinx `.mif`: one word per line as a binary string.
pub fn parse_mif(text: &str) -> Result<Vec<u64>, (u32, String)> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(n, l)| {
            u64::from_str_radix(l.trim(), 2).map_err(|_| (n as u32 + 1, format!("`{}` is not a binary word", l.trim())))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coe_radixes_separators_comments_and_errors() {
        let coe = "; icons\nmemory_initialization_radix = 2;\nmemory_initialization_vector =\n01 10,\n11,\n00;\n";
        assert_eq!(parse_coe(coe).unwrap(), [1, 2, 3, 0]);
        assert_eq!(
            parse_coe("memory_initialization_radix=10;\nmemory_initialization_vector= 9, 12;").unwrap(),
            [9, 12]
        );
        assert_eq!(
            parse_coe("memory_initialization_radix=16;\nmemory_initialization_vector=\n1, 2\n").unwrap_err().1,
            "the vector does not end with `;`"
        );
        assert_eq!(
            parse_coe("memory_initialization_radix=8;\n").unwrap_err(),
            (1, "radix 8: expected 2, 10 or 16".to_string())
        );
        assert_eq!(parse_coe("memory_initialization_radix=2;\nmemory_initialization_vector=\n012;").unwrap_err().0, 3);
        assert_eq!(parse_mif("0101\n1111\n").unwrap(), [5, 15]);
        // The closing `;` alone on the last line.
        assert_eq!(
            parse_coe("memory_initialization_radix=16;\nmemory_initialization_vector=\n1,\n2\n;\n").unwrap(),
            [1, 2]
        );
    }

    fn xci(component: &str, values: &[(&str, &str)]) -> String {
        let mut s = format!(
            "<spirit:design><spirit:componentInstance><spirit:componentRef spirit:vendor=\"xilinx.com\" spirit:library=\"ip\" spirit:name=\"{component}\" spirit:version=\"8.3\"/><spirit:configurableElementValues>\n"
        );
        for (k, v) in values {
            s.push_str(&format!("<spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.{k}\">{v}</spirit:configurableElementValue>\n"));
        }
        s + "</spirit:configurableElementValues></spirit:componentInstance></spirit:design>"
    }

    #[test]
    fn a_block_rom_from_its_xci_and_coe() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("ip/icon_rom")).unwrap();
        std::fs::write(
            dir.path().join("icons.coe"),
            "memory_initialization_radix=16;\nmemory_initialization_vector=0,3,2;",
        )
        .unwrap();
        let path = dir.path().join("ip/icon_rom/icon_rom.xci");
        std::fs::write(
            &path,
            xci(
                "blk_mem_gen",
                &[
                    ("Component_Name", "icon_rom"),
                    ("Memory_Type", "Single_Port_ROM"),
                    ("Read_Width_A", "2"),
                    ("Write_Depth_A", "4096"),
                    ("Register_PortA_Output_of_Memory_Primitives", "true"),
                    ("Register_PortA_Output_of_Memory_Core", "false"),
                    ("Enable_A", "Always_Enabled"),
                    ("Coe_File", "../../icons.coe"),
                ],
            ),
        )
        .unwrap();
        let core = MemCore::from_xci(&path).unwrap().unwrap();
        assert_eq!(core.kind, Kind::Block { has_enable: false, writable: false, latency: 2 });
        assert_eq!((core.width, core.depth, core.init.clone()), (2, 4096, vec![0, 3, 2]));
        let v = core.verilog();
        assert!(v.contains("module icon_rom (\n    input wire clka,\n    input wire [11:0] addra,\n    output wire [1:0] douta\n);"), "{v}");
        assert!(v.contains("mem[1] = 2'h3;") && v.contains("assign douta = q[1];"), "{v}");
    }

    #[test]
    fn a_distributed_rom_and_what_is_not_a_memory() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("d.xci");
        std::fs::write(dir.path().join("c.coe"), "memory_initialization_radix=16;\nmemory_initialization_vector=5,6;")
            .unwrap();
        let values = [("Component_Name", "lut"), ("depth", "16"), ("data_width", "8"), ("coefficient_file", "c.coe")];
        std::fs::write(&path, xci("dist_mem_gen", &values)).unwrap();
        let core = MemCore::from_xci(&path).unwrap().unwrap();
        assert_eq!(core.kind, Kind::Distributed { registered: false, writable: false });
        assert!(core.verilog().contains("assign spo = mem[a];"));
        std::fs::write(&path, xci("clk_wiz", &[("Component_Name", "clk_wiz_0")])).unwrap();
        assert_eq!(MemCore::from_xci(&path).unwrap(), None);
    }
}
