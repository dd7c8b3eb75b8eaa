//! botsim's course `debounce` and `sevensegment` (rtl/board/course/) against spec board.md
//! §2.1, and its Xilinx logic primitives (rtl/board/xilinx.v: LUTs, flip-flops, shift
//! registers, the carry chain) against their library guides' descriptions, clock by clock: a
//! behavioural model of the words (below, written from them, not from the Verilog) and the
//! Verilog under Icarus (a four-state simulator: an uninitialised register is `x` there, and
//! fails) see the same random inputs, and every output pin must agree at every clock.

use std::path::PathBuf;

use crate::common;
use common::{icarus, root};

/// A small deterministic generator (xorshift64*), so a failure names its seed.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// §2.1 debounce: the wrap counter, 22 four-bit shift registers entering at the top, outputs
/// set at 0000 and 1111.
struct Debounce {
    top: u64,
    count: u64,
    shift: [u8; 22],
    out: [bool; 22],
}

impl Debounce {
    fn new(top: u64, reset_polarity_low: bool) -> Debounce {
        let mut shift = [0u8; 22];
        if reset_polarity_low {
            shift[0] = 0b0001;
        }
        Debounce { top, count: 0, shift, out: [false; 22] }
    }
    /// One rising edge with `input` (bit 0..5 the buttons, 6..21 the switches).
    fn edge(&mut self, input: u32) {
        let tick = self.count == self.top;
        let mut out = self.out;
        for (i, o) in out.iter_mut().enumerate() {
            match self.shift[i] {
                0b0000 => *o = false,
                0b1111 => *o = true,
                _ => {}
            }
        }
        if tick {
            for (i, s) in self.shift.iter_mut().enumerate() {
                *s = (*s >> 1) | ((input >> i & 1) as u8) << 3;
            }
        }
        self.out = out;
        self.count = if tick { 0 } else { self.count + 1 };
    }
    fn pins(&self) -> u32 {
        self.out.iter().enumerate().map(|(i, &b)| (b as u32) << i).sum()
    }
}

/// The lit segments of a digit code (bit 0 = a ... bit 6 = g), §2.1 with §1's glyphs.
fn lit(code: u8) -> u8 {
    const HEX: [&str; 16] = [
        "abcdef", "bc", "abdeg", "abcdg", "bcfg", "acdfg", "acdefg", "abc", "abcdefg", "abcdfg", "abcefg", "cdefg",
        "adef", "bcdeg", "adefg", "aefg",
    ];
    let segs = match code {
        0..=15 => HEX[code as usize],
        16..=22 => ["a", "b", "c", "d", "e", "f", "g"][code as usize - 16],
        24 => "bcefg",
        25 => "def",
        26 => "abcefg",
        27 => "ef",
        28 => "eg",
        _ => "",
    };
    segs.bytes().map(|c| 1 << (c - b'a')).sum()
}

/// §2.1 sevensegment: the wrap counter (cleared by reset), the anodes walking at each tick,
/// each digit's pattern registered, `seg` registered from the lit digit's pattern.
struct SevenSegment {
    top: u64,
    digits: usize,
    count: u64,
    an: u8,
    patterns: [u8; 8],
    seg: u8,
}

impl SevenSegment {
    fn new(top: u64, digits: usize) -> SevenSegment {
        SevenSegment { top, digits, count: 0, an: 0, patterns: [0; 8], seg: 0 }
    }
    /// One rising edge with reset (active) and the digits' codes and points.
    fn edge(&mut self, reset: bool, codes: [u8; 8], dp: u8) {
        let tick = self.count == self.top;
        self.seg = match (0..8).find(|&i| self.an == !(1u8 << i)) {
            Some(i) => self.patterns[i],
            None => 0,
        };
        for (i, p) in self.patterns.iter_mut().enumerate() {
            *p = (!lit(codes[i]) & 0x7F) | if dp >> i & 1 == 1 { 0 } else { 0x80 };
        }
        if tick {
            self.an = match (0..self.digits - 1).find(|&i| self.an == !(1u8 << i)) {
                Some(i) => !(1u8 << (i + 1)),
                None => !1u8,
            };
        }
        self.count = if reset || tick { 0 } else { self.count + 1 };
    }
}

/// Run `tb` (a testbench module `tb` reading `in.mem`, one hex word per clock, and printing
/// one hex line per clock) with the course file `module` under Icarus; `None` without Icarus.
fn icarus(tb: &str, module: &str, inputs: &[String]) -> Option<Vec<String>> {
    icarus_with(tb, &[&format!("rtl/board/course/{module}")], inputs)
}

