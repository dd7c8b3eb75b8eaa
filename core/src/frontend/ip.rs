//! Vendor IP configurations (spec board.md §6) and the clock cores built from them.
//!
//! A core's configuration is a set of named settings: Vivado's `.xci` (IP-XACT XML, one
//! `configurableElementValue` per setting, `PARAM_VALUE.X` and `MODELPARAM_VALUE.C_X`; or,
//! from Vivado 2020.2, the same in JSON) and ISE's CORE Generator `.xco` (`CSET x=value`
//! lines). [`IpConfig`] reads all three the same way; the memory cores ([`super::memcore`])
//! and the Clocking Wizard ([`ClockCore`]) are built from it, so the generated Verilog a
//! repository did not commit is never needed.
//!
//! ```
//! use botsim_core::frontend::ip::{ClockCore, IpConfig};
//! let xco = "SELECT Clocking_Wizard xilinx.com:ip:clk_wiz:3.6\nCSET component_name=pix25\n\
//!            CSET prim_in_freq=100.000\nCSET clkout1_requested_out_freq=25.000\nCSET use_locked=false\n";
//! let ip = IpConfig::parse(std::path::Path::new("pix25.xco"), xco).unwrap();
//! assert_eq!((ip.name.as_str(), ip.core.as_str()), ("pix25", "clk_wiz"));
//! let core = ClockCore::from_config(&ip).unwrap();
//! assert_eq!(core.outputs[0].port, "clk_out1");
//! assert_eq!(core.outputs[0].period_ps(), (40_000, 1));
//! ```

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::BoardError;

/// One IP core's configuration.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IpConfig {
    pub path: PathBuf,
    /// The component's name: the module a design instantiates.
    pub name: String,
    /// The core's kind (`clk_wiz`, `blk_mem_gen`, `dist_mem_gen`, ...).
    pub core: String,
    /// Settings by lower-case name: `PARAM_VALUE.Read_Width_A` is `read_width_a`,
    /// `MODELPARAM_VALUE.C_READ_WIDTH_A` is `c_read_width_a`.
    values: BTreeMap<String, String>,
}

impl IpConfig {
    /// Read an `.xci` or `.xco` file.
    pub fn read(path: &Path) -> Result<IpConfig, BoardError> {
        let bytes = std::fs::read(path).map_err(|e| BoardError::at(path, 0, 0, format!("cannot read: {e}")))?;
        let text = String::from_utf8_lossy(&bytes);
        IpConfig::parse(path, text.trim_start_matches('\u{feff}'))
    }

    /// Parse a configuration; `path`'s extension says which format it is.
    pub fn parse(path: &Path, text: &str) -> Result<IpConfig, BoardError> {
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let (name, core, values) = match ext.as_str() {
            "xco" => xco(text),
            _ if text.trim_start().starts_with('{') => json(path, text)?,
            _ => xml(path, text)?,
        };
        let name = name.or_else(|| values.get("component_name").cloned()).unwrap_or(stem);
        let core = core.ok_or_else(|| BoardError::at(path, 0, 0, "an IP configuration that names no core"))?;
        Ok(IpConfig { path: path.to_path_buf(), name, core, values })
    }

    /// A setting, by its name in any case (`Read_Width_A`, `C_READ_WIDTH_A`).
    pub fn get(&self, key: &str) -> Option<&str> {
        self.values.get(&key.to_ascii_lowercase()).map(String::as_str).map(str::trim)
    }

    /// The first of several names that is set.
    pub fn any(&self, keys: &[&str]) -> Option<&str> {
        keys.iter().find_map(|k| self.get(k))
    }

    /// A boolean setting (`true`/`false`, `1`/`0`).
    pub fn flag(&self, key: &str) -> Option<bool> {
        self.get(key).map(|v| v.eq_ignore_ascii_case("true") || v == "1")
    }

    /// A numeric setting.
    pub fn number(&self, key: &str) -> Option<f64> {
        self.get(key).and_then(|v| v.parse().ok())
    }

    /// A file a setting names, relative to the configuration's folder; `None` when unset
    /// (or `no_coe_file_loaded`).
    pub fn file(&self, key: &str) -> Option<PathBuf> {
        let v = self.get(key).filter(|v| !v.is_empty() && !v.eq_ignore_ascii_case("no_coe_file_loaded"))?;
        let v = v.replace('\\', "/");
        let p = Path::new(&v);
        Some(if p.is_absolute() || super::project::is_drive_path(&v) {
            p.to_path_buf()
        } else {
            super::repo::tidy(&self.path.parent().unwrap_or(Path::new(".")).join(p))
        })
    }
}

