//! Xilinx memory cores (spec board.md §4) as behavioural Verilog: a Block Memory Generator or
//! Distributed Memory Generator core becomes a module of the core's name with the core's
//! ports, width, depth, read latency, write mode and contents (`.coe`, `.mif` or `.mem`).
//! A core is known from its configuration ([`IpConfig`]: Vivado's `.xci`, ISE's `.xco`) or,
//! with neither, from the `C_*` parameters its generated wrapper gives Xilinx's library model
//! (`blk_mem_gen_v8_3`, `BLK_MEM_GEN_V7_3`, `dist_mem_gen_v8_0`). The library models
//! themselves are Xilinx's simulation code and never compiled: these stand for them.
//!
//! ```
//! use botsim_core::frontend::memcore::parse_coe;
//! let coe = parse_coe("memory_initialization_radix=16;\nmemory_initialization_vector=\n0A, 1f 3,\n;").unwrap();
//! assert_eq!(coe.words, [0x0A, 0x1F, 0x3]);
//! assert!(coe.unterminated.is_none());
//! ```

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::ip::IpConfig;
use super::scan::{Dir, Instance, Module, Port};
use super::BoardError;

/// One port of a block memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PortCfg {
    /// An enable pin (`ena`); without one the port is always enabled.
    pub enable: bool,
    pub write: bool,
    pub read: bool,
    /// Clocks from the address to the data: 1, plus 1 per output register.
    pub latency: u32,
    pub mode: WriteMode,
}

/// What a port reads in the clock it writes (the core's operating mode).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteMode {
    /// The new word (the Block Memory Generator's default).
    WriteFirst,
    /// The old word.
    ReadFirst,
    /// The output keeps its value.
    NoChange,
}

impl WriteMode {
    fn of(v: Option<&str>) -> WriteMode {
        match v.map(|v| v.trim_matches('"').to_ascii_uppercase()).as_deref() {
            Some("READ_FIRST") => WriteMode::ReadFirst,
            Some("NO_CHANGE") => WriteMode::NoChange,
            _ => WriteMode::WriteFirst,
        }
    }
}

/// Which generator, with what it decides about the ports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Block Memory Generator: port A (`clka`, `ena`, `wea`, `addra`, `dina`, `douta`) and,
    /// in the dual-port types, port B (`clkb`...).
    Block { a: PortCfg, b: Option<PortCfg> },
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
    /// The ports a wrapper declares, when the core comes from one: the model has exactly
    /// these (the ones it does not use are inputs it ignores or outputs at 0).
    pub ports: Option<Vec<Port>>,
    /// Where the configuration came from, and what the user should know about its files.
    pub origin: String,
    pub notes: Vec<String>,
}

/// The kinds of memory core botsim models, by the core's name in a configuration.
pub const MEMORY_CORES: &[&str] = &["blk_mem_gen", "dist_mem_gen"];

/// Finds a file by name in the repository (when exactly one has that name).
pub type Finder<'a> = &'a dyn Fn(&str) -> Option<PathBuf>;

/// Is `module` Xilinx's library model of a memory core (`blk_mem_gen_v8_3_3`,
/// `BLK_MEM_GEN_V7_3`, `dist_mem_gen_v8_0_10`)? Returns the core's kind.
pub fn library_model(module: &str) -> Option<&'static str> {
    let lower = module.to_ascii_lowercase();
    MEMORY_CORES.iter().copied().find(|core| {
        lower.strip_prefix(core).and_then(|r| r.strip_prefix("_v")).is_some_and(|version| {
            !version.is_empty() && version.split('_').all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
        })
    })
}

