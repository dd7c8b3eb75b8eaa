//! Nets with several drivers: two instances' outputs on one wire (a game's two bots whose
//! `LMDist_reg` outputs drive the same net), or an output and an `assign`. Vivado refuses the
//! design (DRC MDRV-1, Multiple Driver Nets); Verilog resolves such a wire bit by bit: the
//! value its drivers agree on, x where they differ. A 2-state simulator has no x, and
//! Verilator shows whichever driver it evaluated last, which differs with what stands for a
//! driver (the bot's RTL or its model). botsim makes the resolution explicit, the same on
//! every board: each driver drives a wire of its own, and the net is their AND, the value
//! the drivers agree on and 0 where they differ.
//!
//! ```
//! use botsim_core::frontend::drivers::{rewrite, shared_nets};
//! use botsim_core::frontend::scan::{scan, Dir};
//! let text = "module top(output [7:0] led);\n  wire [7:0] d;\n  src a (.q(d));\n  src b (.q(d));\n  assign led = d;\nendmodule\n";
//! let m = &scan(text)[0];
//! let dir = |module: &str, port: &str| (module == "src" && port == "q").then_some(Dir::Output);
//! let shared = shared_nets(m, &dir);
//! assert_eq!(shared.len(), 1);
//! assert_eq!(shared[0].net, "d");
//! assert_eq!(shared[0].drivers.iter().map(|d| d.what.as_str()).collect::<Vec<_>>(), ["output `q` of `a`", "output `q` of `b`"]);
//! let mut out = text.to_string();
//! for (at, with) in rewrite(m, &shared).into_iter().rev() {
//!     out.replace_range(at, &with);
//! }
//! assert!(out.contains("src a (.q(d__botsim_driver0));"), "{out}");
//! assert!(out.contains("wire [7:0] d; wire [7:0] d__botsim_driver0, d__botsim_driver1; assign d = d__botsim_driver0 & d__botsim_driver1;"), "{out}");
//! ```

use std::collections::BTreeMap;
use std::ops::Range;

use super::scan::{Dir, Module};

/// A net of a module with more than one driver.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SharedNet {
    pub net: String,
    pub drivers: Vec<Driver>,
}

/// One driver of a shared net.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Driver {
    /// `output `LMDist_reg` of `bot31_74``, or `an assign`.
    pub what: String,
    /// The bytes where the driver names the net in the source.
    pub at: Range<usize>,
}

/// The suffix of the wire each driver of a shared net drives instead (`lmdist__botsim_driver0`).
pub const DRIVER_SUFFIX: &str = "__botsim_driver";

/// The nets of `m` driven by more than one instance output or continuous assignment, each
/// output known by `dir(module, port)`. A net with a tri-state driver (`1'bz`) is not one:
/// Verilog resolves it as the design means.
pub fn shared_nets(m: &Module, dir: &dyn Fn(&str, &str) -> Option<Dir>) -> Vec<SharedNet> {
    let mut by_net: BTreeMap<&str, Vec<Driver>> = BTreeMap::new();
    let mut tristate: Vec<&str> = Vec::new();
    // Items of generate branches are alternatives, not drivers side by side.
    for inst in m.instances.iter().filter(|i| !i.guarded) {
        for ((port, expr), at) in inst.connections.iter().zip(&inst.spans) {
            if port.starts_with('#') || !is_name(expr) || dir(&inst.module, port) != Some(Dir::Output) {
                continue;
            }
            by_net
                .entry(expr.as_str())
                .or_default()
                .push(Driver { what: format!("output `{port}` of `{}`", inst.name), at: at.clone() });
        }
    }
    for a in &m.assigns {
        if a.tristate {
            tristate.push(&a.target);
        }
        by_net.entry(a.target.as_str()).or_default().push(Driver { what: "an assign".into(), at: a.at.clone() });
    }
    by_net
        .into_iter()
        .filter(|(net, d)| d.len() > 1 && !tristate.contains(net))
        .map(|(net, mut drivers)| {
            drivers.sort_by_key(|d| d.at.start);
            SharedNet { net: net.to_string(), drivers }
        })
        .collect()
}

/// A plain name: no select, no concatenation, no constant.
fn is_name(e: &str) -> bool {
    let mut c = e.chars();
    c.next().is_some_and(|f| f.is_ascii_alphabetic() || f == '_')
        && c.all(|x| x.is_ascii_alphanumeric() || x == '_' || x == '$')
}

