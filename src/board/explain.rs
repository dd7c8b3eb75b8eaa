//! Verilator's errors in botsim's words. A design is never built as the user wrote it alone:
//! botsim adds its board, its models and the modules it stands in for, and edits what Vivado
//! accepts and Verilator does not. Whatever Verilator then reports reaches the user as one
//! line of botsim's: the user's file:line, what is wrong in their terms and what to do; and
//! where the Verilog botsim wrote is at fault, that botsim is, and how to report it.
//!
//! ```
//! use botsim::board::explain::{explain, File, Origin};
//! let files = [File {
//!     given: "/src/top.v".into(),
//!     shown: "top.v".into(),
//!     origin: Origin::User,
//!     text: "module top(input clk);\n  sub s (.clk(clk), .nope(1'b0));\nendmodule\n\
//!            module sub(input clk);\nendmodule\n".into(),
//!     original: None,
//! }];
//! let stderr = "%Error-PINNOTFOUND: /src/top.v:2:22: Pin not found: 'nope'\n";
//! assert_eq!(
//!     explain(stderr, &files, &|_| None).unwrap(),
//!     "top.v:2:22: `sub` has no port `nope` (its ports: clk)"
//! );
//! ```

use botsim_core::frontend::scan::{self, Module};

/// What a file Verilator read is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// botsim's own Verilog: the board around the design, its models of Xilinx's
    /// primitives, of the KCPSM6 and the bot, the program ROMs.
    Own,
    /// Verilog botsim wrote for this design: a core from its configuration, a course
    /// module's stand-in, a stub, a VHDL entity's conversion, a ROM from its `.psm`.
    Generated,
    /// The user's file (as on disk, or with botsim's edits: `original` then holds the file).
    User,
}

/// A file of the build.
#[derive(Clone, Debug)]
pub struct File {
    /// How Verilator names it in its messages.
    pub given: String,
    /// How the user knows it (their path; for botsim's files, what botsim calls them).
    pub shown: String,
    pub origin: Origin,
    /// The text Verilator read.
    pub text: String,
    /// The file's text on disk, when Verilator read botsim's edit of it.
    pub original: Option<String>,
}

/// How to send botsim what it built wrong.
pub const REPORT: &str =
    "please report it, with the Verilog botsim wrote (BOTSIM_KEEP_GENERATED=DIR botsim board ... keeps it in DIR)";

/// What of botsim's stands for a module of the design.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Stand {
    /// botsim's model of a part whose ports are fixed (the KCPSM6, a Xilinx primitive): a
    /// connection it lacks is the design's.
    Model(String),
    /// Verilog botsim built for this design (a core from its configuration, a ROM): a
    /// connection it lacks is botsim's mistake.
    Built(String),
}

/// The one line for Verilator's first error in `stderr` (`None` when it reports none).
/// `stands_for(module)`: what of botsim's stands for a module of the design, if any.
pub fn explain(stderr: &str, files: &[File], stands_for: &dyn Fn(&str) -> Option<Stand>) -> Option<String> {
    let line = stderr.lines().find(|l| l.starts_with("%Error: ") || l.starts_with("%Error-"))?;
    let rest = line.split_once(": ").map_or(line, |(_, r)| r);
    // `FILE:LINE:COL: message`, or a message alone.
    let located = rest.split_once(": ").and_then(|(loc, msg)| {
        let mut parts = loc.rsplitn(3, ':');
        let col: u32 = parts.next()?.parse().ok()?;
        let line: u32 = parts.next()?.parse().ok()?;
        Some((parts.next()?, line, col, msg))
    });
    let Some((given, l, c, msg)) = located else {
        return Some(format!("Verilator cannot build the design: {}", plain(rest)));
    };
    let msg = plain(msg);
    let Some(file) = files.iter().find(|f| f.given == given || given.ends_with(&format!("/{}", f.given))) else {
        return Some(format!("{given}:{l}:{c}: {msg}"));
    };
    let at = format!("{}:{l}:{c}", file.shown);
    Some(match file.origin {
        Origin::Own => format!("botsim's own Verilog ({at}) does not build with this design: {msg}; {REPORT}"),
        Origin::Generated => {
            let module = module_at(&file.text, l).map_or_else(|| "a module".to_string(), |m| format!("`{}`", m.name));
            format!("botsim built a wrong replacement for {module} ({at}: {msg}); {REPORT}")
        }
        Origin::User => user_error(file, &at, l, &msg, files, stands_for),
    })
}