impl MemCore {
    /// The core a configuration describes, or `None` when it is not a memory core.
    pub fn from_config(ip: &IpConfig, find: Finder) -> Result<Option<MemCore>, BoardError> {
        let err = |m: String| BoardError::at(&ip.path, 0, 0, m);
        let num = |id: &str| -> Result<u32, BoardError> {
            ip.get(id).and_then(|v| v.parse().ok()).ok_or_else(|| err(format!("the core has no numeric {id}")))
        };
        let mut notes = Vec::new();
        let beside_mif = ip.path.with_file_name(format!("{}.mif", ip.name));
        let (kind, width, depth, init) = match ip.core.as_str() {
            "blk_mem_gen" => {
                let memory_type = ip.get("Memory_Type").unwrap_or("Single_Port_RAM").to_ascii_lowercase();
                let rom = memory_type.contains("rom");
                let dual = memory_type.contains("dual");
                let port = |x: &str, write: bool, read: bool| PortCfg {
                    enable: ip.get(&format!("Enable_{x}")).is_some_and(|v| !v.eq_ignore_ascii_case("Always_Enabled")),
                    write,
                    read,
                    latency: 1
                        + ip.flag(&format!("Register_Port{x}_Output_of_Memory_Primitives")).unwrap_or(false) as u32
                        + ip.flag(&format!("Register_Port{x}_Output_of_Memory_Core")).unwrap_or(false) as u32,
                    mode: WriteMode::of(ip.get(&format!("Operating_Mode_{x}"))),
                };
                let simple = memory_type.contains("simple");
                let a = port("A", !rom, !simple);
                let b = dual.then(|| port("B", !rom && !simple, true));
                let width = num("Read_Width_A").or_else(|_| num("Write_Width_A"))?;
                if let Ok(w) = num("Write_Width_A") {
                    if w != width && !rom {
                        return Err(err(format!("port A writes {w} bits and reads {width}: not supported")));
                    }
                }
                let load = ip.flag("Load_Init_File").unwrap_or(false) || rom;
                let file = ip.file("Coe_File").filter(|_| load);
                let init = init_words(file, &beside_mif, find, &ip.path, &mut notes)?;
                (Kind::Block { a, b }, width, num("Write_Depth_A")?, init)
            }
            "dist_mem_gen" => {
                let memory_type = ip.get("memory_type").unwrap_or("rom").to_ascii_lowercase();
                let registered = ip.get("output_options").is_some_and(|v| v.eq_ignore_ascii_case("registered"));
                let init = init_words(ip.file("coefficient_file"), &beside_mif, find, &ip.path, &mut notes)?;
                let kind = Kind::Distributed { registered, writable: memory_type != "rom" };
                (kind, num("data_width")?, num("depth")?, init)
            }
            _ => return Ok(None),
        };
        let core = MemCore {
            name: ip.name.clone(),
            kind,
            width,
            depth,
            init,
            ports: None,
            origin: ip.path.display().to_string(),
            notes,
        };
        core.checked(&ip.path).map(Some)
    }

    /// A Block Memory Generator core committed as its contents alone, a `.coe`: as deep as
    /// the file has words, as wide as its widest word is written (or needs), with the ports
    /// the instance connects (`clka`, `addra`, `douta`; `ena`; `wea`, `dina` make it a RAM;
    /// `clkb`... a second port), read latency 1 as the generator's default.
    ///
    /// ```
    /// use botsim_core::frontend::memcore::MemCore;
    /// let dir = tempfile::tempdir().unwrap();
    /// let coe = dir.path().join("frt.coe");
    /// std::fs::write(&coe, "memory_initialization_radix=16;\nmemory_initialization_vector=\n000, 0F3, 7A1, 000;\n").unwrap();
    /// let core = MemCore::from_coe("knitg", &["clka", "addra", "douta"], &coe).unwrap();
    /// assert_eq!((core.width, core.depth, core.init.len()), (12, 4, 4));
    /// assert!(core.verilog().contains("module knitg ("));
    /// ```
    pub fn from_coe(name: &str, connected: &[&str], path: &Path) -> Result<MemCore, BoardError> {
        let text = std::fs::read(path)
            .map_err(|e| BoardError::at(path, 0, 0, format!("cannot read the memory's initial contents: {e}")))?;
        let coe = parse_coe(&String::from_utf8_lossy(&text)).map_err(|(line, m)| BoardError::at(path, line, 0, m))?;
        let needed = coe.words.iter().map(|w| 64 - w.leading_zeros()).max().unwrap_or(0);
        let width = coe.written_bits.max(needed).clamp(1, 64);
        let mut notes = Vec::new();
        if let Some(line) = coe.unterminated {
            notes.push(format!(
                "{}:{line}: the vector does not end with `;` (Vivado reads it to the end of the file, and so does botsim)",
                path.display()
            ));
        }
        Ok(MemCore {
            name: name.to_string(),
            kind: block_ports(connected),
            width,
            depth: (coe.words.len() as u32).max(1),
            init: coe.words,
            ports: None,
            origin: format!("{} alone (no configuration)", path.display()),
            notes,
        })
    }