/// The edits that give each driver of each shared net of `m` a wire of its own and the net
/// their AND, in the order of the text: (bytes, new text). Every edit stays on its line, so
/// messages still point at the user's lines. The wires are declared right after the net's
/// declaration (after the module's header for a port, or for a net the module does not
/// declare: an implicit one, one bit), of its range.
pub fn rewrite(m: &Module, shared: &[SharedNet]) -> Vec<(Range<usize>, String)> {
    let mut edits = Vec::new();
    for s in shared {
        let (after, range) = match (m.nets.iter().find(|n| n.name == s.net), m.port(&s.net)) {
            (Some(n), _) => (n.end, n.range.clone()),
            (None, Some(p)) => (m.header_end, p.range.map(|(a, b)| format!("[{a}:{b}]"))),
            (None, None) => (m.header_end, None),
        };
        let wire = |k: usize| format!("{}{DRIVER_SUFFIX}{k}", s.net);
        for (k, d) in s.drivers.iter().enumerate() {
            edits.push((d.at.clone(), wire(k)));
        }
        let wires: Vec<String> = (0..s.drivers.len()).map(wire).collect();
        let range = range.map(|r| format!("{r} ")).unwrap_or_default();
        edits.push((
            after..after,
            format!(" wire {range}{}; assign {} = {};", wires.join(", "), s.net, wires.join(" & ")),
        ));
    }
    edits.sort_by_key(|(at, _)| at.start);
    edits
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend::scan::scan;

    fn dir(module: &str, port: &str) -> Option<Dir> {
        match (module, port) {
            ("bot", "LMDist_reg" | "upd") | ("bot31", "LMDist_reg") => Some(Dir::Output),
            (_, "clk") => Some(Dir::Input),
            _ => None,
        }
    }

    fn edited(text: &str) -> String {
        let m = &scan(text)[0];
        let shared = shared_nets(m, &dir);
        let mut out = text.to_string();
        for (at, with) in rewrite(m, &shared).into_iter().rev() {
            out.replace_range(at, &with);
        }
        out
    }

    #[test]
    fn two_outputs_an_output_and_an_assign_and_a_port() {
        let text = "module g(input clk, output [7:0] score);\n  wire [7:0] lm; wire u;\n  bot (.clk(clk), .LMDist_reg(lm), .upd(u));\n  bot31 m (.clk(clk), .LMDist_reg(lm));\n  assign u = 1'b1;\n  bot31 s (.LMDist_reg(score));\n  assign score = 8'd3;\nendmodule\n";
        let m = &scan(text)[0];
        let shared = shared_nets(m, &dir);
        let nets: Vec<(&str, usize)> = shared.iter().map(|s| (s.net.as_str(), s.drivers.len())).collect();
        assert_eq!(nets, [("lm", 2), ("score", 2), ("u", 2)]);
        assert_eq!(shared[2].drivers[1].what, "an assign");
        assert_eq!(&text[shared[2].drivers[1].at.clone()], "u");
        let out = edited(text);
        assert_eq!(out.lines().count(), text.lines().count(), "{out}");
        assert!(out.contains("bot31 m (.clk(clk), .LMDist_reg(lm__botsim_driver1));"), "{out}");
        assert!(out.contains("assign u__botsim_driver1 = 1'b1;"), "{out}");
        assert!(out.contains("module g(input clk, output [7:0] score); wire [7:0] score__botsim_driver0, score__botsim_driver1; assign score = score__botsim_driver0 & score__botsim_driver1;\n"), "{out}");
        assert!(
            out.contains(
                "wire u; wire u__botsim_driver0, u__botsim_driver1; assign u = u__botsim_driver0 & u__botsim_driver1;"
            ),
            "{out}"
        );
    }

    #[test]
    fn an_implicit_net_is_declared_as_one_bit_after_the_header() {
        let out = edited("module g(input clk);\n  bot x (.upd(a));\n  bot y (.upd(a));\nendmodule\n");
        assert!(out.starts_with("module g(input clk); wire a__botsim_driver0, a__botsim_driver1; assign a = a__botsim_driver0 & a__botsim_driver1;\n"), "{out}");
        assert!(out.contains("bot y (.upd(a__botsim_driver1));"), "{out}");
    }

    #[test]
    fn one_driver_a_select_an_input_and_a_tristate_are_no_shared_net() {
        for text in [
            "module g(input clk); wire [7:0] a; bot x (.LMDist_reg(a)); assign b = a; endmodule",
            "module g(input clk); wire [7:0] a; bot x (.LMDist_reg(a[3:0])); bot31 y (.LMDist_reg(a[7:4])); endmodule",
            "module g(input clk); bot x (.clk(clk)); bot31 y (.clk(clk)); endmodule",
            "module g(input clk); wire [7:0] a; bot x (.LMDist_reg(a)); assign a = en ? 8'd1 : 8'bz; endmodule",
            "module g(input clk); wire [7:0] a; bot x (.LMDist_reg(a)); assign a = en ? 8'd1 : 8'hZZ; endmodule",
            // Generate branches: one of them is built.
            "module g #(parameter P = 0) (input clk); wire [7:0] a; if (P) assign a = 8'd1; else assign a = 8'd2; endmodule",
            "module g #(parameter P = 0) (input clk); wire [7:0] a; generate if (P) begin : one bot x (.LMDist_reg(a)); end else begin : two bot31 y (.LMDist_reg(a)); end endgenerate endmodule",
            "module g #(parameter P = 0) (input clk); wire [7:0] a; generate case (P) 0: assign a = 8'd1; default: assign a = 8'd2; endcase endgenerate endmodule",
        ] {
            assert!(shared_nets(&scan(text)[0], &dir).is_empty(), "{text}");
        }
    }
}