/// Verilator's width warnings at connections of what botsim built for the design (`-Wwarn-
/// WIDTH`), in botsim's words: a core built from the design's configuration with another
/// width than the design connects (an 11-bit address to a 4096-deep memory) runs as Vivado
/// builds it (upper bits 0, or dropped), said once at the connection. The design's widths
/// between its own modules are its own (Vivado warns as Verilator does): not said.
///
/// ```
/// use botsim::board::explain::{replacement_widths, File, Origin, Stand};
/// let files = [File {
///     given: "/r/icon.v".into(),
///     shown: "icon.v".into(),
///     origin: Origin::User,
///     text: "module icon(input clk);\n  Icon_Rom rom (.clka(clk), .addra(a12), .douta());\nendmodule\n".into(),
///     original: None,
/// }];
/// let stderr = "%Warning-WIDTH: /r/icon.v:2:29: Input port connection 'addra' expects 8 bits on the pin \
///               connection, but pin connection's VARREF 'a12' generates 12 bits.\n";
/// let said = replacement_widths(stderr, &files, &|m| Some(Stand::Built(format!("botsim's core for `{m}`"))));
/// assert_eq!(said[0], "icon.v:2:29: the design connects 12 bits to `addra` of `Icon_Rom`, 8 bits wide in botsim's core for `Icon_Rom`: as Vivado builds it, the design's upper 4 bits are dropped");
/// ```
pub fn replacement_widths(stderr: &str, files: &[File], stands_for: &dyn Fn(&str) -> Option<Stand>) -> Vec<String> {
    let mut out = Vec::new();
    for line in stderr.lines().filter(|l| l.starts_with("%Warning-WIDTH")) {
        let Some((_, rest)) = line.split_once(": ") else { continue };
        let Some((loc, msg)) = rest.split_once(": ") else { continue };
        let mut parts = loc.rsplitn(3, ':');
        let (Some(c), Some(l), Some(given)) = (parts.next(), parts.next(), parts.next()) else { continue };
        let (Ok(l), Ok(_)) = (l.parse::<u32>(), c.parse::<u32>()) else { continue };
        let Some(port) = msg.split_once("port connection '").and_then(|(_, r)| r.split_once('\'')).map(|(p, _)| p)
        else {
            continue;
        };
        let bits = |after: &str| {
            msg.split_once(after).and_then(|(_, r)| r.split_whitespace().next()).and_then(|n| n.parse::<u32>().ok())
        };
        let (Some(takes), Some(given_bits)) = (bits(" expects "), bits(" generates ")) else { continue };
        let Some(file) = files
            .iter()
            .find(|f| f.origin == Origin::User && (f.given == given || given.ends_with(&format!("/{}", f.given))))
        else {
            continue;
        };
        let Some(inst) = instance_at(&file.text, l) else { continue };
        if let Some(Stand::Built(what)) = stands_for(&inst.module) {
            // The width is the design's configuration's (the core's `.xci`, the ROM's
            // contents): the mismatch is the design's, built as Vivado builds it.
            let d = given_bits.abs_diff(takes);
            let (bits, read, are) =
                if d == 1 { ("bit".to_string(), "reads", "is") } else { (format!("{d} bits"), "read", "are") };
            let output = msg.starts_with("Output");
            let how = match (output, given_bits < takes) {
                (false, true) => format!("its upper {bits} {read} 0"),
                (false, false) => format!("the design's upper {bits} {are} dropped"),
                (true, true) => format!("its upper {bits} {are} dropped"),
                (true, false) => format!("the design's upper {bits} {read} 0"),
            };
            out.push(format!(
                "{}:{l}:{c}: the design connects {given_bits} bits to `{port}` of `{}`, {takes} bits wide in {what}: as Vivado builds it, {how}",
                file.shown, inst.module
            ));
        }
    }
    out
}