    /// A Block Memory Generator RAM committed with neither configuration nor contents (a
    /// frame buffer): `depth` x `width` starting at zero, as the generator makes one with
    /// no initial file, with the ports the instance connects (as [`MemCore::from_coe`]).
    ///
    /// ```
    /// use botsim_core::frontend::memcore::MemCore;
    /// let ram = MemCore::zeroed("fb", &["clka", "wea", "addra", "dina", "douta"], 1 << 15, 8);
    /// assert!(ram.init.is_empty());
    /// assert!(ram.verilog().contains("if ((|wea)) mem[addra] <= dina;"));
    /// ```
    pub fn zeroed(name: &str, connected: &[&str], depth: u32, width: u32) -> MemCore {
        MemCore {
            name: name.to_string(),
            kind: block_ports(connected),
            width: width.clamp(1, 64),
            depth: depth.max(1),
            init: Vec::new(),
            ports: None,
            origin: "the connected widths (no configuration, no .coe)".into(),
            notes: Vec::new(),
        }
    }

    /// The core a generated wrapper (`wrapper`, in `file`) describes through the `C_*`
    /// parameters of its instance `lib` of Xilinx's library model.
    pub fn from_wrapper(wrapper: &Module, lib: &Instance, file: &Path, find: Finder) -> Result<MemCore, BoardError> {
        let at = |m: String| BoardError::at(file, lib.line, lib.col, m);
        let get = |k: &str| {
            lib.params.iter().find(|(n, _)| n.eq_ignore_ascii_case(k)).map(|(_, v)| v.trim().trim_matches('"').trim())
        };
        let num = |k: &str| get(k).and_then(parse_int);
        let need = |k: &str| num(k).ok_or_else(|| at(format!("`{}` gives no numeric {k}", lib.module)));
        let flag = |k: &str| num(k).is_some_and(|v| v != 0);
        let mut notes = Vec::new();
        let core = library_model(&lib.module).unwrap_or("blk_mem_gen");
        let dir = file.parent().unwrap_or(Path::new("."));
        let init_file = |k: &str, load: bool| {
            get(k)
                .filter(|v| load && !v.is_empty() && !v.eq_ignore_ascii_case("no_coe_file_loaded") && *v != "NONE")
                .map(|v| dir.join(v.replace('\\', "/")))
        };
        let (kind, width, depth, init) = if core == "dist_mem_gen" {
            let registered = flag("C_HAS_QSPO") && !flag("C_HAS_SPO");
            let writable = flag("C_HAS_WE") || flag("C_HAS_D");
            let file_name = init_file("C_MEM_INIT_FILE", flag("C_READ_MIF"));
            let init = init_words(file_name, &dir.join(format!("{}.mif", wrapper.name)), find, file, &mut notes)?;
            (Kind::Distributed { registered, writable }, need("C_WIDTH")?, need("C_DEPTH")?, init)
        } else {
            // C_MEM_TYPE: 0 single-port RAM, 1 simple dual-port RAM, 2 true dual-port RAM,
            // 3 single-port ROM, 4 dual-port ROM.
            let mem_type = num("C_MEM_TYPE").unwrap_or(0);
            let rom = mem_type >= 3;
            let port = |x: &str, write: bool, read: bool| PortCfg {
                enable: flag(&format!("C_HAS_EN{x}")),
                write,
                read,
                latency: 1
                    + flag(&format!("C_HAS_MEM_OUTPUT_REGS_{x}")) as u32
                    + flag(&format!("C_HAS_MUX_OUTPUT_REGS_{x}")) as u32,
                mode: WriteMode::of(get(&format!("C_WRITE_MODE_{x}"))),
            };
            let a = port("A", !rom, mem_type != 1);
            let b = matches!(mem_type, 1 | 2 | 4).then(|| port("B", mem_type == 2, true));
            let width = num("C_READ_WIDTH_A").filter(|w| *w > 0).or_else(|| num("C_WRITE_WIDTH_A"));
            let width = width.ok_or_else(|| at(format!("`{}` gives no C_READ_WIDTH_A", lib.module)))?;
            let depth = num("C_READ_DEPTH_A").or_else(|| num("C_WRITE_DEPTH_A"));
            let depth = depth.ok_or_else(|| at(format!("`{}` gives no C_READ_DEPTH_A", lib.module)))?;
            let load = flag("C_LOAD_INIT_FILE");
            let file_name = init_file("C_INIT_FILE_NAME", load).or_else(|| init_file("C_INIT_FILE", load));
            let init = init_words(file_name, &dir.join(format!("{}.mif", wrapper.name)), find, file, &mut notes)?;
            (Kind::Block { a, b }, width, depth, init)
        };
        let core = MemCore {
            name: wrapper.name.clone(),
            kind,
            width: width as u32,
            depth: depth as u32,
            init,
            ports: Some(wrapper.ports.clone()),
            origin: format!("the parameters {} gives `{}` ({}:{})", wrapper.name, lib.module, file.display(), lib.line),
            notes,
        };
        core.checked(file)
    }

