//! Pass 3: addresses, labels, `ADDRESS`, `DEFAULT_JUMP`, `NAMEREG` (sequential) and every
//! instruction's operands, parsed with the register names valid on its line.

use std::collections::HashMap;

use super::lexer::{Arg, ColError, Word};
use super::names::{check_name, is_default_reg};
use super::number::parse_num;
use super::operands::{address, arg_text, char_value, port4, value8, Addr, Opnd, Tmpl, Val};
use super::{Assembler, SymbolValue};
use crate::diag::Loc;
use crate::isa::{Cond, Instr, Op2, Reg, Shift};

pub(super) struct Placed {
    /// The source line (index into the assembler's lines).
    pub src: usize,
    pub addr: u16,
    pub tmpl: Tmpl,
}

/// What pass 3 found: every instruction placed, the labels on each line, DEFAULT_JUMP.
pub(super) struct Layout {
    pub placed: Vec<Placed>,
    /// Source line -> the labels defined on it.
    pub labels_at: HashMap<usize, Vec<String>>,
    /// DEFAULT_JUMP's target and its line.
    pub default_jump: Option<(Addr, usize)>,
}

pub(super) struct RegNames {
    current: [String; 16],
}

impl RegNames {
    fn new() -> RegNames {
        RegNames { current: std::array::from_fn(|i| format!("s{i:X}")) }
    }

    /// The register a word names on this line: `Ok(Some)` for a valid name, `Err` for a default
    /// name that NAMEREG has replaced, `Ok(None)` when it is not a register name at all.
    fn lookup(&self, w: &str) -> Result<Option<u8>, String> {
        if let Some(i) = self.current.iter().position(|n| n == w || (is_default_reg(n) && n.eq_ignore_ascii_case(w))) {
            return Ok(Some(i as u8));
        }
        if is_default_reg(w) {
            let i = u8::from_str_radix(&w[1..], 16).unwrap_or(0);
            return Err(format!("register '{w}' was renamed '{}' by NAMEREG", self.current[i as usize]));
        }
        Ok(None)
    }
}

