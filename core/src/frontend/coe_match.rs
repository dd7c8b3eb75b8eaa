//! Memory cores committed without their configuration (no `.xci`, no `.xco`, no wrapper)
//! and without a `.coe` of their own name, matched to the repository's `.coe` files: a file
//! fits an instance when its words fit the address the instance connects and its values the
//! data width; among those that fit, the one whose name most resembles the module's is taken
//! when it is the only closest. Teams name their screens `player1wins` and their files
//! `Player1_wins_final.coe`.
//!
//! ```
//! use botsim_core::frontend::coe_match::resemblance;
//! assert!(resemblance("player1wins", "Player1_wins_final") > resemblance("player1wins", "Player2_wins_final"));
//! assert!(resemblance("tie", "tie_final") >= 0.5);
//! assert!(resemblance("game_init", "start_screen_key") < 0.5);
//! ```

use std::path::{Path, PathBuf};

use super::memcore::Coe;
use super::scan::{Instance, Module};

/// How far a name must resemble the module's to be taken (see [`resemblance`]).
pub const RESEMBLES: f64 = 0.5;

/// The widths an instance connects to one memory port, where they can be read from the
/// declarations of the module that instantiates it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Shape {
    /// Bits of the address (`addra`).
    pub addr: Option<u32>,
    /// Bits of the data (`douta`, else `dina`).
    pub data: Option<u32>,
}

impl Shape {
    /// The widths connected to port `a` (else `b`) of `inst`, read in `scope`.
    pub fn connected(inst: &Instance, scope: &Module) -> Shape {
        let width = |port: &str| {
            inst.connections.iter().find(|(p, _)| p.eq_ignore_ascii_case(port)).and_then(|(_, e)| expr_width(e, scope))
        };
        let of = |x: &str| Shape {
            addr: width(&format!("addr{x}")),
            data: width(&format!("dout{x}")).or_else(|| width(&format!("din{x}"))),
        };
        let a = of("a");
        let b = of("b");
        Shape { addr: a.addr.or(b.addr), data: a.data.or(b.data) }
    }

    /// The depth the connected address reaches.
    pub fn depth(&self) -> Option<u32> {
        self.addr.filter(|&a| a <= 20).map(|a| 1 << a)
    }

    /// `its 15-bit address and 12-bit data`, as far as known.
    pub fn describe(&self) -> String {
        match (self.addr, self.data) {
            (Some(a), Some(d)) => format!("its {a}-bit address and {d}-bit data"),
            (Some(a), None) => format!("its {a}-bit address"),
            (None, Some(d)) => format!("its {d}-bit data"),
            (None, None) => "its ports (their widths unread)".into(),
        }
    }

    /// Do `coe`'s words fit: no more than the address reaches and more than one bit fewer
    /// would (Vivado sizes a core's address to its depth), each value within the data width?
    pub fn fits(&self, coe: &Coe) -> bool {
        let words = coe.words.len() as u64;
        let addr_ok = self.addr.map_or(true, |a| a <= 32 && words <= 1 << a && (a <= 1 || words > 1 << (a - 1)));
        let needed = coe.words.iter().map(|w| 64 - w.leading_zeros()).max().unwrap_or(0);
        let data_ok = self.data.map_or(true, |d| needed <= d);
        addr_ok && data_ok
    }
}

/// The width of a connected expression, read from `scope`'s declarations: a name, a part or
/// bit select with constant bounds, a sized literal, a concatenation of those. `None` where
/// it depends on a parameter or is not one of those.
pub fn expr_width(expr: &str, scope: &Module) -> Option<u32> {
    let e = expr.trim();
    if let Some(inner) = e.strip_prefix('(').and_then(|r| r.strip_suffix(')')) {
        return expr_width(inner, scope);
    }
    if let Some(inner) = e.strip_prefix('{').and_then(|r| r.strip_suffix('}')) {
        if inner.contains('{') {
            return None; // a replication
        }
        return inner.split(',').map(|p| expr_width(p, scope)).sum();
    }
    if let Some((size, _)) = e.split_once('\'') {
        return size.trim().parse().ok();
    }
    if let Some((name, select)) = e.split_once('[') {
        let select = select.strip_suffix(']')?;
        declared(name.trim(), scope)?;
        return match select.split_once(':') {
            Some((m, l)) => range_width(m, l),
            None => select.trim().parse::<i64>().ok().map(|_| 1),
        };
    }
    declared(e, scope)
}

/// The width of the port or net `name` of `scope`, when its range is two integers.
fn declared(name: &str, scope: &Module) -> Option<u32> {
    if let Some(p) = scope.ports.iter().find(|p| p.name == name) {
        return match p.range {
            Some((m, l)) => Some(m.abs_diff(l) as u32 + 1),
            None => (p.width > 0).then_some(p.width),
        };
    }
    let net = scope.nets.iter().find(|n| n.name == name)?;
    match &net.range {
        None => Some(1),
        Some(r) => {
            let (m, l) = r.trim().strip_prefix('[')?.strip_suffix(']')?.split_once(':')?;
            range_width(m, l)
        }
    }
}

fn range_width(m: &str, l: &str) -> Option<u32> {
    let (m, l): (i64, i64) = (m.trim().parse().ok()?, l.trim().parse().ok()?);
    Some(m.abs_diff(l) as u32 + 1)
}