    fn checked(self, path: &Path) -> Result<MemCore, BoardError> {
        let (width, depth) = (self.width, self.depth);
        if width == 0 || width > 64 || depth == 0 || depth > 1 << 20 {
            return Err(BoardError::at(path, 0, 0, format!("a {width}-bit x {depth} memory is not supported")));
        }
        if self.init.len() > depth as usize {
            return Err(BoardError::at(
                path,
                0,
                0,
                format!("{} initial words for a depth of {depth}", self.init.len()),
            ));
        }
        Ok(self)
    }

    /// One line for the report: `a Block Memory Generator core, 8 x 4096, read latency 2`.
    pub fn summary(&self) -> String {
        let what = match &self.kind {
            Kind::Block { a, b: None } => format!("Block Memory Generator core, read latency {}", a.latency),
            Kind::Block { a, b: Some(b) } => {
                format!("dual-port Block Memory Generator core, read latencies {} and {}", a.latency, b.latency)
            }
            Kind::Distributed { registered: true, .. } => "Distributed Memory Generator core, registered output".into(),
            Kind::Distributed { .. } => "Distributed Memory Generator core, asynchronous read".into(),
        };
        format!("a {what}, {} x {}", self.width, self.depth)
    }

    /// The ports of the model: the wrapper's, or the generator's for the configuration.
    fn port_list(&self) -> Vec<Port> {
        if let Some(p) = &self.ports {
            return p.clone();
        }
        let aw = addr_width(self.depth);
        let p = |name: &str, dir: Dir, width: u32| Port {
            name: name.to_string(),
            dir,
            width,
            range: Some((width as i64 - 1, 0)),
            line: 0,
            col: 0,
        };
        let mut out = Vec::new();
        match &self.kind {
            Kind::Block { a, b } => {
                for (x, cfg) in [("a", Some(a)), ("b", b.as_ref())] {
                    let Some(cfg) = cfg else { continue };
                    out.push(p(&format!("clk{x}"), Dir::Input, 1));
                    if cfg.enable {
                        out.push(p(&format!("en{x}"), Dir::Input, 1));
                    }
                    if cfg.write {
                        out.push(p(&format!("we{x}"), Dir::Input, 1));
                    }
                    out.push(p(&format!("addr{x}"), Dir::Input, aw));
                    if cfg.write {
                        out.push(p(&format!("din{x}"), Dir::Input, self.width));
                    }
                    if cfg.read {
                        out.push(p(&format!("dout{x}"), Dir::Output, self.width));
                    }
                }
            }
            Kind::Distributed { registered, writable } => {
                out.push(p("a", Dir::Input, aw));
                if *writable {
                    out.push(p("d", Dir::Input, self.width));
                }
                if *registered || *writable {
                    out.push(p("clk", Dir::Input, 1));
                }
                if *writable {
                    out.push(p("we", Dir::Input, 1));
                }
                out.push(p(if *registered { "qspo" } else { "spo" }, Dir::Output, self.width));
            }
        }
        out
    }