impl Assembler<'_> {
    pub(super) fn lay_out(&mut self) -> Layout {
        let mut regs = RegNames::new();
        let mut addr: usize = 0;
        let mut placed = Vec::new();
        let mut labels_at: HashMap<usize, Vec<String>> = HashMap::new();
        let mut default_jump = None;
        let mut past_end_reported = false;
        let limit = self.opts.rom_size.map_or(4096, |s| s.words());

        for src in 0..self.lines.len() {
            let line = self.lines[src].line.clone();
            if let Some(l) = &line.label {
                match check_name(&l.text) {
                    Err(m) => self.err_at(src, l.col, m),
                    Ok(()) if addr > 0xFFF => {
                        self.err_at(src, l.col, format!("label '{}' is past the last address FFF", l.text));
                    }
                    Ok(()) => {
                        let loc = Loc { col: l.col, ..self.lines[src].loc.clone() };
                        self.add_symbol(&l.text, SymbolValue::Label(addr as u16), Some(loc), Some(src));
                        labels_at.entry(src).or_default().push(l.text.clone());
                    }
                }
            }
            let Some(kw) = &line.keyword else { continue };
            let upper = kw.text.to_ascii_uppercase();
            match upper.as_str() {
                "CONSTANT" | "STRING" | "TABLE" | "INCLUDE" => continue,
                "NAMEREG" => {
                    self.namereg(src, kw, &line.args, &mut regs);
                    continue;
                }
                "ADDRESS" => {
                    match &line.args[..] {
                        [Arg::Word(w)] => match parse_num(&w.text, 3, 12) {
                            Some(Ok(a)) if (a as usize) < addr => self.err_at(
                                src,
                                w.col,
                                format!("ADDRESS {:03X} is below the current address {:03X}", a, addr),
                            ),
                            Some(Ok(a)) => addr = a as usize,
                            Some(Err(m)) => self.err_at(src, w.col, m),
                            None => self.err_at(src, w.col, format!("ADDRESS needs a number, found '{}'", w.text)),
                        },
                        _ => self.err_at(src, kw.col, "ADDRESS needs one address, e.g. ADDRESS 3FF"),
                    }
                    continue;
                }
                "DEFAULT_JUMP" => {
                    match &line.args[..] {
                        [Arg::Word(w)] if default_jump.is_none() => match address(w) {
                            Ok(a) => default_jump = Some((a, src)),
                            Err(m) => self.err_at(src, w.col, m),
                        },
                        [Arg::Word(w)] => self.err_at(src, w.col, "DEFAULT_JUMP is given more than once"),
                        _ => self.err_at(src, kw.col, "DEFAULT_JUMP needs one target, e.g. DEFAULT_JUMP reset"),
                    }
                    continue;
                }
                _ => {}
            }
            let tmpl = match self.instruction(kw, &line.args, &regs) {
                Ok(t) => t,
                Err(ColError { col, message: m }) => {
                    self.err_at(src, col, m);
                    addr += 1;
                    continue;
                }
            };
            let size = tmpl.size();
            if addr + size > limit && !past_end_reported {
                past_end_reported = true;
                let what = match self.opts.rom_size {
                    Some(s) if s.words() < 4096 => {
                        format!("the {}-word ROM (last address {:03X})", s.words(), s.words() - 1)
                    }
                    _ => "the last address FFF".to_string(),
                };
                self.err_at(src, kw.col, format!("program runs past {what}"));
            }
            if addr + size <= 4096 {
                placed.push(Placed { src, addr: addr as u16, tmpl });
            }
            addr += size;
        }
        Layout { placed, labels_at, default_jump }
    }

    pub(super) fn namereg(&mut self, src: usize, kw: &Word, args: &[Arg], regs: &mut RegNames) {
        let [Arg::Word(old), Arg::Word(new)] = args else {
            return self.err_at(src, kw.col, "NAMEREG needs a register and a new name, e.g. NAMEREG s5, count");
        };
        let r = match regs.lookup(&old.text) {
            Ok(Some(r)) => r,
            Ok(None) => return self.err_at(src, old.col, format!("'{}' is not a register name", old.text)),
            Err(m) => return self.err_at(src, old.col, m),
        };
        if is_default_reg(&new.text) {
            if u8::from_str_radix(&new.text[1..], 16).ok() != Some(r) {
                return self.err_at(
                    src,
                    new.col,
                    format!("cannot rename s{r:X} to another register name '{}'", new.text),
                );
            }
        } else if let Err(m) = check_name(&new.text) {
            return self.err_at(src, new.col, m);
        } else if let Some(&i) = self.index.get(&new.text) {
            let at = self.symbols[i].loc.as_ref().map_or(" (a predefined name)".to_string(), |l| format!(" at {l}"));
            return self.err_at(src, new.col, format!("'{}' is already defined{at}", new.text));
        } else if regs.current.iter().any(|n| n == &new.text) {
            return self.err_at(src, new.col, format!("'{}' already names a register", new.text));
        }
        regs.current[r as usize] = new.text.clone();
    }

    /// Parse one instruction's operands.
    pub(super) fn instruction(&mut self, kw: &Word, args: &[Arg], regs: &RegNames) -> Result<Tmpl, ColError> {
        let upper = kw.text.to_ascii_uppercase();
        let reg = |a: &Arg| -> Result<Reg, ColError> {
            match a {
                Arg::Word(w) => match regs.lookup(&w.text) {
                    Ok(Some(r)) => Ok(Reg(r)),
                    Ok(None) => Err(ColError::new(w.col, format!("expected a register, found '{}'", w.text))),
                    Err(m) => Err(ColError::new(w.col, m)),
                },
                other => Err(ColError::new(other.col(), format!("expected a register, found '{}'", arg_text(other)))),
            }
        };
        let count = |n: usize, form: &str| -> Result<(), ColError> {
            if args.len() == n {
                Ok(())
            } else {
                Err(ColError::new(kw.col, format!("{upper} takes {form}")))
            }
        };
        let op2 = Op2::ALL.into_iter().find(|o| o.mnemonic() == upper);
        if let Some(op) = op2 {
            let form =
                if op.indirect() { "a register and a port or (sY)" } else { "a register and a register or constant" };
            count(2, &format!("two operands: {form}"))?;
            let sx = if op == Op2::Star {
                match &args[0] {
                    Arg::Word(w) if is_default_reg(&w.text) => Reg(u8::from_str_radix(&w.text[1..], 16).unwrap_or(0)),
                    a => {
                        return Err(ColError::new(
                            a.col(),
                            format!("STAR needs a default register name s0-sF first, found '{}'", arg_text(a)),
                        ))
                    }
                }
            } else {
                reg(&args[0])?
            };
            let second = match (&args[1], op.indirect()) {
                (Arg::Paren(ws, col), true) => match &ws[..] {
                    [w] => Opnd::Reg(reg(&Arg::Word(w.clone()))?),
                    _ => return Err(ColError::new(*col, "expected one register in '( )'")),
                },
                (Arg::Paren(_, col), false) => return Err(ColError::new(*col, format!("{upper} does not take '( )'"))),
                (Arg::Word(w), indirect) => match regs.lookup(&w.text) {
                    Ok(Some(_)) if indirect => {
                        return Err(ColError::new(w.col, format!("write a register port or address as '({})'", w.text)))
                    }
                    Ok(Some(r)) => Opnd::Reg(Reg(r)),
                    Err(m) => return Err(ColError::new(w.col, m)),
                    Ok(None) => Opnd::Val(value8(w)?),
                },
                (Arg::Str(w), _) => Opnd::Val(Val::Lit(char_value(&w.text).map_err(|m| ColError::new(w.col, m))?)),
                (a, _) => return Err(ColError::new(a.col(), format!("unexpected '{}'", arg_text(a)))),
            };
            return Ok(Tmpl::Op2(op, sx, second));
        }
        if let Some(s) = Shift::ALL.into_iter().find(|s| s.mnemonic() == upper) {
            count(1, "one register")?;
            return Ok(Tmpl::Fixed(Instr::Shift(s, reg(&args[0])?)));
        }
        let word_arg = |i: usize| -> Option<String> {
            match args.get(i) {
                Some(Arg::Word(w)) => Some(w.text.to_ascii_uppercase()),
                _ => None,
            }
        };
        let cond_of = |s: &str| Cond::ALL.into_iter().find(|c| c.name() == s);
        match upper.as_str() {
            "HWBUILD" => {
                count(1, "one register")?;
                Ok(Tmpl::Fixed(Instr::HwBuild(reg(&args[0])?)))
            }
            "JUMP" | "CALL" => {
                let (cond, target) = match args {
                    [Arg::Word(t)] => (None, t),
                    [Arg::Word(c), Arg::Word(t)] => match cond_of(&c.text.to_ascii_uppercase()) {
                        Some(cond) => (Some(cond), t),
                        None => {
                            return Err(ColError::new(
                                c.col,
                                format!("expected a condition Z, NZ, C or NC, found '{}'", c.text),
                            ))
                        }
                    },
                    [Arg::Paren(_, col), ..] => {
                        return Err(ColError::new(*col, format!("write {upper}@ (sX, sY) for a register target")))
                    }
                    _ => return Err(ColError::new(kw.col, format!("{upper} takes [condition,] target"))),
                };
                let a = address(target).map_err(|m| ColError::new(target.col, m))?;
                Ok(if upper == "JUMP" { Tmpl::Jump(cond, a) } else { Tmpl::Call(cond, a) })
            }
            "JUMP@" | "CALL@" => match args {
                [Arg::Paren(ws, _)] if ws.len() == 2 => {
                    let x = reg(&Arg::Word(ws[0].clone()))?;
                    let y = reg(&Arg::Word(ws[1].clone()))?;
                    Ok(Tmpl::Fixed(if upper == "JUMP@" { Instr::JumpAt(x, y) } else { Instr::CallAt(x, y) }))
                }
                _ => Err(ColError::new(kw.col, format!("{upper} takes (sX, sY)"))),
            },
            "RETURN" => match args {
                [] => Ok(Tmpl::Fixed(Instr::Return(None))),
                [Arg::Word(c)] => match cond_of(&c.text.to_ascii_uppercase()) {
                    Some(cond) => Ok(Tmpl::Fixed(Instr::Return(Some(cond)))),
                    None => {
                        Err(ColError::new(c.col, format!("expected a condition Z, NZ, C or NC, found '{}'", c.text)))
                    }
                },
                _ => Err(ColError::new(kw.col, "RETURN takes an optional condition (no comma)")),
            },
            "RETURNI" => match word_arg(0).as_deref() {
                Some("ENABLE") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::ReturnI(true))),
                Some("DISABLE") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::ReturnI(false))),
                _ => Err(ColError::new(kw.col, "RETURNI takes ENABLE or DISABLE")),
            },
            "ENABLE" | "DISABLE" => match word_arg(0).as_deref() {
                Some("INTERRUPT") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::Interrupt(upper == "ENABLE"))),
                _ => Err(ColError::new(kw.col, format!("write {upper} INTERRUPT"))),
            },
            "REGBANK" => match word_arg(0).as_deref() {
                Some("A") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::RegBank(false))),
                Some("B") if args.len() == 1 => Ok(Tmpl::Fixed(Instr::RegBank(true))),
                _ => Err(ColError::new(kw.col, "REGBANK takes A or B")),
            },
            "OUTPUTK" => {
                count(2, "a constant (or STRING$/TABLE#) and a port 0-F")?;
                let port = match &args[1] {
                    Arg::Word(w) => port4(w)?,
                    a => return Err(ColError::new(a.col(), format!("expected a port 0-F, found '{}'", arg_text(a)))),
                };
                match &args[0] {
                    Arg::Word(w) if w.text.ends_with('$') || w.text.ends_with('#') => {
                        let bytes = self.sequence(&w.text).map_err(|m| ColError::new(w.col, m))?;
                        Ok(Tmpl::OutputKSeq(bytes, w.text.clone(), port))
                    }
                    Arg::Word(w) => Ok(Tmpl::OutputK(value8(w)?, port)),
                    Arg::Str(w) => {
                        Ok(Tmpl::OutputK(Val::Lit(char_value(&w.text).map_err(|m| ColError::new(w.col, m))?), port))
                    }
                    a => Err(ColError::new(a.col(), format!("expected a constant, found '{}'", arg_text(a)))),
                }
            }
            "LOAD&RETURN" => {
                count(2, "a register and a constant (or STRING$/TABLE#)")?;
                let sx = reg(&args[0])?;
                match &args[1] {
                    Arg::Word(w) if w.text.ends_with('$') || w.text.ends_with('#') => {
                        let bytes = self.sequence(&w.text).map_err(|m| ColError::new(w.col, m))?;
                        Ok(Tmpl::LoadReturnSeq(sx, bytes, w.text.clone()))
                    }
                    Arg::Word(w) => Ok(Tmpl::LoadReturn(sx, value8(w)?)),
                    Arg::Str(w) => {
                        Ok(Tmpl::LoadReturn(sx, Val::Lit(char_value(&w.text).map_err(|m| ColError::new(w.col, m))?)))
                    }
                    a => Err(ColError::new(a.col(), format!("expected a constant, found '{}'", arg_text(a)))),
                }
            }
            "INST" => match args {
                [Arg::Word(w)] => match parse_num(&w.text, 5, 18) {
                    Some(Ok(v)) if v <= 0x3FFFF => Ok(Tmpl::Inst(v)),
                    Some(Ok(_)) => Err(ColError::new(w.col, format!("INST value '{}' is above 3FFFF", w.text))),
                    Some(Err(m)) => Err(ColError::new(w.col, m)),
                    None => Err(ColError::new(w.col, format!("INST needs a 5-digit hex word, found '{}'", w.text))),
                },
                _ => Err(ColError::new(kw.col, "INST takes one 18-bit word, e.g. INST 2EA7B")),
            },
            _ => Err(ColError::new(kw.col, format!("unknown instruction or directive '{}'", kw.text))),
        }
    }

    /// The bytes of a STRING$ or TABLE#, marking it used.
    pub(super) fn sequence(&mut self, name: &str) -> Result<Vec<u8>, String> {
        match self.index.get(name) {
            Some(&i) => {
                self.symbols[i].used = true;
                match &self.symbols[i].value {
                    SymbolValue::String(b) | SymbolValue::Table(b) => Ok(b.clone()),
                    _ => Err(format!("'{name}' is not a STRING or TABLE")),
                }
            }
            None => Err(format!("undefined {} '{name}'", if name.ends_with('$') { "STRING" } else { "TABLE" })),
        }
    }
}