/// How much a file's name (its stem) resembles a module's, 0 to 1, without regard to case,
/// `_`, `-` or spaces: 0.5 and more when one name holds the other, else the share of
/// letter pairs they have in common (Sørensen-Dice).
pub fn resemblance(module: &str, stem: &str) -> f64 {
    let norm = |s: &str| s.chars().filter(|c| c.is_alphanumeric()).flat_map(char::to_lowercase).collect::<String>();
    let (a, b) = (norm(module), norm(stem));
    if a.is_empty() || b.is_empty() {
        return 0.0;
    }
    let dice = strsim::sorensen_dice(&a, &b);
    let (short, long) = if a.len() <= b.len() { (&a, &b) } else { (&b, &a) };
    if short.chars().count() >= 3 && long.contains(short.as_str()) {
        let share = short.chars().count() as f64 / long.chars().count() as f64;
        return dice.max(0.5 + 0.5 * share);
    }
    dice
}

/// A `.coe` that fits an instance, with how much its name resembles the module's.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    pub path: PathBuf,
    pub resemblance: f64,
}

/// What the repository's `.coe` files offer one core.
#[derive(Clone, Debug, PartialEq)]
pub enum Offer {
    /// One file fits and its name is the only closest that resembles the module's.
    Taken(Candidate),
    /// The files that fit, closest first (none of them the only closest that resembles).
    Choose(Vec<Candidate>),
}

/// The `.coe` files (read: `(path, contents)`) that fit `shape`, weighed against `module`.
pub fn offer<'a>(module: &str, shape: &Shape, coes: impl IntoIterator<Item = &'a (PathBuf, Coe)>) -> Offer {
    let stem = |p: &Path| p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let mut fit: Vec<Candidate> = coes
        .into_iter()
        .filter(|(_, c)| shape.fits(c))
        .map(|(p, _)| Candidate { path: p.clone(), resemblance: resemblance(module, &stem(p)) })
        .collect();
    fit.sort_by(|x, y| y.resemblance.total_cmp(&x.resemblance).then_with(|| x.path.cmp(&y.path)));
    match &fit[..] {
        [best, rest @ ..]
            if best.resemblance >= RESEMBLES && rest.first().map_or(true, |r| r.resemblance < best.resemblance) =>
        {
            Offer::Taken(best.clone())
        }
        _ => Offer::Choose(fit),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend::scan::scan;

    fn coe(words: usize, max: u64) -> Coe {
        let mut w = vec![0; words];
        if let Some(last) = w.last_mut() {
            *last = max;
        }
        Coe { words: w, unterminated: None, written_bits: 0 }
    }

    #[test]
    fn widths_of_what_is_connected_are_read_from_the_declarations() {
        let m = &scan(
            "module top(input [3:0] sw, output [11:0] rgb);\n\
             wire [14:0] addr; wire [7:0] row, col; reg [11:0] pix; wire one;\n\
             parameter W = 4; wire [W-1:0] p;\n\
             screen s(.clka(clk), .addra(addr), .douta(pix));\nendmodule\n",
        )[0];
        let w = |e: &str| expr_width(e, m);
        assert_eq!(w("addr"), Some(15));
        assert_eq!(w(" sw "), Some(4));
        assert_eq!(w("{row[6:0], col}"), Some(15));
        assert_eq!(w("{3'd0, one}"), Some(4));
        assert_eq!(w("addr[3]"), Some(1));
        assert_eq!(w("(pix)"), Some(12));
        assert_eq!(w("p"), None, "a parameter's range is not evaluated");
        assert_eq!(w("nothing"), None);
        assert_eq!(w("{4{one}}"), None);
        let shape = Shape::connected(&m.instances[0], m);
        assert_eq!(shape, Shape { addr: Some(15), data: Some(12) });
        assert_eq!(shape.depth(), Some(32768));
    }

    #[test]
    fn a_coe_fits_when_its_words_need_the_address_and_its_values_the_data() {
        let s = Shape { addr: Some(15), data: Some(12) };
        assert!(s.fits(&coe(19200, 0xFFF)));
        assert!(s.fits(&coe(32768, 1)));
        assert!(!s.fits(&coe(32769, 1)), "more words than the address reaches");
        assert!(!s.fits(&coe(16384, 1)), "a 14-bit address would do: another core's");
        assert!(!s.fits(&coe(19200, 0x1FFF)), "a 13-bit value");
        assert!(Shape::default().fits(&coe(5, 1 << 40)), "nothing known: nothing excluded");
    }

    #[test]
    fn the_only_closest_resembling_file_is_taken_else_all_that_fit_are_offered_closest_first() {
        let s = Shape { addr: Some(15), data: Some(12) };
        let files = |names: &[&str]| -> Vec<(PathBuf, Coe)> {
            names.iter().map(|n| (PathBuf::from(format!("ip/{n}.coe")), coe(19200, 0xABC))).collect()
        };
        let coes = files(&["Player1_wins_final", "Player2_wins_final", "tie_final", "start_screen_key"]);
        let taken = |m: &str| match offer(m, &s, &coes) {
            Offer::Taken(c) => c.path.file_stem().unwrap().to_string_lossy().into_owned(),
            other => panic!("{m}: {other:?}"),
        };
        assert_eq!(taken("player1wins"), "Player1_wins_final");
        assert_eq!(taken("player2wins"), "Player2_wins_final");
        assert_eq!(taken("tie"), "tie_final");
        let Offer::Choose(c) = offer("game_init", &s, &coes) else { panic!("nothing resembles game_init") };
        assert_eq!(c.len(), 4);
        assert!(c.windows(2).all(|w| w[0].resemblance >= w[1].resemblance));
        // Two as close as each other: neither is taken.
        let twins = files(&["bg_a", "bg_b"]);
        assert!(matches!(offer("bg", &s, &twins), Offer::Choose(c) if c.len() == 2));
        // What does not fit is not offered, however it is named.
        let small = vec![(PathBuf::from("tie.coe"), coe(100, 1))];
        assert_eq!(offer("tie", &s, &small), Offer::Choose(vec![]));
    }
}
