//! A source-level trace of a running KCPSM6 and a profile of where its time goes, from the
//! ISS's [`Retired`] records and a [`SourceMap`].
//!
//! One line per completed instruction (or interrupt entry), in a window of cycles:
//!
//! ```text
//!     cycle      time_ms  pc   where          source                   instruction          effects
//!   1148874    11.488740  03A  loop+2         linefollow.psm:57        INPUT s0, 0A         s0=18  IN 0A=18  C0 Z1 A IE
//! ```
//!
//! The profile counts, per address and then per label, the instructions completed and the
//! cycles from the end of the previous one to the end of this one (so a label's cycles
//! include the cycles its instructions waited in sleep, reset or an interrupt entry).
//!
//! ```
//! use kcpsm6::{asm::assemble_source, iss::{Cpu, Config, NullBus, Pins}, source::SourceMap, trace::Tracer};
//! use std::path::Path;
//! let text = "start: LOAD s0, 03\nloop:  SUB s0, 01\n       JUMP NZ, loop\ndone:  JUMP done\n";
//! let p = assemble_source(Path::new("p.psm"), text, &Default::default()).unwrap();
//! let mut t = Tracer::new(SourceMap::of_source(&p, Path::new("p.psm"), text), 0, u64::MAX);
//! let mut cpu = Cpu::new(Config::default(), &p.image.words[..]);
//! let mut out = Vec::new();
//! for _ in 0..40 {
//!     if let Some(r) = cpu.tick(Pins::default(), &mut NullBus::default()) {
//!         t.retired(&r, cpu.cycle(), None, &mut out).unwrap();
//!     }
//! }
//! let lines = String::from_utf8(out).unwrap();
//! assert!(lines.lines().any(|l| l.contains("loop+1") && l.contains("p.psm:3") && l.contains("JUMP NZ, 001")));
//! assert!(t.profile().contains("loop"));
//! ```

use std::io::{self, Write};

use crate::disasm::disassemble_word;
use crate::isa::ROM_WORDS;
use crate::iss::{PortKind, RetireKind, Retired};
use crate::source::{SourceLine, SourceMap};

/// `file.psm:57`: the file's name and the line.
fn at(l: &SourceLine) -> String {
    let name = l.file.file_name().map_or_else(|| l.file.display().to_string(), |n| n.to_string_lossy().into());
    format!("{name}:{}", l.line)
}

/// Writes trace lines and keeps the profile.
pub struct Tracer {
    map: SourceMap,
    /// The cycles whose instructions are traced: `from..to` (the profile counts all).
    from: u64,
    to: u64,
    header: bool,
    /// Per address: instructions completed, cycles.
    counts: Vec<(u64, u64)>,
    last_end: u64,
}

impl Tracer {
    /// A tracer for the program `map` describes, writing lines for instructions whose D cycle
    /// is in `from..to`.
    pub fn new(map: SourceMap, from: u64, to: u64) -> Tracer {
        Tracer { map, from, to, header: false, counts: vec![(0, 0); ROM_WORDS], last_end: 0 }
    }