type Parsed = (Option<String>, Option<String>, BTreeMap<String, String>);

/// The setting's name without its `PARAM_VALUE.`/`MODELPARAM_VALUE.` prefix, lower case.
fn key_of(id: &str) -> Option<(String, bool)> {
    if let Some(k) = id.strip_prefix("PARAM_VALUE.") {
        Some((k.to_ascii_lowercase(), true))
    } else {
        id.strip_prefix("MODELPARAM_VALUE.").map(|k| (k.to_ascii_lowercase(), false))
    }
}

fn xml(path: &Path, text: &str) -> Result<Parsed, BoardError> {
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let pos = e.pos();
        BoardError::at(path, pos.row, pos.col, format!("not a well-formed IP file: {e}"))
    })?;
    let mut name = None;
    let mut core = None;
    let mut values = BTreeMap::new();
    let attr = |n: roxmltree::Node, a: &str| n.attributes().find(|x| x.name() == a).map(|x| x.value().to_string());
    for n in doc.descendants().filter(|n| n.is_element()) {
        match n.tag_name().name() {
            "instanceName" if name.is_none() => name = n.text().map(|t| t.trim().to_string()),
            "componentRef" if core.is_none() => core = attr(n, "name"),
            "configurableElementValue" => {
                let Some((key, param)) = attr(n, "referenceId").as_deref().and_then(key_of) else { continue };
                let v = n.text().unwrap_or("").trim().to_string();
                // PARAM_VALUE (what the user set) over MODELPARAM_VALUE (what Vivado derived).
                if param || !values.contains_key(&key) {
                    values.insert(key, v);
                }
            }
            _ => {}
        }
    }
    Ok((name, core, values))
}

/// Vivado 2020.2+ `.xci`: `ip_inst.xci_name`, `component_reference` (`vendor:lib:core:ver`),
/// `parameters.component_parameters.X[0].value` and `model_parameters.C_X[0].value`.
fn json(path: &Path, text: &str) -> Result<Parsed, BoardError> {
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| {
        BoardError::at(path, e.line() as u32, e.column() as u32, format!("not a well-formed IP file: {e}"))
    })?;
    let inst = &v["ip_inst"];
    let name = inst["xci_name"].as_str().map(str::to_string);
    let core = inst["component_reference"].as_str().and_then(|r| r.split(':').nth(2)).map(str::to_string);
    let mut values = BTreeMap::new();
    for (group, param) in [("model_parameters", false), ("component_parameters", true)] {
        if let Some(map) = inst["parameters"][group].as_object() {
            for (k, entry) in map {
                let value = entry.get(0).and_then(|e| e.get("value")).or(Some(entry)).and_then(|x| x.as_str());
                if let Some(value) = value {
                    let key = k.to_ascii_lowercase();
                    if param || !values.contains_key(&key) {
                        values.insert(key, value.to_string());
                    }
                }
            }
        }
    }
    Ok((name, core, values))
}

/// ISE `.xco`: `SELECT <title> <vendor>:ip:<core>:<version>` and `CSET key=value` lines.
fn xco(text: &str) -> Parsed {
    let mut core = None;
    let mut values = BTreeMap::new();
    for line in text.lines().map(str::trim) {
        let mut words = line.splitn(2, char::is_whitespace);
        match (words.next().map(str::to_ascii_uppercase).as_deref(), words.next()) {
            (Some("SELECT"), Some(rest)) => {
                core = rest.split_whitespace().last().and_then(|vlnv| vlnv.split(':').nth(2)).map(str::to_string);
            }
            (Some("CSET"), Some(rest)) => {
                if let Some((k, v)) = rest.split_once('=') {
                    values.insert(k.trim().to_ascii_lowercase(), v.trim().to_string());
                }
            }
            _ => {}
        }
    }
    (None, core, values)
}

/// The Clocking Wizard's kinds of clock core.
pub const CLOCK_CORES: &[&str] = &["clk_wiz"];

