//! Pass 4: resolve names, emit the words and the listing.

use std::collections::HashMap;

use super::layout::Layout;
use super::operands::{arg_text, Addr, Opnd, Tmpl, Val};
use super::{Assembler, Listed, SymbolValue};
use crate::image::Image;
use crate::isa::{Instr, Operand};

/// What pass 4 produced.
pub(super) struct Encoded {
    pub image: Image,
    /// Every occupied address, ascending.
    pub occupied: Vec<u16>,
    pub listing: Vec<Listed>,
}

impl Assembler<'_> {
    pub(super) fn lookup(&mut self, name: &str) -> Option<SymbolValue> {
        let i = *self.index.get(name)?;
        self.symbols[i].used = true;
        Some(self.symbols[i].value.clone())
    }

    /// Resolve an 8-bit value; returns it and a listing annotation.
    pub(super) fn resolve_val(&mut self, v: &Val, src: usize) -> Option<(u8, Option<String>)> {
        match v {
            Val::Lit(b) => Some((*b, None)),
            Val::Const { name, col, invert } => match self.lookup(name) {
                Some(SymbolValue::Constant(c)) => {
                    let tag = if *invert { format!("~{name}") } else { name.clone() };
                    Some((if *invert { !c } else { c }, Some(tag)))
                }
                Some(SymbolValue::Label(_)) => {
                    self.err_at(
                        src,
                        *col,
                        format!("'{name}' is a label; write {name}'upper or {name}'lower for its address bytes"),
                    );
                    None
                }
                Some(_) => {
                    self.err_at(src, *col, format!("'{name}' is not a CONSTANT"));
                    None
                }
                None => {
                    self.err_at(src, *col, format!("undefined constant '{name}'"));
                    None
                }
            },
            Val::LabelPart { name, col, upper } => match self.lookup(name) {
                Some(SymbolValue::Label(a)) => {
                    let b = if *upper { (a >> 8) as u8 } else { a as u8 };
                    Some((b, Some(format!("{name}'{}", if *upper { "upper" } else { "lower" }))))
                }
                _ => {
                    self.err_at(src, *col, format!("undefined label '{name}'"));
                    None
                }
            },
        }
    }

    pub(super) fn resolve_addr(&mut self, a: &Addr, src: usize) -> Option<u16> {
        match a {
            Addr::Lit(v) => Some(*v),
            Addr::Label(name, col) => match self.lookup(name) {
                Some(SymbolValue::Label(v)) => Some(v),
                Some(_) => {
                    self.err_at(src, *col, format!("'{name}' is not a label"));
                    None
                }
                None => {
                    self.err_at(src, *col, format!("undefined label '{name}'"));
                    None
                }
            },
        }
    }

    pub(super) fn encode(&mut self, layout: &Layout) -> Encoded {
        let mut image = Image::zeroed();
        let mut occupied = Vec::new();
        let mut listing = Vec::new();
        let mut by_src: HashMap<usize, usize> = HashMap::new();
        for (i, p) in layout.placed.iter().enumerate() {
            by_src.insert(p.src, i);
        }
        for src in 0..self.lines.len() {
            let loc = self.lines[src].loc.clone();
            let comment = self.lines[src].line.comment.clone();
            let label = layout.labels_at.get(&src).and_then(|v| v.first().cloned());
            let Some(&pi) = by_src.get(&src) else {
                let text = self.directive_text(src);
                let address = label.as_ref().and_then(|l| match self.lookup_quiet(l) {
                    Some(SymbolValue::Label(a)) => Some(a),
                    _ => None,
                });
                if label.is_some() || !text.is_empty() || comment.is_some() {
                    listing.push(Listed { loc, address, word: None, label, text, comment });
                }
                continue;
            };
            let p = &layout.placed[pi];
            let words = self.encode_one(&p.tmpl, p.src);
            for (k, (word, text)) in words.into_iter().enumerate() {
                let a = p.addr + k as u16;
                image.words[a as usize] = word;
                occupied.push(a);
                listing.push(Listed {
                    loc: loc.clone(),
                    address: Some(a),
                    word: Some(word),
                    label: if k == 0 { label.clone() } else { None },
                    text,
                    comment: if k == 0 { comment.clone() } else { None },
                });
            }
        }
        occupied.sort_unstable();
        Encoded { image, occupied, listing }
    }

    pub(super) fn lookup_quiet(&self, name: &str) -> Option<SymbolValue> {
        self.index.get(name).map(|&i| self.symbols[i].value.clone())
    }

    /// The words of one placed instruction with their canonical, annotated text.
    pub(super) fn encode_one(&mut self, t: &Tmpl, src: usize) -> Vec<(u32, String)> {
        let ann = |base: String, tag: Option<String>| match tag {
            Some(t) => format!("{base}[{t}]"),
            None => base,
        };
        match t {
            Tmpl::Fixed(i) => vec![(i.encode(), i.to_string())],
            Tmpl::Inst(w) => vec![(*w, format!("INST {w:05X}"))],
            Tmpl::Op2(op, sx, Opnd::Reg(sy)) => {
                let i = Instr::Op2(*op, *sx, Operand::Reg(*sy));
                vec![(i.encode(), i.to_string())]
            }
            Tmpl::Op2(op, sx, Opnd::Val(v)) => {
                let Some((k, tag)) = self.resolve_val(v, src) else { return vec![(0, String::new())] };
                let i = Instr::Op2(*op, *sx, Operand::Const(k));
                vec![(i.encode(), ann(i.to_string(), tag))]
            }
            Tmpl::OutputK(v, p) => {
                let (Some((k, tk)), Some((port, tp))) = (self.resolve_val(v, src), self.resolve_val(p, src)) else {
                    return vec![(0, String::new())];
                };
                if port > 15 {
                    let col = match p {
                        Val::Const { col, .. } | Val::LabelPart { col, .. } => *col,
                        Val::Lit(_) => 0,
                    };
                    self.err_at(src, col, format!("OUTPUTK port must be 0-F, the constant is {port:02X}"));
                    return vec![(0, String::new())];
                }
                let i = Instr::OutputK(k, port);
                let text = format!("OUTPUTK {}, {}", ann(format!("{k:02X}"), tk), ann(format!("{port:X}"), tp));
                vec![(i.encode(), text)]
            }
            Tmpl::OutputKSeq(bytes, name, p) => {
                let Some((port, _)) = self.resolve_val(p, src) else { return vec![(0, String::new())] };
                bytes
                    .iter()
                    .map(|&b| {
                        (Instr::OutputK(b, port & 15).encode(), format!("OUTPUTK {b:02X}[{name}], {:X}", port & 15))
                    })
                    .collect()
            }
            Tmpl::LoadReturn(sx, v) => {
                let Some((k, tag)) = self.resolve_val(v, src) else { return vec![(0, String::new())] };
                let i = Instr::LoadReturn(*sx, k);
                vec![(i.encode(), ann(i.to_string(), tag))]
            }
            Tmpl::LoadReturnSeq(sx, bytes, name) => bytes
                .iter()
                .map(|&b| (Instr::LoadReturn(*sx, b).encode(), format!("LOAD&RETURN {sx}, {b:02X}[{name}]")))
                .collect(),
            Tmpl::Jump(c, a) | Tmpl::Call(c, a) => {
                let Some(target) = self.resolve_addr(a, src) else { return vec![(0, String::new())] };
                let i = if matches!(t, Tmpl::Jump(..)) { Instr::Jump(*c, target) } else { Instr::Call(*c, target) };
                let tag = match a {
                    Addr::Label(n, _) => Some(n.clone()),
                    Addr::Lit(_) => None,
                };
                vec![(i.encode(), ann(i.to_string(), tag))]
            }
        }
    }

    /// The listing text of a directive line.
    pub(super) fn directive_text(&self, src: usize) -> String {
        let l = &self.lines[src].line;
        let Some(kw) = &l.keyword else { return String::new() };
        let args: Vec<String> = l.args.iter().map(arg_text).collect();
        format!("{} {}", kw.text.to_ascii_uppercase(), args.join(", ")).trim_end().to_string()
    }
}
