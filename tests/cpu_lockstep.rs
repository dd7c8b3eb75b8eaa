//! CPU lock-step testbench: the RTL core (rtl/kcpsm6.v under Verilator) against the ISS,
//! on directed programs covering every instruction and on thousands of random programs with
//! random reset, sleep and interrupt stimulus, in all three scratch-pad variants.

mod common;

use std::collections::BTreeSet;

use botsim::sim::rtl::SIZES;
use common::cpu_coverage::{Coverage, Stimulus};
use common::lockstep::Lockstep;
use kcpsm6::asm::assemble_str;
use kcpsm6::iss::{Pins, RetireKind, ScratchPad};
use proptest::prelude::*;

/// Every instruction form, looping so it runs with changing data; an ISR at each variant's
/// vector is provided by `with_isr`.
const DIRECTED: &str = "
        LOAD s0, 01
        LOAD sF, 80
loop:   LOAD s1, s0
        AND s4, s0
        AND s4, 7E
        OR s5, s6
        OR s5, 0F
        XOR s6, s5
        XOR s6, 3C
        TEST s0, s6
        TEST s0, 81
        TESTCY s1, s2
        TESTCY s1, 0F
        ADD s0, s1
        ADD s0, 37
        ADDCY s1, s0
        ADDCY s1, 01
        SUB s2, s3
        SUB s2, 11
        SUBCY s3, s2
        SUBCY s3, 01
        COMPARE s2, s3
        COMPARE s2, 40
        COMPARECY s3, s4
        COMPARECY s3, 05
        SL0 s7
        SL1 s7
        SLX s8
        SLA s8
        RL s9
        SR0 s9
        SR1 sA
        SRX sA
        SRA sB
        RR sB
        HWBUILD sC
        STAR s0, s1
        STAR s1, 5A
        REGBANK B
        ADD s0, 03
        REGBANK A
        INPUT sD, 3C
        INPUT sE, (s0)
        OUTPUT sD, 12
        OUTPUT sE, (s1)
        OUTPUTK A5, 3
        INST 2A5B0
        STORE s0, 3F
        STORE s1, (s0)
        FETCH s2, 3F
        FETCH s3, (s1)
        ENABLE INTERRUPT
        CALL sub
        CALL value
        LOAD s4, sub'upper
        LOAD s5, sub'lower
        CALL@ (s4, s5)
        DISABLE INTERRUPT
        COMPARE s0, s0       ; Z=1 C=0
        CALL Z, subz
        CALL NZ, subz
        CALL C, sub
        CALL NC, sub
        COMPARE sF, 00       ; Z=0
        CALL subz
        CALL plain
        JUMP Z, j1
j1:     JUMP NZ, j2
j2:     JUMP C, j3
j3:     JUMP NC, j4
j4:     TEST s0, 00          ; Z=1
        JUMP j5
j5:     INST 23000
        INST 33000
        LOAD s4, 00
        LOAD s5, loop'lower
        COMPARE sF, 00
        JUMP@ (s4, s5)
        ADDRESS 100
sub:    RETURN C
        RETURN NC
subz:   RETURN Z
        RETURN NZ
value:  LOAD&RETURN s7, 42
plain:  RETURN
";

fn with_isr(src: &str, vector: u16) -> Vec<u32> {
    let isr = format!("\nADDRESS {vector:03X}\n        ADD sF, 01\n        LOAD&RETURN s6, 77\n");
    let mut p = assemble_str(&format!("{src}{isr}")).unwrap_or_else(|e| panic!("{e}")).image.words.to_vec();
    // LOAD&RETURN at the vector would pop the interrupted address + 1: use RETURNI instead,
    // alternating ENABLE / DISABLE by variant.
    p[vector as usize + 1] = if vector & 1 == 1 { 0x29001 } else { 0x29000 };
    p
}

fn inputs(seed: u8) -> [u8; 256] {
    std::array::from_fn(|i| (i as u8).wrapping_mul(37) ^ seed)
}

