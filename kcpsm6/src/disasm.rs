//! Disassembler: an [`Image`] back to KCPSM6 source that re-assembles to the same 4096 words.
//!
//! Jump and call targets get labels `L_AAA`; words that are not a canonical instruction
//! (undefined opcodes, undocumented variants) are written as `INST hhhhh`; long runs of zero
//! words become `ADDRESS` directives.
//!
//! ```
//! use kcpsm6::{asm::assemble_str, disasm::disassemble};
//! let p = assemble_str("start: ADD s0, 01\nJUMP NZ, start\nINST 23456\n").unwrap();
//! let text = disassemble(&p.image);
//! assert!(text.contains("L_000:"));
//! assert!(text.contains("JUMP NZ, L_000"));
//! assert!(text.contains("INST 23456"));
//! assert_eq!(assemble_str(&text).unwrap().image, p.image);
//! ```

use std::collections::BTreeSet;

use crate::image::Image;
use crate::isa::Instr;

/// Runs of at least this many zero words are skipped with `ADDRESS`.
const ZERO_RUN: usize = 8;

/// One line of disassembly for a word at `addr` (targets as 3-digit hex).
pub fn disassemble_word(word: u32) -> String {
    match Instr::decode(word) {
        Some(i) => i.to_string(),
        None => format!("INST {word:05X}"),
    }
}

/// The whole image as assemblable source.
pub fn disassemble(image: &Image) -> String {
    let words = &image.words[..];
    let Some(last) = words.iter().rposition(|&w| w != 0) else {
        return "; empty program: every location holds 00000\n".to_string();
    };
    let mut targets = BTreeSet::new();
    for &w in &words[..=last] {
        if let Some(Instr::Jump(_, t) | Instr::Call(_, t)) = Instr::decode(w) {
            if (t as usize) <= last {
                targets.insert(t as usize);
            }
        }
    }
    let mut out = String::from("; Disassembled by the botsim KCPSM6 toolchain.\n");
    let mut a = 0;
    while a <= last {
        // Skip a long run of zeros that holds no target.
        let run = words[a..=last].iter().take_while(|&&w| w == 0).count();
        let run_end = a + run;
        if run >= ZERO_RUN && !targets.range(a..run_end).any(|_| true) {
            out.push_str(&format!("                ADDRESS {run_end:03X}\n"));
            a = run_end;
            continue;
        }
        if targets.contains(&a) {
            out.push_str(&format!("L_{a:03X}:\n"));
        }
        let w = words[a];
        let text = match Instr::decode(w) {
            Some(Instr::Jump(c, t)) if targets.contains(&(t as usize)) => {
                format!("JUMP {}L_{t:03X}", c.map_or(String::new(), |c| format!("{}, ", c.name())))
            }
            Some(Instr::Call(c, t)) if targets.contains(&(t as usize)) => {
                format!("CALL {}L_{t:03X}", c.map_or(String::new(), |c| format!("{}, ", c.name())))
            }
            _ => disassemble_word(w),
        };
        out.push_str(&format!("                {text:<28}; {a:03X}: {w:05X}\n"));
        a += 1;
    }
    out
}