/// An error Verilator found in a user's file.
fn user_error(
    file: &File,
    at: &str,
    line: u32,
    msg: &str,
    files: &[File],
    stands_for: &dyn Fn(&str) -> Option<Stand>,
) -> String {
    let quoted = |prefix: &str| msg.strip_prefix(prefix).map(|r| r.trim_end_matches('\'').to_string());
    if let Some(pin) = quoted("Pin not found: '") {
        let Some(inst) = instance_at(&file.text, line) else {
            return format!("{at}: a connection names a port `{pin}` that the module does not have");
        };
        let module = inst.module.as_str();
        let ports = defined(files, module).map(|m| m.ports.iter().map(|p| p.name.clone()).collect::<Vec<_>>());
        let ports = match ports {
            Some(p) if p.is_empty() => " (it has no ports)".to_string(),
            Some(p) => format!(" (its ports: {})", p.join(", ")),
            None => String::new(),
        };
        return match stands_for(module) {
            Some(Stand::Built(what)) => format!(
                "{at}: the design connects `{pin}` of `{module}`, which {what} does not have{ports}: botsim built it wrong; {REPORT}"
            ),
            Some(Stand::Model(what)) => format!("{at}: `{module}` has no port `{pin}`: {what} has the real one's{ports}"),
            None => format!("{at}: `{module}` has no port `{pin}`{ports}"),
        };
    }
    if let Some(module) = quoted("Cannot find file containing module: '") {
        return format!("{at}: `{module}` is defined in no file botsim compiles (add its file, or --stub {module})");
    }
    if edited_line(file, line) {
        return format!("{at}: botsim's edit of this line does not build ({msg}); {REPORT}");
    }
    if msg.starts_with("syntax error") {
        // A `begin` without its `end`: Verilator stops at the module's end, or at the next
        // thing only a module may hold (an instance's `#(`, an `always`); the mistake is
        // where the `begin` is.
        let module_level = ["endmodule", "'#'", "always", "assign", "initial", "module"]
            .iter()
            .any(|w| msg.contains(&format!("unexpected {w}")));
        if module_level {
            if let Some((l, c)) = botsim_core::frontend::scan::unclosed_begin(&file.text, line) {
                return format!(
                    "{}:{l}:{c}: this `begin` has no `end` (Verilator stops later, {at}: {msg})",
                    file.shown
                );
            }
        }
        return format!("{at}: this does not parse ({msg})");
    }
    format!("{at}: {msg}")
}

/// Verilator's words without its asides (`... For error description see`).
fn plain(msg: &str) -> String {
    msg.trim().to_string()
}

/// botsim compiled line `line` of `file` otherwise than the file has it.
fn edited_line(file: &File, line: u32) -> bool {
    let Some(original) = &file.original else { return false };
    let nth = |t: &str| t.lines().nth(line as usize - 1).map(str::to_string);
    // A line blanked out (a module left out) is no edit of what the user wrote there.
    nth(&file.text).is_some_and(|compiled| !compiled.trim().is_empty() && Some(compiled) != nth(original))
}

/// The module of `text` whose lines hold `line`.
fn module_at(text: &str, line: u32) -> Option<Module> {
    let line_of = |byte: usize| text[..byte.min(text.len())].matches('\n').count() as u32 + 1;
    scan::scan(text).into_iter().find(|m| line_of(m.span.start) <= line && line <= line_of(m.span.end))
}