    /// The core as behavioural Verilog.
    pub fn verilog(&self) -> String {
        let (w, d) = (self.width, self.depth);
        let ports = self.port_list();
        let has = |n: &str| ports.iter().any(|p| p.name == n);
        let decl: Vec<String> = ports
            .iter()
            .map(|p| {
                let dir = match p.dir {
                    Dir::Input => "input",
                    Dir::Output => "output",
                    Dir::Inout => "inout",
                };
                let range = match p.range {
                    Some((m, l)) if p.width > 1 || m != l || m != 0 || self.ports.is_some() => format!("[{m}:{l}] "),
                    None if p.width > 1 => format!("[{}:0] ", p.width - 1),
                    _ => String::new(),
                };
                format!("{dir} wire {range}{}", p.name)
            })
            .collect();
        let mut body = String::new();
        let mut driven = Vec::new();
        match &self.kind {
            Kind::Block { a, b } => {
                for (x, cfg) in [("a", Some(a)), ("b", b.as_ref())] {
                    let Some(cfg) = cfg else { continue };
                    let clk = format!("clk{x}");
                    if !has(&clk) {
                        continue;
                    }
                    let en = if has(&format!("en{x}")) { format!("en{x}") } else { "1'b1".into() };
                    let we = if cfg.write && has(&format!("we{x}")) { format!("(|we{x})") } else { "1'b0".into() };
                    let (addr, din, dout) = (format!("addr{x}"), format!("din{x}"), format!("dout{x}"));
                    let lat = cfg.latency.max(1);
                    let write = if we != "1'b0" {
                        format!("            if ({we}) mem[{addr}] <= {din};\n")
                    } else {
                        String::new()
                    };
                    let read = match cfg.mode {
                        WriteMode::WriteFirst if we != "1'b0" => {
                            format!("            q{x}[0] <= {we} ? {din} : mem[{addr}];\n")
                        }
                        WriteMode::NoChange if we != "1'b0" => {
                            format!("            if (!{we}) q{x}[0] <= mem[{addr}];\n")
                        }
                        _ => format!("            q{x}[0] <= mem[{addr}];\n"),
                    };
                    let _ = write!(
                        body,
                        "    reg [{wm}:0] q{x} [0:{lm}];\n\
                         \x20   initial for (k = 0; k < {lat}; k = k + 1) q{x}[k] = {w}'d0;\n\
                         \x20   always @(posedge {clk}) begin\n\
                         \x20       if ({en}) begin\n{write}{read}\
                         \x20       end\n\
                         \x20       for (k = 1; k < {lat}; k = k + 1) q{x}[k] <= q{x}[k - 1];\n\
                         \x20   end\n",
                        wm = w - 1,
                        lm = lat - 1,
                    );
                    if cfg.read && has(&dout) {
                        let _ = writeln!(body, "    assign {dout} = q{x}[{}];", lat - 1);
                        driven.push(dout);
                    }
                }
            }
            Kind::Distributed { registered, writable } => {
                if *writable && has("we") && has("clk") {
                    body.push_str("    always @(posedge clk) if (we) mem[a] <= d;\n");
                }
                if *registered {
                    let _ = writeln!(body, "    reg [{}:0] q = {w}'d0;\n    always @(posedge clk) q <= mem[a];", w - 1);
                    body.push_str("    assign qspo = q;\n");
                    driven.push("qspo".into());
                } else {
                    body.push_str("    assign spo = mem[a];\n");
                    driven.push("spo".into());
                }
            }
        }
        // Outputs of a wrapper the model does not compute (a second port's status, ECC).
        for p in ports.iter().filter(|p| p.dir == Dir::Output && !driven.contains(&p.name)) {
            let _ = writeln!(body, "    assign {} = 0;", p.name);
        }
        let mut init = String::new();
        for (i, v) in self.init.iter().enumerate() {
            if *v != 0 {
                let _ = writeln!(init, "        mem[{i}] = {w}'h{v:X};");
            }
        }
        format!(
            "// Generated by botsim board: `{name}`, {summary}, from {origin}.\n\
             `timescale 1ns / 1ps\n\
             /* verilator lint_off WIDTH */\n\
             module {name} (\n    {decl}\n);\n\
             \x20   reg [{wm}:0] mem [0:{dm}];\n\
             \x20   integer i, k;\n\
             \x20   initial begin\n\
             \x20       for (i = 0; i < {d}; i = i + 1) mem[i] = {w}'d0;\n{init}\
             \x20   end\n{body}endmodule\n",
            name = self.name,
            summary = self.summary(),
            origin = self.origin,
            decl = decl.join(",\n    "),
            wm = w - 1,
            dm = d - 1,
        )
    }
}

/// The ports of a Block Memory Generator core without configuration, from those the
/// instance connects: port A always, port B where any of its pins is connected; enables and
/// writes where connected; read latency 1 and write-first, the generator's defaults.
fn block_ports(connected: &[&str]) -> Kind {
    let has = |p: &str| connected.iter().any(|c| c.eq_ignore_ascii_case(p));
    let port = |x: &str| PortCfg {
        enable: has(&format!("en{x}")),
        write: has(&format!("we{x}")) || has(&format!("din{x}")),
        read: true,
        latency: 1,
        mode: WriteMode::WriteFirst,
    };
    let b = (has("clkb") || has("addrb") || has("doutb")).then(|| port("b"));
    Kind::Block { a: port("a"), b }
}