#[test]
fn directed_program_in_every_variant() {
    for size in SIZES {
        let vector = botsim::sim::rtl::CpuHarness::new(size).config().interrupt_vector;
        let prog = with_isr(DIRECTED, vector);
        let mut ls = Lockstep::new(size, &prog, inputs(0x3C));
        // A long interrupt request now and then, overlapping the ENABLE ... DISABLE window.
        ls.run(6000, |cpu| Pins { interrupt: cpu.cycle() % 700 > 400, ..Pins::default() })
            .unwrap_or_else(|e| panic!("{size:?}: {e}"));
        let ops: BTreeSet<u32> =
            ls.retired.iter().filter(|r| r.kind == RetireKind::Executed).map(|r| r.word >> 12).collect();
        let missing: Vec<String> = (0..0x40u32)
            .filter(|op| ![0x27, 0x3B, 0x3F, 0x15].contains(op) && !ops.contains(op))
            .map(|op| format!("{op:02X}"))
            .collect();
        assert!(missing.is_empty(), "{size:?}: opcodes never executed: {missing:?}");
        assert!(ls.retired.iter().any(|r| r.kind == RetireKind::Interrupt), "{size:?}: no interrupt taken");
    }
}

#[test]
fn reset_sleep_and_interrupt_sequences_in_lockstep() {
    let prog = with_isr(DIRECTED, 0x3FF);
    let mut ls = Lockstep::new(ScratchPad::B64, &prog, inputs(1));
    ls.run(3000, |cpu| {
        let c = cpu.cycle();
        Pins {
            reset: (500..503).contains(&c) || c == 1201,
            sleep: (800..830).contains(&c) || (2000..2001).contains(&c),
            interrupt: (1500..1540).contains(&c) || c % 97 == 0,
        }
    })
    .unwrap();
}

#[test]
fn stack_overflow_and_underflow_reset_in_lockstep() {
    let deep = "LOAD s0, 00\nrec: ADD s0, 01\nOUTPUT s0, 01\nCALL rec\n";
    let mut ls = Lockstep::new(ScratchPad::B64, &assemble_str(deep).unwrap().image.words[..], inputs(0));
    ls.run(600, |_| Pins::default()).unwrap();
    assert!(ls.retired.iter().filter(|r| r.pc == 0).count() >= 2, "overflow restarted the program");
    let under = "LOAD s0, 00\nOUTPUT s0, 02\nRETURN\n";
    let mut ls = Lockstep::new(ScratchPad::B128, &assemble_str(under).unwrap().image.words[..], inputs(0));
    ls.run(200, |_| Pins::default()).unwrap();
    // An interrupt at depth 30 overflows too.
    let isr_deep = "ENABLE INTERRUPT\nrec: CALL rec\n";
    let mut prog = assemble_str(isr_deep).unwrap().image.words.to_vec();
    prog[0x3FF] = 0x22001; // vector: JUMP rec
    let mut ls = Lockstep::new(ScratchPad::B64, &prog, inputs(0));
    ls.run(400, |cpu| Pins { interrupt: cpu.cycle() > 60, ..Pins::default() }).unwrap();
}

