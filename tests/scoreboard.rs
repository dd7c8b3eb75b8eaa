//! Scoreboard: every snapshot of the RTL (bot.v + firmware under Verilator) equals the golden
//! model's, on random worlds and random motor sequences, in both compatibility modes and with
//! several thresholds.

mod common;

use botsim::firmware::{Compat, Firmware, Timing};
use botsim::golden::GoldenBot;
use botsim::regs::MotCtl;
use botsim::world::World;
use botsim::IssBot;
use botsim::RtlBot;
use common::strategies::{motors, world};
use proptest::prelude::*;

/// The RTL against the golden model (registers) and against the ISS backend (registers and
/// the cycle of every pulse).
fn check(world: World, threshold: u8, compat: Compat, segments: &[(u8, u8)]) -> Result<(), TestCaseError> {
    let fw = Firmware { threshold, timing: Timing::Fast, compat };
    let fail = |e: botsim::Error| TestCaseError::fail(e.to_string());
    let mut bot = RtlBot::builder().firmware(fw).world(world.clone()).build().map_err(fail)?;
    let mut iss = IssBot::new(&fw.assemble().unwrap(), world.clone()).unwrap();
    let mut model = GoldenBot::new(world, threshold, compat);
    let s0 = bot.wait_update().map_err(fail)?;
    prop_assert_eq!(s0.regs, model.initial(), "sample 0");
    prop_assert_eq!(iss.wait_update_within(10_000).map_err(fail)?, s0, "ISS backend, sample 0");
    let mut k = 0;
    for &(m, n) in segments {
        bot.set_motors(MotCtl(m));
        iss.set_motors(MotCtl(m));
        for _ in 0..n {
            k += 1;
            let s = bot.wait_update().map_err(fail)?;
            let want = model.step(MotCtl(m));
            prop_assert_eq!(s.regs, want, "sample {} with MotCtl {:02X}", k, m);
            prop_assert_eq!(iss.wait_update_within(10_000).map_err(fail)?, s, "ISS backend, sample {}", k);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn rtl_matches_the_model_on_random_worlds_and_motors(
        w in world(),
        segs in motors(),
        threshold in prop::sample::select(vec![1u8, 2, 3, 4, 15]),
        compat in prop::sample::select(vec![Compat::Symmetric, Compat::BotSim20]),
    ) {
        check(w, threshold, compat, &segs)?;
    }
}

/// A long drive with small thresholds through all headings on the built-in world.
#[test]
fn long_drive_on_the_builtin_world() {
    let script: Vec<(u8, u8)> = [
        (0x33, 30),
        (0x30, 9),
        (0x33, 20),
        (0x23, 9),
        (0x22, 25),
        (0x03, 5),
        (0x33, 40),
        (0x32, 13),
        (0x33, 30),
        (0x00, 3),
        (0x02, 7),
        (0x20, 7),
        (0x44, 4),
        (0xFF, 9),
    ]
    .to_vec();
    check(World::builtin(), 2, Compat::Symmetric, &script).unwrap();
}