/// Does a core without configuration have a write port, by the pins the instance connects
/// (`wea`/`dina`, or port B's)?
pub fn writable(connected: &[&str]) -> bool {
    match block_ports(connected) {
        Kind::Block { a, b } => a.write || b.is_some_and(|b| b.write),
        Kind::Distributed { writable, .. } => writable,
    }
}

fn addr_width(depth: u32) -> u32 {
    (32 - depth.saturating_sub(1).leading_zeros()).max(1)
}

/// A Verilog integer parameter value: `12`, `32'd12`, `'h0C`.
fn parse_int(v: &str) -> Option<i64> {
    let v = v.replace('_', "");
    match v.split_once('\'') {
        None => v.parse().ok(),
        Some((_, rest)) => {
            let rest = rest.trim_start_matches(['s', 'S']);
            let (radix, digits) = match rest.chars().next()?.to_ascii_lowercase() {
                'h' => (16, &rest[1..]),
                'd' => (10, &rest[1..]),
                'o' => (8, &rest[1..]),
                'b' => (2, &rest[1..]),
                _ => return None,
            };
            i64::from_str_radix(digits, radix).ok()
        }
    }
}

/// The words of a core's initial contents: `file` where it is; otherwise the `.mif` Vivado
/// made from it beside the core (`beside`), or a file of the same name elsewhere in the
/// repository, each said in a note.
fn init_words(
    file: Option<PathBuf>,
    beside: &Path,
    find: Finder,
    owner: &Path,
    notes: &mut Vec<String>,
) -> Result<Vec<u64>, BoardError> {
    let Some(file) = file else { return Ok(Vec::new()) };
    let path = if file.is_file() {
        file
    } else if beside.is_file() {
        notes.push(format!(
            "{}: names {}, which is not here; using {}, the .mif Vivado made from it",
            owner.display(),
            file.display(),
            beside.display()
        ));
        beside.to_path_buf()
    } else {
        let name = file.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        match find(&name) {
            Some(found) => {
                notes.push(format!(
                    "{}: names {}, which is not here; using {}",
                    owner.display(),
                    file.display(),
                    found.display()
                ));
                found
            }
            None => {
                // Vivado or ISE would build it from a netlist that holds the contents (a
                // `.ngc`, a `.dcp`), which botsim cannot read: the design runs, its memory
                // blank, and the user is told which file would fill it.
                notes.push(format!(
                    "{}: the core's initial contents {} are not in the repository (a path from another machine, or only in a netlist): it starts all 0; add the file to see them",
                    owner.display(),
                    file.display()
                ));
                return Ok(Vec::new());
            }
        }
    };
    read_init(&path, notes)
}

/// The words of a `.coe`, a Xilinx `.mif` or a `$readmemh` `.mem` file.
fn read_init(path: &Path, notes: &mut Vec<String>) -> Result<Vec<u64>, BoardError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| BoardError::at(path, 0, 0, format!("cannot read the memory's initial contents: {e}")))?;
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    match ext.as_str() {
        "mif" => parse_mif(&text).map_err(|(line, m)| BoardError::at(path, line, 0, m)),
        "mem" => parse_mem(&text).map_err(|(line, m)| BoardError::at(path, line, 0, m)),
        _ => {
            let coe = parse_coe(&text).map_err(|(line, m)| BoardError::at(path, line, 0, m))?;
            if let Some(line) = coe.unterminated {
                notes.push(format!(
                    "{}:{line}: the vector does not end with `;` (Vivado reads it to the end of the file, and so does botsim)",
                    path.display()
                ));
            }
            Ok(coe.words)
        }
    }
}

/// A `$readmemh` file (Vivado's `.mem`): hexadecimal words, `@address` lines.
pub fn parse_mem(text: &str) -> Result<Vec<u64>, (u32, String)> {
    use kcpsm6::readmemh::{entries, Error};
    let entries = entries(text, 1 << 20).map_err(|e| match e {
        Error::BadAddress { token, line, .. } => (line as u32, format!("`{token}` is not an address in the memory")),
        Error::PastEnd { line, .. } => (line as u32, "a word past the end of the memory".to_string()),
        Error::UnclosedComment { line, .. } => (line as u32, "a comment without its */".to_string()),
    })?;
    let mut words = Vec::new();
    for e in entries {
        let v = u64::from_str_radix(&e.value, 16)
            .map_err(|_| (e.line as u32, format!("`{}` is not a hexadecimal word", e.value)))?;
        if words.len() <= e.address {
            words.resize(e.address + 1, 0);
        }
        words[e.address] = v;
    }
    Ok(words)
}

