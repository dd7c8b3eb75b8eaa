//! The KCPSM6 instruction set as one typed value: [`Instr`], with [`Instr::encode`] and
//! [`Instr::decode`] shared by the assembler, the disassembler and the tests.
//!
//! Only the canonical encodings (the words an assembler emits) decode to an [`Instr`]; any
//! other 18-bit word still *executes* (the ISS decodes raw bits the way the hardware does) but
//! is written as `INST hhhhh` by the disassembler.
//!
//! ```
//! use kcpsm6::isa::{Instr, Op2, Operand, Reg};
//! let add = Instr::Op2(Op2::Add, Reg(1), Operand::Const(0x2A));
//! assert_eq!(add.encode(), 0x1112A);
//! assert_eq!(Instr::decode(0x1112A), Some(add));
//! assert_eq!(add.to_string(), "ADD s1, 2A");
//! ```

use std::fmt;

/// Largest 18-bit instruction word.
pub const WORD_MASK: u32 = 0x3_FFFF;
/// Number of words in the 12-bit program address space.
pub const ROM_WORDS: usize = 4096;

/// What the hardware does with a word: the meaning of its 6-bit opcode `[17:12]` (spec §1.2,
/// §1.7). Every opcode has one, so every 18-bit word executes; the four undefined opcodes are
/// [`Opcode::Nop`]. The register/constant forms of a two-operand instruction share a name (bit
/// 12 selects the constant), as do the conditional and unconditional control-flow forms (see
/// [`Cond::of`]).
///
/// ```
/// use kcpsm6::isa::{Cond, Opcode, PortKind};
/// assert_eq!(Opcode::of(0x1112A), Opcode::Add);
/// assert_eq!(Opcode::of(0x36004), Opcode::Jump);
/// assert_eq!(Cond::of(0x36004), Some(Cond::NZ));
/// assert_eq!(Opcode::of(0x2A000).strobe(), Some(PortKind::KWrite));
/// assert_eq!(Opcode::of(0x23000), Opcode::Nop);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Opcode {
    Load,
    And,
    Or,
    Xor,
    Input,
    Fetch,
    Test,
    TestCy,
    Add,
    AddCy,
    /// Shifts, rotates and HWBUILD (opcodes 14 and 15).
    Shift,
    Star,
    Sub,
    SubCy,
    Compare,
    CompareCy,
    Call,
    LoadReturn,
    Jump,
    CallAt,
    Return,
    JumpAt,
    /// ENABLE / DISABLE INTERRUPT.
    Interrupt,
    ReturnI,
    /// OUTPUTK and the undocumented opcode 2A.
    OutputK,
    Output,
    Store,
    RegBank,
    /// The undefined opcodes 23, 27, 33, 3B, 3F.
    Nop,
}

/// The opcode table, indexed by `[17:12]`: the single place that numbers the instructions.
const OPCODES: [Opcode; 64] = {
    use Opcode::*;
    [
        Load, Load, And, And, Or, Or, Xor, Xor, Input, Input, Fetch, Fetch, Test, Test, TestCy, TestCy, // 00-0F
        Add, Add, AddCy, AddCy, Shift, Shift, Star, Star, Sub, Sub, SubCy, SubCy, Compare, Compare, CompareCy,
        CompareCy, // 10-1F
        Call, LoadReturn, Jump, Nop, CallAt, Return, JumpAt, Nop, Interrupt, ReturnI, OutputK, OutputK, Output, Output,
        Store, Store, // 20-2F
        Call, Return, Jump, Nop, Call, Return, Jump, RegBank, Call, Return, Jump, Nop, Call, Return, Jump,
        Nop, // 30-3F
    ]
};

impl Opcode {
    /// The opcode of an 18-bit word.
    #[inline]
    pub fn of(word: u32) -> Opcode {
        OPCODES[(word >> 12 & 63) as usize]
    }

    /// Writes sX (STAR: the other bank's) in the second cycle.
    pub fn writes_register(self) -> bool {
        use Opcode::*;
        matches!(self, Load | And | Or | Xor | Input | Fetch | Add | AddCy | Shift | Star | Sub | SubCy | LoadReturn)
    }

    /// Writes C and Z in the second cycle (RETURNI: the flags saved on the stack).
    pub fn writes_flags(self) -> bool {
        use Opcode::*;
        matches!(
            self,
            And | Or | Xor | Test | TestCy | Add | AddCy | Shift | Sub | SubCy | Compare | CompareCy | ReturnI
        )
    }