/// One output of a clock core.
#[derive(Clone, Debug, PartialEq)]
pub struct ClockOutput {
    pub port: String,
    /// The frequency in Hz (as configured, or from the primitive's settings).
    pub hz: f64,
    pub phase_deg: f64,
    pub duty: f64,
    /// The primitive's output divide (`CLKOUTn_DIVIDE`), when the core sets the primitive.
    pub divide: Option<f64>,
}

impl ClockOutput {
    /// The period in picoseconds as a fraction (numerator, denominator), exact for a
    /// frequency given to the hertz.
    pub fn period_ps(&self) -> (u64, u64) {
        let hz = self.hz.round().max(1.0) as u64;
        let (n, d) = (1_000_000_000_000u64, hz);
        let g = gcd(n, d);
        (n / g, d / g)
    }
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// The primitive a clock core sets, with its multiply and divide, when its configuration
/// has them (Vivado's `MMCM_*`/`PLL_*` settings): the outputs then are exactly the
/// hardware's.
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    /// `MMCME2_ADV` or `PLLE2_ADV`.
    pub name: &'static str,
    pub clkin_period_ns: f64,
    pub mult: f64,
    pub divclk: u32,
}

/// A clock core: a Clocking Wizard from its configuration, or a clock module described on
/// the command line (`--clock`).
#[derive(Clone, Debug, PartialEq)]
pub struct ClockCore {
    pub name: String,
    pub input: String,
    pub input_hz: f64,
    pub outputs: Vec<ClockOutput>,
    /// The reset input and whether it is active low.
    pub reset: Option<(String, bool)>,
    pub locked: Option<String>,
    pub primitive: Option<Primitive>,
    /// Other inputs the design connects (tied to nothing inside).
    pub other_inputs: Vec<String>,
    /// Where it comes from, for the generated file's header.
    pub origin: String,
}

impl ClockCore {
    /// A Clocking Wizard from its `.xci`/`.xco`.
    pub fn from_config(ip: &IpConfig) -> Result<ClockCore, BoardError> {
        let err = |m: String| BoardError::at(&ip.path, 0, 0, m);
        let input_hz = ip.number("prim_in_freq").unwrap_or(100.0) * 1e6;
        let input = ip.any(&["primary_port", "clk_in1_port"]).unwrap_or("clk_in1").to_string();
        let prim_name = ip.any(&["primitive", "primtype_sel"]).unwrap_or("MMCM").to_ascii_uppercase();
        let pll = prim_name.starts_with("PLL");
        let (p, k) = if pll { ("pll_", "") } else { ("mmcm_", "_f") };
        let mult = ip.number(&format!("{p}clkfbout_mult{k}"));
        let divclk = ip.number(&format!("{p}divclk_divide"));
        let period = ip.number(&format!("{p}clkin1_period")).or_else(|| ip.number(&format!("{p}clkin_period")));
        let primitive = match (mult, divclk, period) {
            (Some(mult), Some(divclk), Some(clkin_period_ns)) if mult > 0.0 && divclk >= 1.0 => Some(Primitive {
                name: if pll { "PLLE2_ADV" } else { "MMCME2_ADV" },
                clkin_period_ns,
                mult,
                divclk: divclk as u32,
            }),
            _ => None,
        };
        let mut outputs = Vec::new();
        for n in 1..=7u32 {
            let used = ip.flag(&format!("clkout{n}_used")).unwrap_or(n == 1);
            if !used {
                continue;
            }
            let port = ip.get(&format!("clk_out{n}_port")).unwrap_or(&format!("clk_out{n}")).to_string();
            let requested = ip.number(&format!("clkout{n}_requested_out_freq"));
            let divide = match n {
                1 if !pll => ip.number("mmcm_clkout0_divide_f"),
                _ => ip.number(&format!("{p}clkout{}_divide", n - 1)),
            };
            let phase_deg = ip
                .number(&format!("{p}clkout{}_phase", n - 1))
                .or_else(|| ip.number(&format!("clkout{n}_requested_phase")))
                .unwrap_or(0.0);
            let duty = ip
                .number(&format!("{p}clkout{}_duty_cycle", n - 1))
                .or_else(|| ip.number(&format!("clkout{n}_requested_duty_cycle")).map(|d| d / 100.0))
                .unwrap_or(0.5);
            let hz = match (&primitive, divide) {
                (Some(pr), Some(d)) if d > 0.0 => 1e12 / (pr.clkin_period_ns * 1000.0) * pr.mult / pr.divclk as f64 / d,
                _ => requested
                    .map(|f| f * 1e6)
                    .ok_or_else(|| err(format!("clk_out{n} has no frequency (CLKOUT{n}_REQUESTED_OUT_FREQ)")))?,
            };
            outputs.push(ClockOutput { port, hz, phase_deg, duty, divide: divide.filter(|_| primitive.is_some()) });
        }
        if outputs.is_empty() {
            return Err(err("the clock core has no output in use".into()));
        }
        let reset = ip.flag("use_reset").unwrap_or(true).then(|| {
            let port = ip.get("reset_port").unwrap_or("reset").to_string();
            let low = ip.get("reset_type").is_some_and(|t| t.eq_ignore_ascii_case("ACTIVE_LOW"));
            (port, low)
        });
        let locked =
            ip.flag("use_locked").unwrap_or(true).then(|| ip.get("locked_port").unwrap_or("locked").to_string());
        Ok(ClockCore {
            name: ip.name.clone(),
            input,
            input_hz,
            outputs,
            reset,
            locked,
            primitive,
            other_inputs: Vec::new(),
            origin: ip.path.display().to_string(),
        })
    }