/// A `.coe` file's words.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Coe {
    pub words: Vec<u64>,
    /// The last line, when the vector runs to the end of the file without its `;`.
    pub unterminated: Option<u32>,
    /// The widest word as written, in bits (its digits: a `.coe` of 12-bit words writes
    /// `0A3`); 0 for radix 10.
    pub written_bits: u32,
}

/// `.coe`: `memory_initialization_radix = 2|10|16;` and `memory_initialization_vector =`
/// values separated by commas and/or white space, ending with `;` (`;` comments too). A
/// vector that runs to the end of the file without its `;` is read to the end.
pub fn parse_coe(text: &str) -> Result<Coe, (u32, String)> {
    let mut radix = None;
    let mut words = Vec::new();
    let mut in_vector = false;
    let mut written_bits = 0;
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
            written_bits = written_bits.max(match radix {
                2 => tok.len() as u32,
                16 => 4 * tok.len() as u32,
                _ => 0,
            });
        }
        if done {
            return Ok(Coe { words, unterminated: None, written_bits });
        }
    }
    if in_vector {
        Ok(Coe { words, unterminated: Some(text.lines().count() as u32), written_bits })
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
    use crate::frontend::scan::scan;

    fn nowhere(_: &str) -> Option<PathBuf> {
        None
    }

    #[test]
    fn coe_radixes_separators_comments_and_errors() {
        let words = |t: &str| parse_coe(t).map(|c| c.words);
        let coe = "; icons\nmemory_initialization_radix = 2;\nmemory_initialization_vector =\n01 10,\n11,\n00;\n";
        assert_eq!(words(coe).unwrap(), [1, 2, 3, 0]);
        assert_eq!(words("memory_initialization_radix=10;\nmemory_initialization_vector= 9, 12;").unwrap(), [9, 12]);
        // No `;` at the end: read to the end of the file, and said.
        let c = parse_coe("memory_initialization_radix=16;\nmemory_initialization_vector=\n1, 2\n").unwrap();
        assert_eq!((c.words, c.unterminated), (vec![1, 2], Some(3)));
        assert_eq!(
            parse_coe("memory_initialization_radix=8;\n").unwrap_err(),
            (1, "radix 8: expected 2, 10 or 16".to_string())
        );
        assert_eq!(parse_coe("memory_initialization_radix=2;\nmemory_initialization_vector=\n012;").unwrap_err().0, 3);
        assert_eq!(parse_mif("0101\n1111\n").unwrap(), [5, 15]);
        // The closing `;` alone on the last line.
        assert_eq!(
            words("memory_initialization_radix=16;\nmemory_initialization_vector=\n1,\n2\n;\n").unwrap(),
            [1, 2]
        );
    }

    fn xci(component: &str, values: &[(&str, &str)]) -> String {
        let mut s = format!(
            "<spirit:design xmlns:spirit=\"s\"><spirit:componentInstance><spirit:componentRef spirit:vendor=\"xilinx.com\" spirit:library=\"ip\" spirit:name=\"{component}\" spirit:version=\"8.3\"/><spirit:configurableElementValues>\n"
        );
        for (k, v) in values {
            s.push_str(&format!("<spirit:configurableElementValue spirit:referenceId=\"PARAM_VALUE.{k}\">{v}</spirit:configurableElementValue>\n"));
        }
        s + "</spirit:configurableElementValues></spirit:componentInstance></spirit:design>"
    }

    fn from_xci(path: &Path) -> Option<MemCore> {
        MemCore::from_config(&IpConfig::read(path).unwrap(), &nowhere).unwrap()
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
        let values = [
            ("Component_Name", "icon_rom"),
            ("Memory_Type", "Single_Port_ROM"),
            ("Read_Width_A", "2"),
            ("Write_Depth_A", "4096"),
            ("Register_PortA_Output_of_Memory_Primitives", "true"),
            ("Register_PortA_Output_of_Memory_Core", "false"),
            ("Enable_A", "Always_Enabled"),
            ("Coe_File", "../../icons.coe"),
        ];
        std::fs::write(&path, xci("blk_mem_gen", &values)).unwrap();
        let core = from_xci(&path).unwrap();
        let rom = PortCfg { enable: false, write: false, read: true, latency: 2, mode: WriteMode::WriteFirst };
        assert_eq!(core.kind, Kind::Block { a: rom, b: None });
        assert_eq!((core.width, core.depth, core.init.clone()), (2, 4096, vec![0, 3, 2]));
        let v = core.verilog();
        assert!(
            v.contains("module icon_rom (\n    input wire clka,\n    input wire [11:0] addra,\n    output wire [1:0] douta\n);"),
            "{v}"
        );
        assert!(v.contains("mem[1] = 2'h3;") && v.contains("assign douta = qa[1];"), "{v}");
        // The .coe named by a path from another machine: the .mif beside the .xci stands for it.
        std::fs::write(&path, xci("blk_mem_gen", &[values.as_slice(), &[("Coe_File", "C:/team/icons.coe")]].concat()))
            .unwrap();
        std::fs::write(dir.path().join("ip/icon_rom/icon_rom.mif"), "01\n10\n").unwrap();
        let core = from_xci(&path).unwrap();
        assert_eq!(core.init, [1, 2]);
        assert!(core.notes[0].contains("names C:/team/icons.coe, which is not here; using"), "{:?}", core.notes);
    }

    #[test]
    fn a_distributed_rom_and_what_is_not_a_memory() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("d.xci");
        std::fs::write(dir.path().join("c.coe"), "memory_initialization_radix=16;\nmemory_initialization_vector=5,6;")
            .unwrap();
        let values = [("Component_Name", "lut"), ("depth", "16"), ("data_width", "8"), ("coefficient_file", "c.coe")];
        std::fs::write(&path, xci("dist_mem_gen", &values)).unwrap();
        let core = from_xci(&path).unwrap();
        assert_eq!(core.kind, Kind::Distributed { registered: false, writable: false });
        assert!(core.verilog().contains("assign spo = mem[a];"));
        std::fs::write(&path, xci("clk_wiz", &[("Component_Name", "clk_wiz_0")])).unwrap();
        assert_eq!(from_xci(&path), None);
    }

    #[test]
    fn a_wrapper_of_the_library_model_gives_the_core_through_its_parameters() {
        // ISE's CORE Generator wrapper (and Vivado's simulation wrapper) instantiate Xilinx's
        // library model with the core's settings as C_* parameters.
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("frame.mif"), "0011\n0101\n").unwrap();
        let text = "module frame(clka, wea, addra, dina, clkb, addrb, doutb);\n\
            input clka; input [0:0] wea; input [9:0] addra; input [3:0] dina;\n\
            input clkb; input [9:0] addrb; output [3:0] doutb;\n\
            BLK_MEM_GEN_V7_3 #(.C_MEM_TYPE(1), .C_READ_WIDTH_A(4), .C_READ_DEPTH_A(1024), .C_HAS_ENA(0),\n\
              .C_LOAD_INIT_FILE(1), .C_INIT_FILE_NAME(\"frame.mif\"), .C_HAS_MEM_OUTPUT_REGS_B(1),\n\
              .C_WRITE_MODE_A(\"READ_FIRST\"))\n\
            inst (.CLKA(clka), .WEA(wea), .ADDRA(addra), .DINA(dina), .CLKB(clkb), .ADDRB(addrb), .DOUTB(doutb));\n\
            endmodule\n";
        let file = dir.path().join("frame.v");
        let m = &scan(text)[0];
        assert_eq!(library_model(&m.instances[0].module), Some("blk_mem_gen"));
        let core = MemCore::from_wrapper(m, &m.instances[0], &file, &nowhere).unwrap();
        assert_eq!((core.width, core.depth, core.init.clone()), (4, 1024, vec![3, 5]));
        let Kind::Block { a, b: Some(b) } = core.kind.clone() else { panic!("{:?}", core.kind) };
        assert_eq!((a.write, a.read, a.mode), (true, false, WriteMode::ReadFirst));
        assert_eq!((b.write, b.read, b.latency), (false, true, 2));
        let v = core.verilog();
        assert!(v.contains("module frame (\n    input wire clka,\n    input wire [0:0] wea,"), "{v}");
        assert!(v.contains("assign doutb = qb[1];") && v.contains("if ((|wea)) mem[addra] <= dina;"), "{v}");
        for not in ["dist_mem_gen", "blk_mem_gen_vx", "blk_mem_gen_0", "blk_mem_gen_v8_"] {
            assert_eq!(library_model(not), None, "{not}");
        }
        assert_eq!(library_model("dist_mem_gen_v8_0_10"), Some("dist_mem_gen"));
    }
}