    /// The CY forms (TESTCY, ADDCY, SUBCY, COMPARECY): they take the carry in and chain Z,
    /// `Z = (r == 0) & Zold` (§1.4).
    pub fn carry_form(self) -> bool {
        matches!(self, Opcode::TestCy | Opcode::AddCy | Opcode::SubCy | Opcode::CompareCy)
    }

    /// The strobe the instruction raises in its second cycle.
    pub fn strobe(self) -> Option<PortKind> {
        match self {
            Opcode::Input => Some(PortKind::Read),
            Opcode::Output => Some(PortKind::Write),
            Opcode::OutputK => Some(PortKind::KWrite),
            _ => None,
        }
    }

    /// Pushes the call stack when taken.
    pub fn pushes(self) -> bool {
        matches!(self, Opcode::Call | Opcode::CallAt)
    }

    /// Pops the call stack when taken.
    pub fn pops(self) -> bool {
        matches!(self, Opcode::Return | Opcode::LoadReturn | Opcode::ReturnI)
    }
}

/// Which strobe a port access raises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PortKind {
    /// `read_strobe` (INPUT).
    Read,
    /// `write_strobe` (OUTPUT).
    Write,
    /// `k_write_strobe` (OUTPUTK and the undocumented opcode 2A).
    KWrite,
}

/// A register `s0`..`sF` of the active bank (the bank is machine state, not part of the name).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Reg(pub u8);

impl fmt::Display for Reg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "s{:X}", self.0 & 15)
    }
}

/// The second operand of a two-operand instruction: a register or an 8-bit constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Operand {
    Reg(Reg),
    Const(u8),
}

/// Two-operand instructions: the even opcode takes `sY`, the odd one (`base + 1`) a constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Op2 {
    Load,
    And,
    Or,
    Xor,
    Input,
    Fetch,
    Test,
    TestCy,
    Add,
    AddCy,
    Star,
    Sub,
    SubCy,
    Compare,
    CompareCy,
    Output,
    Store,
}

impl Op2 {
    /// Every two-operand instruction, in opcode order.
    pub const ALL: [Op2; 17] = [
        Op2::Load,
        Op2::And,
        Op2::Or,
        Op2::Xor,
        Op2::Input,
        Op2::Fetch,
        Op2::Test,
        Op2::TestCy,
        Op2::Add,
        Op2::AddCy,
        Op2::Star,
        Op2::Sub,
        Op2::SubCy,
        Op2::Compare,
        Op2::CompareCy,
        Op2::Output,
        Op2::Store,
    ];

    /// The hardware opcode this instruction executes as.
    pub fn opcode(self) -> Opcode {
        match self {
            Op2::Load => Opcode::Load,
            Op2::And => Opcode::And,
            Op2::Or => Opcode::Or,
            Op2::Xor => Opcode::Xor,
            Op2::Input => Opcode::Input,
            Op2::Fetch => Opcode::Fetch,
            Op2::Test => Opcode::Test,
            Op2::TestCy => Opcode::TestCy,
            Op2::Add => Opcode::Add,
            Op2::AddCy => Opcode::AddCy,
            Op2::Star => Opcode::Star,
            Op2::Sub => Opcode::Sub,
            Op2::SubCy => Opcode::SubCy,
            Op2::Compare => Opcode::Compare,
            Op2::CompareCy => Opcode::CompareCy,
            Op2::Output => Opcode::Output,
            Op2::Store => Opcode::Store,
        }
    }

    /// The register-form opcode number (`[17:12]`, from the opcode table); the constant form
    /// is this plus one.
    pub fn base_opcode(self) -> u32 {
        let op = self.opcode();
        OPCODES.iter().position(|&o| o == op).expect("every Op2 is in the opcode table") as u32
    }

    pub fn mnemonic(self) -> &'static str {
        match self {
            Op2::Load => "LOAD",
            Op2::And => "AND",
            Op2::Or => "OR",
            Op2::Xor => "XOR",
            Op2::Input => "INPUT",
            Op2::Fetch => "FETCH",
            Op2::Test => "TEST",
            Op2::TestCy => "TESTCY",
            Op2::Add => "ADD",
            Op2::AddCy => "ADDCY",
            Op2::Star => "STAR",
            Op2::Sub => "SUB",
            Op2::SubCy => "SUBCY",
            Op2::Compare => "COMPARE",
            Op2::CompareCy => "COMPARECY",
            Op2::Output => "OUTPUT",
            Op2::Store => "STORE",
        }
    }

    /// INPUT, OUTPUT, FETCH and STORE write their register operand as `(sY)`.
    pub fn indirect(self) -> bool {
        matches!(self, Op2::Input | Op2::Output | Op2::Fetch | Op2::Store)
    }

    fn from_opcode(op: Opcode) -> Option<Op2> {
        Op2::ALL.into_iter().find(|o| o.opcode() == op)
    }
}