    /// One record; `end` is the CPU's cycle after it (the next to simulate), `time_ps` the
    /// time of the edge that ended it, when known.
    pub fn retired(&mut self, r: &Retired, end: u64, time_ps: Option<u64>, out: &mut impl Write) -> io::Result<()> {
        let c = &mut self.counts[r.pc as usize % ROM_WORDS];
        c.0 += 1;
        c.1 += end - self.last_end;
        self.last_end = end;
        if r.cycle < self.from || r.cycle >= self.to {
            return Ok(());
        }
        if !self.header {
            self.header = true;
            writeln!(
                out,
                "{:>10} {:>12}  {:<3}  {:<20} {:<28} {:<22} {:<30}  | source text",
                "cycle", "time_ms", "pc", "where", "source", "instruction", "effects"
            )?;
        }
        let time = time_ps.map_or("-".to_string(), |t| format!("{:.6}", t as f64 / 1e9));
        let source = self.map.line(r.pc).map_or(String::new(), at);
        let instruction = match r.kind {
            RetireKind::Executed => disassemble_word(r.word),
            RetireKind::Interrupt => format!("(interrupt; {} cancelled)", disassemble_word(r.word)),
        };
        let mut effects = String::new();
        if let Some((bank_b, x, v)) = r.reg_write {
            effects.push_str(&format!("s{x:X}{}={v:02X}  ", if bank_b { "'" } else { "" }));
        }
        if let Some((a, v)) = r.spm_write {
            effects.push_str(&format!("spm[{a:02X}]={v:02X}  "));
        }
        if let Some(p) = r.port {
            let what = match p.kind {
                PortKind::Read => "IN",
                PortKind::Write => "OUT",
                PortKind::KWrite => "OUTK",
            };
            effects.push_str(&format!("{what} {:02X}={:02X}  ", p.port, p.value));
        }
        effects.push_str(&format!(
            "C{} Z{} {}{}",
            r.c as u8,
            r.z as u8,
            if r.bank { "B" } else { "A" },
            if r.ie { " IE" } else { "" }
        ));
        let text = self.map.line(r.pc).map_or(String::new(), |l| format!("  | {}", l.text.trim()));
        writeln!(
            out,
            "{:>10} {time:>12}  {:03X}  {:<20} {source:<28} {instruction:<22} {effects:<30}{text}",
            r.cycle,
            r.pc,
            self.map.describe(r.pc)
        )
    }

    /// Where the time went: per label, the instructions and cycles and their share, the
    /// most cycles first; then the ten busiest source lines.
    pub fn profile(&self) -> String {
        let total: u64 = self.counts.iter().map(|c| c.1).sum::<u64>().max(1);
        let mut by_label: std::collections::BTreeMap<String, (u64, u64)> = Default::default();
        for (addr, &(n, cycles)) in self.counts.iter().enumerate() {
            if n == 0 {
                continue;
            }
            let label = self.map.label(addr as u16).map_or("(no label)".to_string(), |(l, _)| l.to_string());
            let e = by_label.entry(label).or_default();
            e.0 += n;
            e.1 += cycles;
        }
        let mut rows: Vec<_> = by_label.into_iter().collect();
        rows.sort_by(|a, b| b.1 .1.cmp(&a.1 .1).then(a.0.cmp(&b.0)));
        let mut s = String::from(
            "; cycles: from the end of the instruction before to the end of this one (reset, sleep and\n\
             ; interrupt entries count toward the instruction that follows them)\n",
        );
        s.push_str(&format!("{:<24} {:>14} {:>14} {:>7}\n", "label", "instructions", "cycles", "share"));
        for (label, (n, cycles)) in rows {
            s.push_str(&format!("{label:<24} {n:>14} {cycles:>14} {:>6.2}%\n", 100.0 * cycles as f64 / total as f64));
        }
        let mut lines: Vec<(u16, u64, u64)> =
            self.counts.iter().enumerate().filter(|(_, c)| c.0 > 0).map(|(a, c)| (a as u16, c.0, c.1)).collect();
        lines.sort_by(|a, b| b.2.cmp(&a.2).then(a.0.cmp(&b.0)));
        s.push_str(&format!("\n{:<4} {:<20} {:<40} {:>14} {:>7}\n", "pc", "where", "source", "cycles", "share"));
        for (addr, _, cycles) in lines.into_iter().take(10) {
            let src = self.map.line(addr).map_or(String::new(), |l| format!("{} {}", at(l), l.text.trim()));
            s.push_str(&format!(
                "{addr:03X}  {:<20} {src:<40} {cycles:>14} {:>6.2}%\n",
                self.map.describe(addr),
                100.0 * cycles as f64 / total as f64
            ));
        }
        s
    }
}