/// The instance of `text` that line `line` is part of: the last one that begins at or
/// before it in its module.
fn instance_at(text: &str, line: u32) -> Option<scan::Instance> {
    module_at(text, line)?.instances.into_iter().filter(|i| i.line <= line).max_by_key(|i| (i.line, i.col))
}

/// The definition of `module` among the build's files.
fn defined(files: &[File], module: &str) -> Option<Module> {
    files.iter().flat_map(|f| scan::scan(&f.text)).find(|m| m.name == module)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(given: &str, shown: &str, origin: Origin, text: &str, original: Option<&str>) -> File {
        File { given: given.into(), shown: shown.into(), origin, text: text.into(), original: original.map(Into::into) }
    }

    const TOP: &str =
        "module top(input clk);\n  Icon_Rom rom (.clka(clk), .addra(8'd0), .douta());\n  foo f (.x(clk));\nendmodule\n";

    #[test]
    fn each_kind_of_error_is_said_in_botsims_words() {
        let core = "module Icon_Rom(input clk, input [7:0] addr, output [1:0] data);\nendmodule\n";
        let files = [
            file("/r/top.v", "top.v", Origin::User, TOP, None),
            file("user1_Icon_Rom.v", "botsim/cores/Icon_Rom.v", Origin::Generated, core, None),
            file("botsim_board.sv", "botsim's board", Origin::Own, "module botsim_board;\nendmodule\n", None),
        ];
        let stands = |m: &str| (m == "Icon_Rom").then(|| Stand::Built("botsim's Block Memory Generator core".into()));
        let say = |e: &str| explain(e, &files, &stands).unwrap();
        // A pin of botsim's replacement: botsim's fault, and how to report it.
        let s = say("%Error-PINNOTFOUND: /r/top.v:2:18: Pin not found: 'clka'\n");
        assert!(s.starts_with("top.v:2:18: the design connects `clka` of `Icon_Rom`, which botsim's Block Memory Generator core does not have (its ports: clk, addr, data): botsim built it wrong;"), "{s}");
        assert!(s.contains("BOTSIM_KEEP_GENERATED"), "{s}");
        // A module nothing defines: the user's to add, or to stub.
        let s = say("%Error: /r/top.v:3:3: Cannot find file containing module: 'foo'\n");
        assert_eq!(s, "top.v:3:3: `foo` is defined in no file botsim compiles (add its file, or --stub foo)");
        // In what botsim wrote: botsim's fault, the module named.
        let s = say("%Error: user1_Icon_Rom.v:1:20: Can't find definition of variable: 'q'\n");
        assert!(s.starts_with("botsim built a wrong replacement for `Icon_Rom` (botsim/cores/Icon_Rom.v:1:20: Can't find definition of variable: 'q');"), "{s}");
        let s = say("%Error: botsim_board.sv:1:8: Duplicate declaration\n");
        assert!(s.starts_with("botsim's own Verilog (botsim's board:1:8) does not build with this design"), "{s}");
    }

    #[test]
    fn a_syntax_error_in_a_line_botsim_rewrote_is_botsims() {
        let original = "module top(input clk);\n  wire [7:0] byte = 8'h1FF;\nendmodule\n";
        let rewritten = "module top(input clk);\n  wire [7:0] \\byte  = 8'hFF ;\nendmodule\n";
        let files = [file("user0_top.v", "top.v", Origin::User, rewritten, Some(original))];
        let s = explain("%Error: user0_top.v:2:14: syntax error, unexpected '='\n", &files, &|_| None).unwrap();
        assert!(
            s.starts_with("top.v:2:14: botsim's edit of this line does not build (syntax error, unexpected '=');"),
            "{s}"
        );
        // The same error on a line the user wrote is theirs.
        let files = [file("user0_top.v", "top.v", Origin::User, original, Some(original))];
        let s = explain("%Error: user0_top.v:2:14: syntax error, unexpected '='\n", &files, &|_| None).unwrap();
        assert_eq!(s, "top.v:2:14: this does not parse (syntax error, unexpected '=')");
    }
}