/// Shift and rotate instructions (opcode 14, sub-code in `[7:0]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shift {
    Sl0,
    Sl1,
    Slx,
    Sla,
    Rl,
    Sr0,
    Sr1,
    Srx,
    Sra,
    Rr,
}

impl Shift {
    pub const ALL: [Shift; 10] = [
        Shift::Sl0,
        Shift::Sl1,
        Shift::Slx,
        Shift::Sla,
        Shift::Rl,
        Shift::Sr0,
        Shift::Sr1,
        Shift::Srx,
        Shift::Sra,
        Shift::Rr,
    ];

    pub fn code(self) -> u32 {
        match self {
            Shift::Sl0 => 0x06,
            Shift::Sl1 => 0x07,
            Shift::Slx => 0x04,
            Shift::Sla => 0x00,
            Shift::Rl => 0x02,
            Shift::Sr0 => 0x0E,
            Shift::Sr1 => 0x0F,
            Shift::Srx => 0x0A,
            Shift::Sra => 0x08,
            Shift::Rr => 0x0C,
        }
    }

    pub fn mnemonic(self) -> &'static str {
        match self {
            Shift::Sl0 => "SL0",
            Shift::Sl1 => "SL1",
            Shift::Slx => "SLX",
            Shift::Sla => "SLA",
            Shift::Rl => "RL",
            Shift::Sr0 => "SR0",
            Shift::Sr1 => "SR1",
            Shift::Srx => "SRX",
            Shift::Sra => "SRA",
            Shift::Rr => "RR",
        }
    }
}

/// Branch conditions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cond {
    Z,
    NZ,
    C,
    NC,
}

impl Cond {
    pub const ALL: [Cond; 4] = [Cond::Z, Cond::NZ, Cond::C, Cond::NC];

    /// The condition of a control-flow word: bits `[17:16]` = 11 make it conditional, bits
    /// `[15:14]` name it. (REGBANK, 37, has the same bits; its condition is not used.)
    #[inline]
    pub fn of(word: u32) -> Option<Cond> {
        (word >> 16 & 3 == 3).then(|| Cond::ALL[(word >> 14 & 3) as usize])
    }

    /// Whether a control-flow word acts with the flags `c`, `z`: always when unconditional.
    #[inline]
    pub fn taken(word: u32, c: bool, z: bool) -> bool {
        Cond::of(word).map_or(true, |cond| cond.holds(c, z))
    }

    /// Whether the condition holds for the flags `c`, `z`.
    #[inline]
    pub fn holds(self, c: bool, z: bool) -> bool {
        match self {
            Cond::Z => z,
            Cond::NZ => !z,
            Cond::C => c,
            Cond::NC => !c,
        }
    }

    /// Bits `[15:14]` of a conditional control-flow word.
    fn bits(self) -> u32 {
        match self {
            Cond::Z => 0,
            Cond::NZ => 1,
            Cond::C => 2,
            Cond::NC => 3,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Cond::Z => "Z",
            Cond::NZ => "NZ",
            Cond::C => "C",
            Cond::NC => "NC",
        }
    }
}

/// One KCPSM6 instruction in canonical form.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Instr {
    /// LOAD, AND, ..., STORE: `op sX, sY|kk` (INPUT/OUTPUT/FETCH/STORE print `(sY)`).
    Op2(Op2, Reg, Operand),
    Shift(Shift, Reg),
    HwBuild(Reg),
    /// `OUTPUTK kk, p`.
    OutputK(u8, u8),
    Jump(Option<Cond>, u16),
    Call(Option<Cond>, u16),
    Return(Option<Cond>),
    /// `JUMP@ (sX, sY)`.
    JumpAt(Reg, Reg),
    /// `CALL@ (sX, sY)`.
    CallAt(Reg, Reg),
    /// `LOAD&RETURN sX, kk`.
    LoadReturn(Reg, u8),
    /// `RETURNI ENABLE` (true) / `RETURNI DISABLE` (false).
    ReturnI(bool),
    /// `ENABLE INTERRUPT` (true) / `DISABLE INTERRUPT` (false).
    Interrupt(bool),
    /// `REGBANK A` (false) / `REGBANK B` (true).
    RegBank(bool),
}