    /// What the core makes, in one line: `100 MHz in; clk_out1 25 MHz, clk_out2 75 MHz`.
    pub fn summary(&self) -> String {
        let outs: Vec<String> = self.outputs.iter().map(|o| format!("{} {}", o.port, mhz(o.hz))).collect();
        format!("{} in; {}", mhz(self.input_hz), outs.join(", "))
    }

    /// The core as Verilog: the primitive with the core's settings (as the Clocking Wizard
    /// generates it: the input clock into an MMCM or PLL, the feedback output back to its
    /// input), or, without them, one generated clock per output at its frequency that runs
    /// once the input has locked, as the primitive's outputs do.
    pub fn verilog(&self) -> String {
        let mut ports = vec![format!("input wire {}", self.input)];
        if let Some((r, _)) = &self.reset {
            ports.push(format!("input wire {r}"));
        }
        for i in &self.other_inputs {
            ports.push(format!("input wire {i}"));
        }
        for o in &self.outputs {
            ports.push(format!("output wire {}", o.port));
        }
        if let Some(l) = &self.locked {
            ports.push(format!("output wire {l}"));
        }
        let rst = match &self.reset {
            Some((r, true)) => format!("~{r}"),
            Some((r, false)) => r.clone(),
            None => "1'b0".into(),
        };
        let mut body = String::new();
        let locked = self.locked.clone().unwrap_or_else(|| "botsim_locked".into());
        if self.locked.is_none() {
            body.push_str("    wire botsim_locked;\n");
        }
        match &self.primitive {
            Some(p) => {
                let mut params = vec![
                    format!(".CLKIN1_PERIOD({})", real(p.clkin_period_ns)),
                    format!(".DIVCLK_DIVIDE({})", p.divclk),
                ];
                let pll = p.name.starts_with("PLL");
                params.push(if pll {
                    format!(".CLKFBOUT_MULT({})", p.mult.round() as u32)
                } else {
                    format!(".CLKFBOUT_MULT_F({})", real(p.mult))
                });
                let mut conns = vec![
                    format!(".CLKIN1({})", self.input),
                    ".CLKIN2(1'b0)".to_string(),
                    ".CLKINSEL(1'b1)".to_string(),
                    ".CLKFBIN(botsim_clkfb)".to_string(),
                    ".CLKFBOUT(botsim_clkfb)".to_string(),
                    format!(".RST({rst})"),
                    ".PWRDWN(1'b0)".to_string(),
                    format!(".LOCKED({locked})"),
                ];
                for (k, o) in self.outputs.iter().enumerate() {
                    let d = o.divide.unwrap_or(1.0);
                    params.push(if k == 0 && !pll {
                        format!(".CLKOUT0_DIVIDE_F({})", real(d))
                    } else {
                        format!(".CLKOUT{k}_DIVIDE({})", d.round() as u32)
                    });
                    params.push(format!(".CLKOUT{k}_PHASE({})", real(o.phase_deg)));
                    params.push(format!(".CLKOUT{k}_DUTY_CYCLE({})", real(o.duty)));
                    conns.push(format!(".CLKOUT{k}({})", o.port));
                }
                let _ = write!(
                    body,
                    "    wire botsim_clkfb;\n    {} #(\n        {}\n    ) botsim_prim (\n        {}\n    );\n",
                    p.name,
                    params.join(",\n        "),
                    conns.join(",\n        ")
                );
            }
            None => {
                let _ = writeln!(
                    body,
                    "    botsim_lock botsim_lock (.clk({}), .rst({rst}), .locked({locked}));",
                    self.input
                );
                for o in &self.outputs {
                    let (num, den) = o.period_ps();
                    let _ = writeln!(
                        body,
                        "    botsim_clkgen #(.PERIOD_NUM({num}), .PERIOD_DEN({den}), .PHASE_MDEG({}), .DUTY_PERMILLE({})) botsim_{p} (.run({locked}), .clk({p}));",
                        (o.phase_deg * 1000.0).round() as i64,
                        (o.duty * 1000.0).round() as i64,
                        p = o.port
                    );
                }
            }
        }
        format!(
            "// Generated by botsim board: the clock core `{name}` ({summary}), from {origin}.\n\
             `timescale 1ns / 1ps\n\
             module {name} (\n    {ports}\n);\n{body}endmodule\n",
            name = self.name,
            summary = self.summary(),
            origin = self.origin,
            ports = ports.join(",\n    "),
        )
    }
}

