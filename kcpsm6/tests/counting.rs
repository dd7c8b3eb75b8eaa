//! Firmware that counts (kcpsm6::counting), against the ISS: random loops of counting chains,
//! nested delays, scratch-pad counts and instructions that spoil them. Wherever a period is
//! proven to count, the core after any number of periods within its room is the simulated one;
//! loops built only to count are proven so.

use kcpsm6::asm::assemble_str;
use kcpsm6::counting::CountingPeriod;
use kcpsm6::iss::{Config, Cpu, NullBus, Pins};
use proptest::prelude::*;

/// One piece of a loop body.
#[derive(Clone, Debug)]
enum Piece {
    /// A chain that counts: ADD/SUB on the first register, the CY form on the others.
    Count { add: bool, regs: Vec<u8>, k: Vec<u8> },
    /// A COMPARE chain on the same registers.
    Compare { regs: Vec<u8>, k: Vec<u8> },
    /// A count in the scratch pad: FETCH, ADD/SUB, STORE (through sA).
    Scratch { add: bool, at: u8, k: u8 },
    /// An inner delay (s9, reloaded).
    Inner { n: u8 },
    /// Work on the invariant registers sB-sE: LOAD, TEST, OUTPUT.
    Plain { op: u8, reg: u8, k: u8 },
    /// Anything on any register (may spoil a count).
    Noise { word: String },
}

impl Piece {
    fn text(&self, at: usize) -> String {
        match self {
            Piece::Count { add, regs, k } => regs
                .iter()
                .zip(k)
                .enumerate()
                .map(|(i, (r, k))| {
                    let op = match (add, i) {
                        (true, 0) => "ADD",
                        (true, _) => "ADDCY",
                        (false, 0) => "SUB",
                        (false, _) => "SUBCY",
                    };
                    format!("{op} s{r}, {k:02X}\n")
                })
                .collect(),
            Piece::Compare { regs, k } => regs
                .iter()
                .zip(k)
                .enumerate()
                .map(|(i, (r, k))| format!("{} s{r}, {k:02X}\n", if i == 0 { "COMPARE" } else { "COMPARECY" }))
                .collect(),
            Piece::Scratch { add, at, k } => {
                format!("FETCH sA, {at:02X}\n{} sA, {k:02X}\nSTORE sA, {at:02X}\n", if *add { "ADD" } else { "SUB" })
            }
            Piece::Inner { n } => format!("LOAD s9, {n:02X}\ninner_{at}: SUB s9, 01\nJUMP NZ, inner_{at}\n"),
            Piece::Plain { op, reg, k } => {
                let r = 0xB + reg % 4;
                match op % 3 {
                    0 => format!("LOAD s{r:X}, {k:02X}\n"),
                    1 => format!("TEST s{r:X}, {k:02X}\n"),
                    _ => format!("OUTPUT s{r:X}, {k:02X}\n"),
                }
            }
            Piece::Noise { word } => format!("{word}\n"),
        }
    }
}

fn count_regs() -> impl Strategy<Value = Vec<u8>> {
    // Distinct registers of s0-s3, low byte first.
    prop::sample::subsequence(vec![0u8, 1, 2, 3], 1..=3).prop_shuffle()
}

fn piece(noise: bool) -> impl Strategy<Value = Piece> {
    let count = (any::<bool>(), count_regs(), prop::collection::vec(0u8..4, 3))
        .prop_map(|(add, regs, k)| Piece::Count { add, k: k[..regs.len()].to_vec(), regs });
    let compare = (count_regs(), prop::collection::vec(any::<u8>(), 3))
        .prop_map(|(regs, k)| Piece::Compare { k: k[..regs.len()].to_vec(), regs });
    let scratch = (any::<bool>(), 0u8..4, 1u8..3).prop_map(|(add, at, k)| Piece::Scratch { add, at, k });
    let inner = (1u8..6).prop_map(|n| Piece::Inner { n });
    let plain = (any::<u8>(), any::<u8>(), any::<u8>()).prop_map(|(op, reg, k)| Piece::Plain { op, reg, k });
    let noise_word = (0usize..8, 0u8..16, any::<u8>()).prop_map(|(op, r, k)| {
        let ops = ["AND", "OR", "XOR", "SL0", "SR0", "RL", "LOAD", "OUTPUT"];
        let word = match ops[op] {
            "SL0" | "SR0" | "RL" => format!("{} s{r:X}", ops[op]),
            o => format!("{o} s{r:X}, {k:02X}"),
        };
        Piece::Noise { word }
    });
    if noise {
        prop_oneof![4 => count, 2 => compare, 2 => scratch, 1 => inner, 2 => plain, 3 => noise_word].boxed()
    } else {
        prop_oneof![4 => count, 2 => compare, 2 => scratch, 1 => inner, 2 => plain].boxed()
    }
}

/// A loop: initial values, the body, and the branch back on the flags the body leaves.
#[derive(Clone, Debug)]
struct Loop {
    init: Vec<u8>,
    body: Vec<Piece>,
    cond: &'static str,
    warm: u64,
}