impl Instr {
    /// The 18-bit word.
    pub fn encode(self) -> u32 {
        let x = |r: Reg| (r.0 as u32 & 15) << 8;
        let a = |addr: u16| addr as u32 & 0xFFF;
        match self {
            Instr::Op2(op, sx, Operand::Reg(sy)) => op.base_opcode() << 12 | x(sx) | (sy.0 as u32 & 15) << 4,
            Instr::Op2(op, sx, Operand::Const(k)) => (op.base_opcode() + 1) << 12 | x(sx) | k as u32,
            Instr::Shift(s, sx) => 0x14000 | x(sx) | s.code(),
            Instr::HwBuild(sx) => 0x14080 | x(sx),
            Instr::OutputK(k, p) => 0x2B000 | (k as u32) << 4 | (p as u32 & 15),
            Instr::Jump(None, t) => 0x22000 | a(t),
            Instr::Call(None, t) => 0x20000 | a(t),
            Instr::Return(None) => 0x25000,
            Instr::Jump(Some(c), t) => 0x32000 | c.bits() << 14 | a(t),
            Instr::Call(Some(c), t) => 0x30000 | c.bits() << 14 | a(t),
            Instr::Return(Some(c)) => 0x31000 | c.bits() << 14,
            Instr::JumpAt(sx, sy) => 0x26000 | x(sx) | (sy.0 as u32 & 15) << 4,
            Instr::CallAt(sx, sy) => 0x24000 | x(sx) | (sy.0 as u32 & 15) << 4,
            Instr::LoadReturn(sx, k) => 0x21000 | x(sx) | k as u32,
            Instr::ReturnI(e) => 0x29000 | e as u32,
            Instr::Interrupt(e) => 0x28000 | e as u32,
            Instr::RegBank(b) => 0x37000 | b as u32,
        }
    }

    /// The instruction whose canonical encoding is `word`, or `None` for any other word
    /// (undefined opcodes, undocumented variants, non-zero don't-care bits).
    pub fn decode(word: u32) -> Option<Instr> {
        if word > WORD_MASK {
            return None;
        }
        let sx = Reg((word >> 8 & 15) as u8);
        let sy = Reg((word >> 4 & 15) as u8);
        let kk = (word & 0xFF) as u8;
        let aaa = (word & 0xFFF) as u16;
        let cond = Cond::of(word);
        let instr = match Opcode::of(word) {
            Opcode::Shift if kk == 0x80 => Instr::HwBuild(sx),
            Opcode::Shift => Instr::Shift(Shift::ALL.into_iter().find(|s| s.code() == kk as u32)?, sx),
            Opcode::OutputK => Instr::OutputK((word >> 4 & 0xFF) as u8, (word & 15) as u8),
            Opcode::Call => Instr::Call(cond, aaa),
            Opcode::Jump => Instr::Jump(cond, aaa),
            Opcode::Return => Instr::Return(cond),
            Opcode::CallAt => Instr::CallAt(sx, sy),
            Opcode::JumpAt => Instr::JumpAt(sx, sy),
            Opcode::LoadReturn => Instr::LoadReturn(sx, kk),
            Opcode::Interrupt => Instr::Interrupt(word & 1 == 1),
            Opcode::ReturnI => Instr::ReturnI(word & 1 == 1),
            Opcode::RegBank => Instr::RegBank(word & 1 == 1),
            Opcode::Nop => return None,
            op => {
                let o = Op2::from_opcode(op)?;
                if word & 1 << 12 != 0 {
                    Instr::Op2(o, sx, Operand::Const(kk))
                } else {
                    Instr::Op2(o, sx, Operand::Reg(sy))
                }
            }
        };
        (instr.encode() == word).then_some(instr)
    }

