//! The course's own modules that some repositories do not carry (spec board.md §2): botsim's
//! clean-room `debounce`, `sevensegment` and `dtg` (rtl/board/course/), with the course's
//! ports and parameters. One stands in only where a design instantiates a module of that
//! name (in any case) that nothing in the sources defines, and only when the instance's
//! connections are ports it has.
//!
//! ```
//! use botsim_core::frontend::course::stand_in;
//! let (text, module) = stand_in("SevenSegment", &["d0", "d7"]).unwrap();
//! assert!(text.contains("module SevenSegment #("));
//! assert!(module.port("digits_out").is_some());
//! assert!(stand_in("uart", &[]).is_none());
//! // A Nexys3 design connects four digits: the version that walks four.
//! let (text, _) = stand_in("sevensegment", &["d0", "d1", "d2", "d3"]).unwrap();
//! assert!(text.contains("DIGITS                 = 4"));
//! ```

use super::scan::{self, Module};

/// The course modules botsim has, with their Verilog.
pub const MODULES: [(&str, &str); 3] = [
    ("debounce", include_str!("../../../rtl/board/course/debounce.v")),
    ("sevensegment", include_str!("../../../rtl/board/course/sevensegment.v")),
    ("dtg", include_str!("../../../rtl/board/course/dtg.v")),
];

/// botsim's stand-in for the course module `name` (matched without regard to case, and named
/// as the design spells it) for an instance that connects the ports `connected`: its Verilog
/// and its scanned ports. A `sevensegment` that connects none of d4..d7 is the Nexys3
/// version, which walks four digits.
pub fn stand_in(name: &str, connected: &[&str]) -> Option<(String, Module)> {
    let (own, text) = MODULES.iter().find(|(m, _)| m.eq_ignore_ascii_case(name))?;
    let mut text = text.replacen(&format!("module {own} "), &format!("module {name} "), 1);
    // By name, or by position (clk, reset, d0..d7: d4 is the seventh).
    let eight = connected.iter().any(|c| {
        ["d4", "d5", "d6", "d7"].iter().any(|d| c.eq_ignore_ascii_case(d))
            || c.strip_prefix('#').and_then(|n| n.parse::<usize>().ok()).is_some_and(|n| n >= 6)
    });
    if *own == "sevensegment" && !eight {
        text = text.replacen(
            "parameter integer DIGITS                 = 8",
            "parameter integer DIGITS                 = 4",
            1,
        );
    }
    let module = scan::scan(&text).into_iter().find(|m| m.name == name)?;
    Some((text, module))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend::scan::Dir;

    #[test]
    fn the_stand_ins_have_the_course_ports() {
        let (_, db) = stand_in("debounce", &[]).unwrap();
        for (p, d) in [
            ("clk", Dir::Input),
            ("pbtn_in", Dir::Input),
            ("switch_in", Dir::Input),
            ("pbtn_db", Dir::Output),
            ("swtch_db", Dir::Output),
        ] {
            assert_eq!(db.port(p).map(|p| p.dir), Some(d), "{p}");
        }
        assert!(db.params.iter().any(|p| p == "RESET_POLARITY_LOW") && db.params.iter().any(|p| p == "SIMULATE"));
        let (_, seg) = stand_in("sevensegment", &["d7"]).unwrap();
        for p in ["d0", "d7", "dp", "seg", "an", "clk", "reset"] {
            assert!(seg.port(p).is_some(), "{p}");
        }
        let (_, dtg) = stand_in("dtg", &[]).unwrap();
        for p in ["clock", "rst", "horiz_sync", "vert_sync", "video_on", "pixel_row", "pixel_column"] {
            assert!(dtg.port(p).is_some(), "{p}");
        }
    }
}