/// A real parameter value as Verilog writes it (always with a decimal point).
fn real(v: f64) -> String {
    let s = format!("{v}");
    if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.0")
    }
}

/// A frequency as people write it.
pub fn mhz(hz: f64) -> String {
    let m = hz / 1e6;
    if (m - m.round()).abs() < 1e-9 {
        format!("{} MHz", m.round())
    } else {
        format!("{:.3} MHz", m)
    }
}

/// `--clock MODULE.PORT=FREQ`: an output of a clock module the design has no configuration
/// for.
#[derive(Clone, Debug, PartialEq)]
pub struct ClockSpec {
    /// The module (or instance) name.
    pub target: String,
    pub port: String,
    pub hz: f64,
}

impl ClockSpec {
    /// Parse `clk_wiz_0.clk_out1=25MHz` (also `25 MHz`, `65.5MHz`, `25000kHz`, `25e6`).
    pub fn parse(s: &str) -> Result<ClockSpec, String> {
        let bad = || format!("--clock {s}: expected MODULE.PORT=FREQUENCY (e.g. clk_wiz_0.clk_out1=25MHz)");
        let (lhs, freq) = s.split_once('=').ok_or_else(bad)?;
        let (target, port) = lhs.trim().rsplit_once('.').ok_or_else(bad)?;
        if target.is_empty() || port.is_empty() {
            return Err(bad());
        }
        let hz = parse_frequency(freq.trim()).ok_or_else(bad)?;
        Ok(ClockSpec { target: target.to_string(), port: port.to_string(), hz })
    }
}

/// A frequency in Hz from `25MHz`, `25 MHz`, `25000kHz`, `25e6`, `25000000Hz`.
pub fn parse_frequency(s: &str) -> Option<f64> {
    let lower = s.to_ascii_lowercase().replace(' ', "");
    let (num, scale) = if let Some(n) = lower.strip_suffix("ghz") {
        (n, 1e9)
    } else if let Some(n) = lower.strip_suffix("mhz") {
        (n, 1e6)
    } else if let Some(n) = lower.strip_suffix("khz") {
        (n, 1e3)
    } else if let Some(n) = lower.strip_suffix("hz") {
        (n, 1.0)
    } else {
        (lower.as_str(), 1.0)
    };
    let v: f64 = num.parse().ok()?;
    (v.is_finite() && v > 0.0 && v * scale <= 2e9).then_some(v * scale)
}