    /// The mnemonic as the assembler spells it.
    pub fn mnemonic(self) -> &'static str {
        match self {
            Instr::Op2(op, ..) => op.mnemonic(),
            Instr::Shift(s, _) => s.mnemonic(),
            Instr::HwBuild(_) => "HWBUILD",
            Instr::OutputK(..) => "OUTPUTK",
            Instr::Jump(..) => "JUMP",
            Instr::Call(..) => "CALL",
            Instr::Return(_) => "RETURN",
            Instr::JumpAt(..) => "JUMP@",
            Instr::CallAt(..) => "CALL@",
            Instr::LoadReturn(..) => "LOAD&RETURN",
            Instr::ReturnI(_) => "RETURNI",
            Instr::Interrupt(true) => "ENABLE",
            Instr::Interrupt(false) => "DISABLE",
            Instr::RegBank(_) => "REGBANK",
        }
    }
}

/// Canonical assembly text, re-assemblable to the same word.
impl fmt::Display for Instr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let m = self.mnemonic();
        match *self {
            Instr::Op2(op, sx, Operand::Reg(sy)) if op.indirect() => write!(f, "{m} {sx}, ({sy})"),
            Instr::Op2(_, sx, Operand::Reg(sy)) => write!(f, "{m} {sx}, {sy}"),
            Instr::Op2(_, sx, Operand::Const(k)) => write!(f, "{m} {sx}, {k:02X}"),
            Instr::Shift(_, sx) | Instr::HwBuild(sx) => write!(f, "{m} {sx}"),
            Instr::OutputK(k, p) => write!(f, "{m} {k:02X}, {p:X}"),
            Instr::Jump(None, t) | Instr::Call(None, t) => write!(f, "{m} {t:03X}"),
            Instr::Jump(Some(c), t) | Instr::Call(Some(c), t) => {
                write!(f, "{m} {}, {t:03X}", c.name())
            }
            Instr::Return(None) => write!(f, "{m}"),
            Instr::Return(Some(c)) => write!(f, "{m} {}", c.name()),
            Instr::JumpAt(sx, sy) | Instr::CallAt(sx, sy) => write!(f, "{m} ({sx}, {sy})"),
            Instr::LoadReturn(sx, k) => write!(f, "{m} {sx}, {k:02X}"),
            Instr::ReturnI(e) => write!(f, "{m} {}", if e { "ENABLE" } else { "DISABLE" }),
            Instr::Interrupt(_) => write!(f, "{m} INTERRUPT"),
            Instr::RegBank(b) => write!(f, "{m} {}", if b { "B" } else { "A" }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spec_encodings() {
        let s = |n| Reg(n);
        let cases = [
            (Instr::Op2(Op2::Load, s(0), Operand::Reg(s(0))), 0x00000),
            (Instr::Op2(Op2::Output, s(0), Operand::Const(0x56)), 0x2D056),
            (Instr::Op2(Op2::Star, s(3), Operand::Const(0x7F)), 0x1737F),
            (Instr::Jump(Some(Cond::Z), 0x123), 0x32123),
            (Instr::Jump(Some(Cond::NZ), 0x123), 0x36123),
            (Instr::Jump(Some(Cond::C), 0x123), 0x3A123),
            (Instr::Jump(Some(Cond::NC), 0x123), 0x3E123),
            (Instr::Call(Some(Cond::NC), 0x0FF), 0x3C0FF),
            (Instr::Return(Some(Cond::Z)), 0x31000),
            (Instr::Return(Some(Cond::NZ)), 0x35000),
            (Instr::Return(Some(Cond::C)), 0x39000),
            (Instr::Return(Some(Cond::NC)), 0x3D000),
            (Instr::OutputK(0xAB, 0xC), 0x2BABC),
            (Instr::HwBuild(s(5)), 0x14580),
            (Instr::Shift(Shift::Sra, s(2)), 0x14208),
            (Instr::RegBank(true), 0x37001),
            (Instr::ReturnI(true), 0x29001),
            (Instr::Interrupt(false), 0x28000),
        ];
        for (i, w) in cases {
            assert_eq!(i.encode(), w, "{i}");
            assert_eq!(Instr::decode(w), Some(i), "{w:05X}");
        }
    }

    #[test]
    fn non_canonical_words_do_not_decode() {
        for w in [0x23000, 0x27000, 0x3B000, 0x3F000, 0x15006, 0x2A123, 0x00011, 0x14001, 0x14081] {
            assert_eq!(Instr::decode(w), None, "{w:05X}");
        }
    }

    #[test]
    fn decode_encode_is_identity_on_every_word() {
        for w in 0..=WORD_MASK {
            if let Some(i) = Instr::decode(w) {
                assert_eq!(i.encode(), w);
            }
        }
    }
}