/// A random instruction word, biased towards meaningful programs of `len` words.
fn word(len: u32) -> impl Strategy<Value = u32> {
    let reg = 0u32..16;
    let target = 0u32..len + 2;
    prop_oneof![
        // two-operand forms (register and constant)
        6 => (prop::sample::select(vec![0x00u32, 0x02, 0x04, 0x06, 0x08, 0x0A, 0x0C, 0x0E, 0x10, 0x12, 0x16, 0x18, 0x1A, 0x1C, 0x1E, 0x2C, 0x2E]),
              any::<bool>(), reg.clone(), reg.clone(), any::<u8>())
            .prop_map(|(op, k, x, y, kk)| if k { (op + 1) << 12 | x << 8 | kk as u32 } else { op << 12 | x << 8 | y << 4 }),
        // shifts, HWBUILD and undocumented sub-codes
        2 => (reg.clone(), any::<u8>(), any::<bool>()).prop_map(|(x, s, b15)| (0x14 + b15 as u32) << 12 | x << 8 | s as u32),
        // control flow within the program
        3 => (prop::sample::select(vec![0x20u32, 0x22, 0x30, 0x32, 0x34, 0x36, 0x38, 0x3A, 0x3C, 0x3E]), target)
            .prop_map(|(op, t)| op << 12 | t),
        2 => prop::sample::select(vec![0x25000u32, 0x31000, 0x35000, 0x39000, 0x3D000, 0x29000, 0x29001]),
        1 => (0x21u32..=0x21, reg.clone(), any::<u8>()).prop_map(|(op, x, k)| op << 12 | x << 8 | k as u32),
        1 => (prop::sample::select(vec![0x24u32, 0x26]), reg.clone(), reg.clone()).prop_map(|(op, x, y)| op << 12 | x << 8 | y << 4),
        2 => prop::sample::select(vec![0x28000u32, 0x28001, 0x37000, 0x37001, 0x2B123, 0x2A456, 0x23000, 0x3F123]),
        // anything at all
        1 => 0u32..=0x3FFFF,
    ]
}

/// Random programs (48 words, an ISR of 4 at the variant's vector that often starts with a
/// REGBANK, the rest of the ROM
/// `JUMP 000`) with random pins and events aimed at the instruction in flight: ports and state
/// equal in every cycle. Afterwards every coverage bin must have been reached: a reset landing
/// on the D and on the second cycle, an interrupt pre-empting and recognised in the second
/// cycle, and sleep in the second cycle, of REGBANK, RETURNI, STAR, CALL@, JUMP@, STORE,
/// FETCH, OUTPUT and INPUT (sY), ADDCY, SUBCY and the shifts through carry; the carry forms
/// with C = 1 under a reset; a pre-empted REGBANK and RETURNI that switch the bank; a stack
/// error held through sleep.
#[test]
fn random_programs_in_lockstep() {
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    // A fixed seed keeps the coverage closure reproducible; BOTSIM_LOCKSTEP_SEED sweeps others.
    let seed: u64 = std::env::var("BOTSIM_LOCKSTEP_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(2026);
    println!("BOTSIM_LOCKSTEP_SEED={seed}");
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let cases = 2000;
    let mut runner = TestRunner::new_with_rng(
        Config { cases, failure_persistence: None, ..Config::default() },
        TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes),
    );
    let coverage = std::cell::RefCell::new(Coverage::default());
    let strategy = (
        prop::collection::vec(word(48), 48),
        // ISRs often start by switching the bank: REGBANK A or B first, half the time.
        (prop::collection::vec(word(48), 4), prop::option::of(any::<bool>())).prop_map(|(mut isr, bank)| {
            if let Some(b) = bank {
                isr[0] = 0x37000 | b as u32;
            }
            isr
        }),
        prop::sample::select(SIZES.to_vec()),
        any::<u64>(),
        any::<u8>(),
        (0u32..30, 0u32..300, 0u32..800),
    );
    runner
        .run(&strategy, |(body, isr, size, seed, input_seed, rates)| {
            let mut prog = vec![0x22000; 4096]; // JUMP 000 outside the program
            prog[..body.len()].copy_from_slice(&body);
            let vector = botsim::sim::rtl::CpuHarness::new(size).config().interrupt_vector as usize;
            prog[vector..vector + isr.len()].copy_from_slice(&isr);
            prog[vector + isr.len()] = 0x29001; // RETURNI ENABLE
            let mut ls = Lockstep::new(size, &prog, inputs(input_seed));
            let mut stimulus = Stimulus::new(seed, rates, 600);
            let result = ls.run(500, |cpu| {
                coverage.borrow_mut().sample(cpu);
                stimulus.pins(cpu)
            });
            prop_assert!(result.is_ok(), "{}", result.unwrap_err());
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
    let coverage = coverage.into_inner();
    println!("coverage over {cases} programs:\n{coverage}");
    assert!(coverage.holes().is_empty(), "bins never reached: {:?}\n{coverage}", coverage.holes());
}