/// The same with botsim's files `files` (paths from the repository's root).
fn icarus_with(tb: &str, files: &[&str], inputs: &[String]) -> Option<Vec<String>> {
    if !icarus::installed() {
        return None;
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tb.v"), tb).unwrap();
    std::fs::write(dir.path().join("in.mem"), inputs.join("\n") + "\n").unwrap();
    let files: Vec<PathBuf> =
        std::iter::once(dir.path().join("tb.v")).chain(files.iter().map(|f| root().join(f))).collect();
    let out = icarus::simulate(dir.path(), "tb", &files, &[format!("+n={}", inputs.len())]);
    let lines: Vec<String> = out.lines().filter(|l| !l.starts_with("WARNING")).map(str::to_string).collect();
    assert_eq!(lines.len(), inputs.len(), "{out}");
    Some(lines)
}

/// A testbench module `tb` around `body` (the instance and its wires): each clock it takes
/// the next word of `in.mem` into `in` (`bits` wide), raises `clk`, and 1 ns later prints
/// `print` (a `$display` argument list). `setup` runs once before the first clock.
fn testbench(bits: u32, body: &str, setup: &str, print: &str) -> String {
    format!(
        "`timescale 1ns / 1ps
module tb;
    reg clk = 0;
    reg [{top}:0] in;
    reg [{top}:0] mem [0:65535];
    integer n, k;
{body}
    initial begin
        $readmemh(\"in.mem\", mem);
        if (!$value$plusargs(\"n=%d\", n)) n = 0;
{setup}        for (k = 0; k < n; k = k + 1) begin
            in = mem[k];
            #5 clk = 1;
            #1 $display({print});
            #4 clk = 0;
        end
        $finish;
    end
endmodule
",
        top = bits - 1
    )
}

/// Inputs that hold each value a random while (1 to `hold` clocks), changing a few bits.
fn inputs(rng: &mut Rng, n: usize, bits: u32, hold: u64) -> Vec<u64> {
    let mut v = rng.next() & ((1u64 << bits) - 1);
    let mut left = 0;
    (0..n)
        .map(|_| {
            if left == 0 {
                left = 1 + rng.below(hold);
                for _ in 0..1 + rng.below(3) {
                    v ^= 1 << rng.below(bits as u64);
                }
            }
            left -= 1;
            v
        })
        .collect()
}

fn debounce_case(seed: u64, params: &str, top: u64, reset_polarity_low: bool) {
    let tb = testbench(
        22,
        &format!(
            "    wire [5:0] pbtn_db;
    wire [15:0] swtch_db;
    debounce #({params}) DUT (.clk(clk), .pbtn_in(in[5:0]), .switch_in(in[21:6]), .pbtn_db(pbtn_db), .swtch_db(swtch_db));"
        ),
        "",
        "\"%h\", {swtch_db, pbtn_db}",
    );
    let mut rng = Rng(seed);
    let ins = inputs(&mut rng, 6000, 22, 12 * (top + 1));
    let text: Vec<String> = ins.iter().map(|v| format!("{v:06x}")).collect();
    let Some(got) = icarus(&tb, "debounce.v", &text) else { return };
    let mut m = Debounce::new(top, reset_polarity_low);
    for (k, (v, line)) in ins.iter().zip(&got).enumerate() {
        m.edge(*v as u32);
        let want = format!("{:06x}", m.pins());
        assert_eq!(line, &want, "debounce #({params}), seed {seed}: clock {k} (input {v:06x}) pins differ");
    }
}

#[test]
fn debounce_pins_follow_the_spec_at_every_clock() {
    // SIMULATE = 1: a tick every 6 clocks; another count; SIMULATE = 0 with a clock that makes
    // top_cnt small (100 Hz / 10 Hz - 1 = 9); the reset button active high.
    debounce_case(1, ".SIMULATE(1)", 5, true);
    debounce_case(2, ".SIMULATE(1), .SIMULATE_FREQUENCY_CNT(2)", 2, true);
    debounce_case(3, ".CLK_FREQUENCY_HZ(100), .DEBOUNCE_FREQUENCY_HZ(10)", 9, true);
    debounce_case(4, ".SIMULATE(1), .RESET_POLARITY_LOW(0)", 5, false);
}

fn sevensegment_case(seed: u64, params: &str, top: u64, polarity_low: bool, digits: usize) {
    let tb = testbench(
        49,
        &format!(
            "    wire [7:0] seg, an;
    wire [63:0] digits_out;
    sevensegment #({params}) DUT (.clk(clk), .reset(in[48]),
        .d0(in[4:0]), .d1(in[9:5]), .d2(in[14:10]), .d3(in[19:15]), .d4(in[24:20]), .d5(in[29:25]),
        .d6(in[34:30]), .d7(in[39:35]), .dp(in[47:40]), .seg(seg), .an(an), .digits_out(digits_out));"
        ),
        "",
        "\"%h %h %h\", an, seg, digits_out",
    );
    let mut rng = Rng(seed);
    let mut ins = inputs(&mut rng, 4000, 48, 40 * (top + 1));
    // The reset: released (at its inactive level) but for a few short presses.
    let inactive = if polarity_low { 1u64 } else { 0 };
    let mut pressed = 0;
    for v in ins.iter_mut() {
        if pressed == 0 && rng.below(500) == 0 {
            pressed = 1 + rng.below(3 * (top + 1));
        }
        let active = pressed > 0;
        pressed = pressed.saturating_sub(1);
        *v |= (inactive ^ active as u64) << 48;
    }
    let text: Vec<String> = ins.iter().map(|v| format!("{v:013x}")).collect();
    let Some(got) = icarus(&tb, "sevensegment.v", &text) else { return };
    let mut m = SevenSegment::new(top, digits);
    for (k, (v, line)) in ins.iter().zip(&got).enumerate() {
        let codes = std::array::from_fn(|i| (v >> (5 * i) & 0x1F) as u8);
        let reset = (v >> 48 & 1 == 1) != polarity_low;
        m.edge(reset, codes, (v >> 40) as u8);
        let want = format!("{:02x} {:02x} {:016x}", m.an, m.seg, 0);
        assert_eq!(line, &want, "sevensegment #({params}), seed {seed}: clock {k} (input {v:013x}) pins differ");
    }
}

#[test]
fn sevensegment_pins_follow_the_spec_at_every_clock() {
    sevensegment_case(11, ".SIMULATE(1)", 5, true, 8);
    sevensegment_case(12, ".SIMULATE(1), .RESET_POLARITY_LOW(0)", 5, false, 8);
    sevensegment_case(13, ".CLK_FREQUENCY_HZ(1000), .REFRESH_FREQUENCY_HZ(100)", 9, true, 8);
    // The Nexys3 version: four digits.
    sevensegment_case(14, ".SIMULATE(1), .DIGITS(4)", 5, true, 4);
}

#[test]
fn every_digit_code_shows_the_spec_glyph() {
    // Codes 0-31 on digit 0, the anodes held on it by a long tick, the point on odd codes.
    let ins: Vec<u64> = (0..32u64).flat_map(|c| [c | (c & 1) << 40 | 1 << 48; 4]).collect();
    let tb_params = ".CLK_FREQUENCY_HZ(1000000), .REFRESH_FREQUENCY_HZ(1)";
    let mut m = SevenSegment::new(999_999, 8);
    let text: Vec<String> = ins.iter().map(|v| format!("{v:013x}")).collect();
    let tb = testbench(
        49,
        &format!(
            "    wire [7:0] seg, an;
    sevensegment #({tb_params}) DUT (.clk(clk), .reset(in[48]), .d0(in[4:0]), .d1(5'd0), .d2(5'd0),
        .d3(5'd0), .d4(5'd0), .d5(5'd0), .d6(5'd0), .d7(5'd0), .dp(in[47:40]), .seg(seg), .an(an), .digits_out());"
        ),
        // Digit 0 lit: a first tick moves the anodes there.
        "        DUT.clk_cnt = 999999;\n",
        "\"%h %h\", an, seg",
    );
    let Some(got) = icarus(&tb, "sevensegment.v", &text) else { return };
    m.count = 999_999;
    for (k, (v, line)) in ins.iter().zip(&got).enumerate() {
        let codes = std::array::from_fn(|i| if i == 0 { (v & 0x1F) as u8 } else { 0 });
        m.edge(false, codes, (v >> 40) as u8);
        assert_eq!(line, &format!("{:02x} {:02x}", m.an, m.seg), "clock {k}, code {}", v & 0x1F);
    }
    // The spec's own words for a few codes (active low; seg[7] the point).
    let seg_of = |code: u64| {
        let k = ins.iter().rposition(|v| v & 0x1F == code).unwrap();
        u8::from_str_radix(got[k].split(' ').nth(1).unwrap(), 16).unwrap()
    };
    assert_eq!(seg_of(8), 0b1000_0000, "8: every segment, no point");
    assert_eq!(seg_of(11) & 0x7F, !0b111_1100 & 0x7F, "b: cdefg");
    assert_eq!(seg_of(24) & 0x7F, !0b111_0110 & 0x7F, "H: bcefg");
    assert_eq!(seg_of(23), 0x7F, "23: blank, its point lit");
    assert_eq!(seg_of(17), 0x7F & !0b10, "17: segment b alone, point lit");
}

/// The logic primitives' inputs, bit by bit, in one word a clock.
mod bits {
    pub const LUT: u32 = 0; // I0-I5: 0-5
    pub const F7: u32 = 6; // I0, I1, S: 6-8
    pub const CI: u32 = 9;
    pub const DI: u32 = 10; // 10-13
    pub const S: u32 = 14; // 14-17
    pub const CE: u32 = 18;
    pub const D: u32 = 19;
    pub const R: u32 = 20;
    pub const SET: u32 = 21;
    pub const CLR: u32 = 22;
    pub const PRE: u32 = 23;
    pub const A16: u32 = 24; // 24-27
    pub const A32: u32 = 28; // 28-32
}

/// The libraries guides' words: a LUT's output is INIT's bit its inputs address (I0 the
/// least significant; LUT6_2's O5 the lower half by I0-I4); MUXF7 and MUXCY pick I1 (CI)
/// when S is high, XORCY is CI xor LI; CARRY4's carry into bit n is the last bit's CO
/// (CI | CYINIT for bit 0), CO[n] that carry where S[n] else DI[n], O = S xor the carries in;
/// FD takes D, FDRE/FDSE take D while CE with R/S over it, FDCE/FDPE likewise with CLR/PRE
/// at once; SRL16E/SRLC32E shift D in at bit 0 while CE, Q the addressed bit, Q31 the last;
/// every register starts at INIT.
struct Primitives {
    lut6: u64,
    lut62: u64,
    lut3: u8,
    fd: bool,
    fdre: bool,
    fdse: bool,
    fdce: bool,
    fdpe: bool,
    srl16: u16,
    srl32: u32,
}

impl Primitives {
    /// One clock: the inputs `v` set, the rising edge, the outputs then.
    fn clock(&mut self, v: u64) -> u64 {
        use bits::*;
        let b = |k: u32| v >> k & 1 == 1;
        // At the edge (the asynchronous clear and preset act as soon as they are set).
        let (ce, d) = (b(CE), b(D));
        // A flip-flop with a clock enable, forced to `to` while `force` is set.
        let next = |q: bool, force: bool, to: bool| {
            if force {
                to
            } else if ce {
                d
            } else {
                q
            }
        };
        self.fd = d;
        self.fdre = next(self.fdre, b(R), false);
        self.fdse = next(self.fdse, b(SET), true);
        self.fdce = next(self.fdce, b(CLR), false);
        self.fdpe = next(self.fdpe, b(PRE), true);
        if ce {
            self.srl16 = self.srl16 << 1 | d as u16;
            self.srl32 = self.srl32 << 1 | d as u32;
        }
        // After it.
        let i6 = v >> LUT & 0x3F;
        let lut6 = self.lut6 >> i6 & 1;
        let (o6, o5) = (self.lut62 >> i6 & 1, self.lut62 >> (i6 & 0x1F) & 1);
        let lut3 = (self.lut3 >> (v & 7)) as u64 & 1;
        let f7 = if b(F7 + 2) { b(F7 + 1) } else { b(F7) } as u64;
        let muxcy = if b(S) { b(CI) } else { b(DI) } as u64;
        let xorcy = (b(CI) ^ b(S)) as u64;
        let (mut carry, mut co, mut o) = (b(CI), 0u64, 0u64);
        for n in 0..4 {
            o |= ((b(S + n) ^ carry) as u64) << n;
            carry = if b(S + n) { carry } else { b(DI + n) };
            co |= (carry as u64) << n;
        }
        let srl16 = (self.srl16 >> (v >> A16 & 0xF)) as u64 & 1;
        let srl32 = (self.srl32 >> (v >> A32 & 0x1F)) as u64 & 1;
        let q31 = (self.srl32 >> 31) as u64;
        let flops = [self.fd, self.fdre, self.fdse, self.fdce, self.fdpe]
            .iter()
            .enumerate()
            .fold(0, |a, (k, f)| a | (*f as u64) << k);
        lut6 | o6 << 1
            | o5 << 2
            | lut3 << 3
            | f7 << 4
            | muxcy << 5
            | xorcy << 6
            | co << 7
            | o << 11
            | flops << 15
            | srl16 << 20
            | srl32 << 21
            | q31 << 22
    }
}

#[test]
fn the_xilinx_logic_primitives_follow_their_library_guides_at_every_clock() {
    for seed in [1u64, 2, 3] {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ seed.wrapping_mul(0x1234_5678_9ABC_DEF1));
        let (lut6, lut62, lut3) = (rng.next(), rng.next(), rng.next() as u8);
        let (srl16, srl32) = (rng.next() as u16, rng.next() as u32);
        let body = format!(
            "    wire [22:0] out;
    LUT6 #(.INIT(64'h{lut6:016X})) L6 (.O(out[0]), .I0(in[0]), .I1(in[1]), .I2(in[2]), .I3(in[3]), .I4(in[4]), .I5(in[5]));
    LUT6_2 #(.INIT(64'h{lut62:016X})) L62 (.O6(out[1]), .O5(out[2]), .I0(in[0]), .I1(in[1]), .I2(in[2]), .I3(in[3]), .I4(in[4]), .I5(in[5]));
    LUT3 #(.INIT(8'h{lut3:02X})) L3 (.O(out[3]), .I0(in[0]), .I1(in[1]), .I2(in[2]));
    MUXF7 M7 (.O(out[4]), .I0(in[6]), .I1(in[7]), .S(in[8]));
    MUXCY MC (.O(out[5]), .CI(in[9]), .DI(in[10]), .S(in[14]));
    XORCY XC (.O(out[6]), .CI(in[9]), .LI(in[14]));
    CARRY4 C4 (.CO(out[10:7]), .O(out[14:11]), .CI(in[9]), .CYINIT(1'b0), .DI(in[13:10]), .S(in[17:14]));
    FD F0 (.Q(out[15]), .C(clk), .D(in[19]));
    FDRE F1 (.Q(out[16]), .C(clk), .CE(in[18]), .D(in[19]), .R(in[20]));
    FDSE F2 (.Q(out[17]), .C(clk), .CE(in[18]), .D(in[19]), .S(in[21]));
    FDCE F3 (.Q(out[18]), .C(clk), .CE(in[18]), .D(in[19]), .CLR(in[22]));
    FDPE F4 (.Q(out[19]), .C(clk), .CE(in[18]), .D(in[19]), .PRE(in[23]));
    SRL16E #(.INIT(16'h{srl16:04X})) S16 (.Q(out[20]), .A0(in[24]), .A1(in[25]), .A2(in[26]), .A3(in[27]), .CE(in[18]), .CLK(clk), .D(in[19]));
    SRLC32E #(.INIT(32'h{srl32:08X})) S32 (.Q(out[21]), .Q31(out[22]), .A(in[32:28]), .CE(in[18]), .CLK(clk), .D(in[19]));
"
        );
        let tb = testbench(33, &body, "", "\"%h\", out");
        // Mostly quiet resets, so the registers hold and shift.
        let v: Vec<u64> = (0..3000)
            .map(|_| {
                let mut x = rng.next() & ((1 << 33) - 1);
                for k in [bits::R, bits::SET, bits::CLR, bits::PRE] {
                    if rng.below(8) != 0 {
                        x &= !(1 << k);
                    }
                }
                x
            })
            .collect();
        let text: Vec<String> = v.iter().map(|x| format!("{x:09X}")).collect();
        let Some(got) = icarus_with(&tb, &["rtl/board/xilinx.v", "rtl/board/botsim_clkgen.v"], &text) else { return };
        let mut p =
            Primitives { lut6, lut62, lut3, fd: false, fdre: false, fdse: true, fdce: false, fdpe: true, srl16, srl32 };
        for (k, (x, line)) in v.iter().zip(&got).enumerate() {
            let want = p.clock(*x);
            assert_eq!(
                u64::from_str_radix(line.trim(), 16).ok(),
                Some(want),
                "seed {seed}, clock {k}: inputs {x:09X}, got {line}, want {want:06X}"
            );
        }
    }
}