impl ClockCore {
    /// A clock module described by `--clock` options, with the ports its instance connects:
    /// the named outputs at their frequencies; a port named like `locked` is its lock output;
    /// one named like `reset`/`rst` its reset (active low when it ends in `n`); the first
    /// other port its input clock.
    pub fn from_specs(name: &str, specs: &[&ClockSpec], connected: &[String]) -> ClockCore {
        let is = |p: &str, words: &[&str]| words.iter().any(|w| p.to_ascii_lowercase().contains(w));
        let outputs: Vec<ClockOutput> = specs
            .iter()
            .map(|s| ClockOutput { port: s.port.clone(), hz: s.hz, phase_deg: 0.0, duty: 0.5, divide: None })
            .collect();
        let rest: Vec<&String> =
            connected.iter().filter(|p| !p.starts_with('#') && !specs.iter().any(|s| &s.port == *p)).collect();
        let locked = rest.iter().find(|p| is(p, &["locked"])).map(|p| p.to_string());
        let reset = rest.iter().find(|p| is(p, &["reset", "rst"])).map(|p| {
            let l = p.to_ascii_lowercase();
            (p.to_string(), l.ends_with('n') || l.ends_with("_b"))
        });
        let others: Vec<String> = rest
            .iter()
            .filter(|p| {
                Some(p.as_str()) != locked.as_deref() && Some(p.as_str()) != reset.as_ref().map(|r| r.0.as_str())
            })
            .map(|p| p.to_string())
            .collect();
        let input = others
            .iter()
            .find(|p| is(p, &["clk", "clock"]))
            .or(others.first())
            .cloned()
            .unwrap_or_else(|| "clk_in1".into());
        ClockCore {
            name: name.to_string(),
            other_inputs: others.into_iter().filter(|p| *p != input).collect(),
            input,
            input_hz: 100e6,
            outputs,
            reset,
            locked,
            primitive: None,
            origin: "--clock".into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xci(values: &[(&str, &str)]) -> String {
        let mut s = String::from(
            "<?xml version=\"1.0\"?>\n<spirit:design xmlns:spirit=\"http://www.spiritconsortium.org/XMLSchema/SPIRIT/1685-2009\">\
             <spirit:componentInstances><spirit:componentInstance><spirit:instanceName>clk_wiz_0</spirit:instanceName>\
             <spirit:componentRef spirit:vendor=\"xilinx.com\" spirit:library=\"ip\" spirit:name=\"clk_wiz\" spirit:version=\"5.1\"/>\
             <spirit:configurableElementValues>\n",
        );
        for (k, v) in values {
            s.push_str(&format!(
                "<spirit:configurableElementValue spirit:referenceId=\"{k}\">{v}</spirit:configurableElementValue>\n"
            ));
        }
        s + "</spirit:configurableElementValues></spirit:componentInstance></spirit:componentInstances></spirit:design>"
    }

    #[test]
    fn a_clocking_wizard_from_its_xci_is_the_mmcm_with_its_computed_settings() {
        // board.md §6: 100 MHz x 9.75 / 13 = 75 MHz.
        let text = xci(&[
            ("PARAM_VALUE.PRIM_IN_FREQ", "100.000"),
            ("PARAM_VALUE.CLK_OUT1_PORT", "sysclk"),
            ("PARAM_VALUE.CLKOUT1_REQUESTED_OUT_FREQ", "75.000"),
            ("PARAM_VALUE.CLKOUT2_USED", "true"),
            ("PARAM_VALUE.CLKOUT2_REQUESTED_OUT_FREQ", "25.000"),
            ("PARAM_VALUE.USE_LOCKED", "true"),
            ("PARAM_VALUE.USE_RESET", "true"),
            ("PARAM_VALUE.RESET_TYPE", "ACTIVE_LOW"),
            ("PARAM_VALUE.RESET_PORT", "resetn"),
            ("PARAM_VALUE.PRIMITIVE", "MMCM"),
            ("PARAM_VALUE.MMCM_CLKFBOUT_MULT_F", "9.750"),
            ("PARAM_VALUE.MMCM_DIVCLK_DIVIDE", "1"),
            ("PARAM_VALUE.MMCM_CLKIN1_PERIOD", "10.0"),
            ("PARAM_VALUE.MMCM_CLKOUT0_DIVIDE_F", "13.000"),
            ("PARAM_VALUE.MMCM_CLKOUT1_DIVIDE", "39"),
            ("MODELPARAM_VALUE.C_CLKOUT2_USED", "1"),
        ]);
        let ip = IpConfig::parse(Path::new("ip/clk_wiz_0/clk_wiz_0.xci"), &text).unwrap();
        let core = ClockCore::from_config(&ip).unwrap();
        assert_eq!(core.summary(), "100 MHz in; sysclk 75 MHz, clk_out2 25 MHz");
        assert_eq!(core.reset, Some(("resetn".to_string(), true)));
        let v = core.verilog();
        assert!(v.contains("module clk_wiz_0 (\n    input wire clk_in1,\n    input wire resetn,\n    output wire sysclk,\n    output wire clk_out2,\n    output wire locked\n);"), "{v}");
        for want in [
            ".CLKFBOUT_MULT_F(9.75)",
            ".CLKOUT0_DIVIDE_F(13.0)",
            ".CLKOUT1_DIVIDE(39)",
            ".RST(~resetn)",
            ".CLKOUT0(sysclk)",
        ] {
            assert!(v.contains(want), "{want} in {v}");
        }
        assert!(v.contains("MMCME2_ADV #("), "{v}");
    }

    #[test]
    fn without_the_primitives_settings_each_output_is_a_clock_at_its_requested_frequency() {
        let ip = IpConfig::parse(
            Path::new("x.xci"),
            &xci(&[("PARAM_VALUE.CLKOUT1_REQUESTED_OUT_FREQ", "65.000"), ("PARAM_VALUE.USE_RESET", "false")]),
        )
        .unwrap();
        let core = ClockCore::from_config(&ip).unwrap();
        assert_eq!(core.outputs[0].period_ps(), (200_000, 13)); // 1e12 / 65e6 = 15384.615... ps
        let v = core.verilog();
        assert!(v.contains("botsim_clkgen #(.PERIOD_NUM(200000), .PERIOD_DEN(13)"), "{v}");
        assert!(v.contains(".rst(1'b0), .locked(locked)"), "{v}");
    }

    #[test]
    fn vivado_2020_json_and_ise_xco_read_as_the_xml() {
        let json = r#"{"schema": "xilinx.com:schema:json_instance:1.0", "ip_inst": {"xci_name": "pix",
            "component_reference": "xilinx.com:ip:clk_wiz:6.0",
            "parameters": {"component_parameters": {"CLKOUT1_REQUESTED_OUT_FREQ": [{"value": "25.000"}]},
                           "model_parameters": {"C_CLKOUT1_REQUESTED_OUT_FREQ": [{"value": "25.0"}]}}}}"#;
        let ip = IpConfig::parse(Path::new("pix.xci"), json).unwrap();
        assert_eq!(
            (ip.name.as_str(), ip.core.as_str(), ip.get("CLKOUT1_REQUESTED_OUT_FREQ")),
            ("pix", "clk_wiz", Some("25.000"))
        );
        let xco = "# comment\nSELECT Block_Memory_Generator xilinx.com:ip:blk_mem_gen:7.3\nCSET component_name=icons\nCSET coe_file=C:\\x\\icons.coe\n";
        let ip = IpConfig::parse(Path::new("ipcore_dir/icons.xco"), xco).unwrap();
        assert_eq!((ip.name.as_str(), ip.core.as_str()), ("icons", "blk_mem_gen"));
        assert_eq!(ip.file("Coe_File"), Some(PathBuf::from("C:/x/icons.coe")));
        let e = IpConfig::parse(Path::new("a.xci"), "<spirit:design").unwrap_err().to_string();
        assert!(e.starts_with("a.xci:1:"), "{e}");
    }

    #[test]
    fn clock_specs_and_the_module_they_describe() {
        let s = ClockSpec::parse("clk_wiz_0.clk_out1=25MHz").unwrap();
        assert_eq!((s.target.as_str(), s.port.as_str(), s.hz), ("clk_wiz_0", "clk_out1", 25e6));
        assert_eq!(parse_frequency("65.5 MHz"), Some(65.5e6));
        assert_eq!(parse_frequency("25000kHz"), Some(25e6));
        assert!(ClockSpec::parse("clk_out1=25MHz").is_err());
        assert!(ClockSpec::parse("a.b=fast").is_err());
        let ports: Vec<String> = ["clk_in1", "reset", "clk_out1", "locked"].map(String::from).to_vec();
        let core = ClockCore::from_specs("clk_wiz_0", &[&s], &ports);
        assert_eq!(core.input, "clk_in1");
        assert_eq!(core.reset, Some(("reset".into(), false)));
        assert_eq!(core.locked.as_deref(), Some("locked"));
        assert!(core.verilog().contains("botsim_clkgen #(.PERIOD_NUM(40000), .PERIOD_DEN(1)"));
    }
}