impl Loop {
    fn program(&self) -> Vec<u32> {
        // At 0C0-0FF: the jumps show sC-sF on port_id (bits 7:4 of their targets), which
        // nothing here counts in.
        let mut src = String::from("JUMP start\nADDRESS 0C0\nstart: ");
        for (r, v) in self.init.iter().enumerate().take(4) {
            src += &format!("LOAD s{r}, {v:02X}\n");
        }
        for (at, v) in self.init[4..].iter().enumerate() {
            src += &format!("LOAD sA, {v:02X}\nSTORE sA, {at:02X}\n");
        }
        src += "again: ";
        for (i, p) in self.body.iter().enumerate() {
            src += &p.text(i);
        }
        src += &format!("JUMP {}again\nhalt: JUMP halt\n", self.cond);
        let p = assemble_str(&src).unwrap_or_else(|e| panic!("{src}\n{e:?}"));
        assert!(p.image.words[0x100..].iter().all(|&w| w == 0), "the loop must end below 100");
        p.image.words.to_vec()
    }
}

fn a_loop(noise: bool) -> impl Strategy<Value = Loop> {
    (
        prop::collection::vec(any::<u8>(), 8),
        prop::collection::vec(piece(noise), 1..6),
        prop::sample::select(vec!["", "NZ, ", "Z, ", "C, ", "NC, "]),
        0u64..400,
    )
        .prop_map(|(init, body, cond, warm)| Loop { init, body, cond, warm })
}

/// The first period the proof accepts within `limit` cycles of the mark, if any (the mark
/// after `warm` cycles), with the mark and the core at its end.
fn first_counting(words: &[u32], warm: u64, limit: u64) -> Option<(CountingPeriod, Cpu)> {
    let mut cpu = Cpu::new(Config::default(), words);
    let mut bus = NullBus::default();
    // Past the start-up, the initial values (13 instructions) and a whole turn of the loop (at
    // most about 150 cycles): a mark within the first turn holds the stack RAM's entry as the
    // initialisation left it, which no later turn writes again.
    for _ in 0..warm + 400 {
        cpu.tick(Pins::default(), &mut bus);
    }
    let mark = cpu.clone();
    for _ in 0..limit {
        cpu.tick(Pins::default(), &mut bus);
        if let Ok(found) = CountingPeriod::find(&mark, &cpu, Pins::default(), &[], true) {
            return Some((found, cpu));
        }
    }
    None
}

/// Every state the proof gives within its room (up to `most` periods) is the simulated one.
fn check_against_simulation(found: &CountingPeriod, end: &Cpu, most: u64) {
    let mut sim = end.clone();
    let mut bus = NullBus::default();
    for n in 0..=found.room().min(most) {
        assert!(found.state_after(n) == sim, "period {n} of room {}", found.room());
        for _ in 0..found.cycles() {
            sim.tick(Pins::default(), &mut bus);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("BOTSIM_COUNTING_CASES").ok().and_then(|n| n.parse().ok()).unwrap_or(256)
    ))]

    /// Wherever the proof says a period counts, the periods after it are as it says.
    #[test]
    fn a_proven_count_is_the_simulation(l in a_loop(true)) {
        if let Some((found, end)) = first_counting(&l.program(), l.warm, 3000) {
            check_against_simulation(&found, &end, 400);
        }
    }

    /// Skipped by whole rooms, one after another, as a board would, the core stays the
    /// simulated one.
    #[test]
    fn skips_after_skips_are_the_simulation(l in a_loop(false)) {
        let Some((mut found, end)) = first_counting(&l.program(), l.warm, 3000) else { return Ok(()) };
        let mut sim = end;
        let mut bus = NullBus::default();
        for _ in 0..3 {
            let k = found.room().min(50);
            for _ in 0..k * found.cycles() {
                sim.tick(Pins::default(), &mut bus);
            }
            found.advance(k);
            prop_assert!(found.state_after(0) == sim);
            if found.room() == 0 {
                break;
            }
        }
    }
}

/// A loop that only counts: a 16-bit count in s0-s1 and scratch-pad counts moved, the count
/// compared, inner delays and plain work beside them, back to the start on a flag of the
/// last chain.
fn a_clean_loop() -> impl Strategy<Value = Loop> {
    let piece = prop_oneof![
        (1u8..4).prop_map(|k| Piece::Count { add: false, regs: vec![0, 1], k: vec![k, 0] }),
        prop::collection::vec(any::<u8>(), 2).prop_map(|k| Piece::Compare { regs: vec![0, 1], k }),
        (any::<bool>(), 0u8..4, 1u8..3).prop_map(|(add, at, k)| Piece::Scratch { add, at, k }),
        (1u8..6).prop_map(|n| Piece::Inner { n }),
        (any::<u8>(), any::<u8>(), any::<u8>()).prop_map(|(op, reg, k)| Piece::Plain { op, reg, k }),
    ];
    (prop::collection::vec(any::<u8>(), 8), prop::collection::vec(piece, 0..5), 0u64..400).prop_map(
        |(init, mut body, warm)| {
            body.insert(0, Piece::Count { add: false, regs: vec![0, 1], k: vec![1, 0] });
            Loop { init, body, cond: "", warm }
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Loops that only count, placed where their jumps show no count, are proven to count.
    #[test]
    fn loops_that_only_count_are_proven(l in a_clean_loop()) {
        let found = first_counting(&l.program(), l.warm, 3000);
        prop_assert!(found.is_some(), "not proven");
        let (found, end) = found.unwrap();
        check_against_simulation(&found, &end, 100);
    }
}
