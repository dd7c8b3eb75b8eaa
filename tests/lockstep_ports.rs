//! Lock-step at the port level: the RTL (Verilator) and the ISS backend (cycle-timed Rust
//! models of world_if and map) run the same program on the same world with the same motor
//! commands, and every port access (INPUT, OUTPUT, OUTPUTK: port, data and cycle) and every
//! snapshot must agree.
//!
//! The firmware alone reads the map with fixed slack; random programs that write MapX/MapY
//! and read the map, MotCtl and the registers at every distance pin each path's latency as far
//! as a program can observe it: strobes are an even number of cycles apart, so a map model two
//! clocks off fails here, and MotCtl (changed from outside at any cycle) is pinned to the
//! clock. Measured by breaking the ISS models on purpose: map latency +1 clock fails all
//! three tests; MotCtl sampled a clock late fails the random programs; map latency -1 clock
//! passes, as it must (no program can tell).

mod common;

use botsim::firmware::{Compat, Firmware, Timing};
use botsim::regs::MotCtl;
use botsim::sim::lockstep::Lockstep;
use botsim::world::{Cell, World};
use botsim::IssBot;
use botsim::RtlBot;
use common::strategies::{motors, world};
use proptest::prelude::*;

fn fail(e: impl std::fmt::Display) -> TestCaseError {
    TestCaseError::fail(e.to_string())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// The RtlBot firmware on random worlds and motor sequences (any MotCtl byte).
    #[test]
    fn firmware_on_random_worlds(world in world(), segments in motors(), threshold in 1u8..6, compat in any::<bool>()) {
        let compat = if compat { Compat::BotSim20 } else { Compat::Symmetric };
        let fw = Firmware { threshold, timing: Timing::Fast, compat };
        let mut both = Lockstep::new(&fw.assemble().unwrap(), world).map_err(fail)?;
        both.wait_update().map_err(fail)?;
        for &(m, n) in &segments {
            both.set_motors(MotCtl(m));
            for _ in 0..n {
                both.wait_update().map_err(fail)?;
            }
        }
        prop_assert!(both.events_compared() >= 19, "only {} accesses", both.events_compared());
    }
}

/// One instruction of a random port-exercising program.
fn instruction() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u8..4, any::<u8>()).prop_map(|(r, k)| format!("LOAD s{r}, {k:02X}")),
        (0u8..4).prop_map(|r| format!("ADD s{r}, 01")),
        // The map address registers, then reads of the map (port A) at every distance.
        (0u8..4).prop_map(|r| format!("OUTPUT s{r}, 08")),
        (0u8..4).prop_map(|r| format!("OUTPUT s{r}, 09")),
        (0u8..4).prop_map(|r| format!("INPUT s{r}, 0A")),
        (0u8..4).prop_map(|r| format!("INPUT s{r}, 0A")),
        // Any port, read or written, by constant or by register.
        (0u8..4, 0u8..16).prop_map(|(r, p)| format!("INPUT s{r}, {p:02X}")),
        (0u8..4, 0u8..16).prop_map(|(r, p)| format!("OUTPUT s{r}, {p:02X}")),
        (0u8..4, 0u8..4).prop_map(|(r, p)| format!("INPUT s{r}, (s{p})")),
        (0u8..4, 0u8..4).prop_map(|(r, p)| format!("OUTPUT s{r}, (s{p})")),
        (any::<u8>(), 0u8..16).prop_map(|(k, p)| format!("OUTPUTK {k:02X}, {p:X}")),
    ]
}

fn program() -> impl Strategy<Value = String> {
    prop::collection::vec(instruction(), 4..60).prop_map(|body| format!("start: {}\nJUMP start\n", body.join("\n")))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// Random programs hammering the bus, with MotCtl changing between runs.
    #[test]
    fn random_programs_on_random_worlds(source in program(), world in world(), motctl in prop::collection::vec(any::<u8>(), 1..5)) {
        let program = botsim::kcpsm6::asm::assemble_str(&source).map_err(fail)?;
        let mut both = Lockstep::new(&program.image, world).map_err(fail)?;
        for (i, &m) in motctl.iter().enumerate() {
            both.set_motors(MotCtl(m));
            both.run(300 + 97 * i as u64).map_err(|e| fail(format!("{e}\n{source}")))?;
        }
        prop_assert!(both.events_compared() > 0);
    }
}

#[test]
fn a_difference_is_reported_with_both_sides() {
    // The same program, but the ISS sees an obstruction at (40, 40) that the RTL's map lacks.
    let source = "start: LOAD s0, 40\nOUTPUT s0, 08\nOUTPUT s0, 09\nLOAD s1, 00\nINPUT s2, 0A\nJUMP start\n";
    let program = botsim::kcpsm6::asm::assemble_str(source).unwrap();
    let mut walled = World::empty();
    walled.set(0x40, 0x40, Cell::Obstruction);
    let rtl = RtlBot::builder().program(program.image.clone()).world(World::empty()).build().unwrap();
    let iss = IssBot::new(&program.image, walled).unwrap();
    let mut both = Lockstep::pair(rtl, iss);
    let e = both.run(200).unwrap_err().to_string();
    // Accesses 0 and 1 are the two OUTPUTs; the INPUT of the map is the third.
    assert!(e.starts_with("port access 2 differs: RTL cycle "), "{e}");
    assert!(e.contains(": INPUT port 0A value 00, ISS cycle ") && e.ends_with(": INPUT port 0A value 02"), "{e}");
}

#[test]
fn waits_in_small_chunks_agree_too() {
    // As the CLI waits (in chunks, to look at Ctrl-C): budgets that end anywhere in a sample.
    let fw = Firmware { timing: Timing::Fast, ..Firmware::default() };
    let mut both = Lockstep::new(&fw.assemble().unwrap(), World::builtin()).unwrap();
    both.set_motors(MotCtl::FORWARD);
    let mut samples = 0;
    let mut chunk = 1;
    while samples < 30 {
        chunk = chunk % 97 + 1;
        match both.wait_update_within(chunk) {
            Ok(s) => {
                assert_eq!(s.sample, samples);
                samples += 1;
            }
            Err(botsim::sim::lockstep::Mismatch::Rtl(botsim::Error::Timeout { .. })) => {}
            Err(e) => panic!("{e}"),
        }
    }
}
