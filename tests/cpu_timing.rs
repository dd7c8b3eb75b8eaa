//! The core's port timing against the exact cycle numbers of spec/kcpsm6.md §2, on both the
//! RTL (rtl/kcpsm6.v under Verilator) and the ISS. The expected numbers are the spec's, worked
//! out in each test's comments; nothing is taken from either core's output.
//!
//! Cycle numbers count the first clock after configuration as cycle 0; with the self-start,
//! the instruction at address a (straight-line from 000) has its D in cycle 5 + 2a.

mod common;

use botsim::sim::rtl::{CpuHarness, Ports};
use common::lockstep::{both_cores, Core};
use kcpsm6::asm::assemble_str;
use kcpsm6::iss::{Phase, Pins, ScratchPad};

fn program(src: &str) -> Vec<u32> {
    assemble_str(src).unwrap_or_else(|e| panic!("{e}")).image.words.to_vec()
}

/// The RTL and the ISS, each loaded with `src` (64-byte variant, inputs all zero).
fn cores(src: &str) -> [Box<dyn Core>; 2] {
    both_cores(ScratchPad::B64, &program(src), [0; 256])
}

/// Ports of cycles 0..n, with pins from `pins(cycle)`.
fn trace(core: &mut dyn Core, n: u64, pins: impl Fn(u64) -> Pins) -> Vec<Ports> {
    (0..n).map(|c| core.tick(pins(c))).collect()
}

fn cycles_where(t: &[Ports], f: impl Fn(&Ports) -> bool) -> Vec<usize> {
    t.iter().enumerate().filter(|(_, p)| f(p)).map(|(i, _)| i).collect()
}

/// (cycle, port_id, out_port) of every write strobe.
fn writes(t: &[Ports]) -> Vec<(usize, u8, u8)> {
    t.iter().enumerate().filter(|(_, p)| p.write_strobe).map(|(i, p)| (i, p.port_id, p.out_port)).collect()
}

/// The ports of cycles 0..n of `src` with `pins(cycle)`, on every core: the RTL under
/// Verilator, the ISS, and the RTL under Icarus, a four-state simulator, where a RAM entry or
/// index the device does not define reads `x` (`icarus::X`).
fn traces(src: &str, n: u64, pins: impl Fn(u64) -> Pins) -> Vec<(&'static str, Vec<Ports>)> {
    let mut out: Vec<(&'static str, Vec<Ports>)> =
        cores(src).into_iter().map(|mut c| (c.name(), trace(&mut *c, n, &pins))).collect();
    let pins: Vec<Pins> = (0..n).map(pins).collect();
    if let Some(t) = common::icarus::trace(&program(src), &pins) {
        out.push(("icarus", t));
    }
    out
}

fn reset_in(cycles: std::ops::RangeInclusive<u64>) -> impl Fn(u64) -> Pins {
    move |c| Pins { reset: cycles.contains(&c), ..Pins::default() }
}

// ---- §2.2-§2.4: sequencing, I/O, reset ---------------------------------------------------------

#[test]
fn power_up_self_start() {
    // One extra bram_enable pulse in cycle 1, the self-start fetch in 4, first D in 5 (§2.4, §2.8).
    for mut core in cores("LOAD s0, 01\nLOAD s0, 02\n") {
        let t = trace(&mut *core, 8, |_| Pins::default());
        assert_eq!(cycles_where(&t, |p| p.bram_enable), vec![1, 4, 6], "{}", core.name());
        assert!(t[..5].iter().all(|p| p.address == 0));
        assert_eq!(t[5].instruction, 0x01001, "000 is on `instruction` in its D cycle");
        assert_eq!((t[6].address, t[6].bram_enable), (1, true), "F of 000 fetches 001");
    }
}

#[test]
fn output_timing_table() {
    // §2.2: OUTPUT s0, 56 with s0 = 12: D shows port_id/out_port without strobe, F strobes.
    for mut core in cores("LOAD s0, 12\nOUTPUT s0, 56\n") {
        let t = trace(&mut *core, 10, |_| Pins::default());
        let (d, f) = (&t[7], &t[8]);
        assert_eq!(
            (d.address, d.bram_enable, d.instruction, d.port_id, d.out_port, d.write_strobe),
            (1, false, 0x2D056, 0x56, 0x12, false),
            "{}",
            core.name()
        );
        assert_eq!(
            (f.address, f.bram_enable, f.instruction, f.port_id, f.out_port, f.write_strobe),
            (2, true, 0x2D056, 0x56, 0x12, true)
        );
        assert_eq!(cycles_where(&t, |p| p.write_strobe || p.read_strobe || p.k_write_strobe), vec![8]);
    }
}

#[test]
fn outputk_pulses_only_k_write_strobe() {
    for mut core in cores("OUTPUTK AB, C\n") {
        let t = trace(&mut *core, 8, |_| Pins::default());
        assert_eq!((t[6].k_write_strobe, t[6].write_strobe, t[6].out_port, t[6].port_id), (true, false, 0xAB, 0xBC));
    }
}

#[test]
fn input_samples_in_port_at_the_end_of_its_second_cycle() {
    // The harness's in_port in cycle t is inputs[port_id of t-1] ^ (t - 1); INPUT at 000 has
    // D 5, F 6: it reads inputs[3C] ^ 5, then OUTPUTs it.
    let mut inputs = [0u8; 256];
    inputs[0x3C] = 0xA0;
    for mut core in both_cores(ScratchPad::B64, &program("INPUT s0, 3C\nOUTPUT s0, 01\n"), inputs) {
        let t = trace(&mut *core, 10, |_| Pins::default());
        assert!(t[6].read_strobe);
        assert_eq!((t[8].write_strobe, t[8].out_port), (true, 0xA0 ^ 5), "{}", core.name());
    }
}

#[test]
fn external_reset_sequence() {
    // §2.4 example: reset high in 21-22 -> r = 23 -> fetch in 26 -> 000's D in 27.
    for mut core in cores("LOAD s0, 01\nLOAD s0, 02\nJUMP 001\n") {
        let t = trace(&mut *core, 29, reset_in(21..=22));
        let fetches: Vec<usize> = cycles_where(&t, |p| p.bram_enable).into_iter().filter(|&c| c >= 21).collect();
        assert_eq!(fetches[..2], [22, 26], "k+1 still makes the step decided in k (22 is F), then 26");
        assert!(t[23..26].iter().all(|p| !p.bram_enable && p.address == 0));
        assert_eq!((t[27].address, t[27].instruction), (0, 0x01001));
        assert_eq!(core.state().registers[0], 0x01, "000 ran again (its write at the end of 28)");
    }
}

#[test]
fn reset_keeps_registers_and_clears_flags_ie_bank_and_stack() {
    let src = "LOAD s3, 77\nSTORE s3, 05\nREGBANK B\nLOAD s1, 00\nSUB s1, 01\nENABLE INTERRUPT\nCALL 100\n";
    for mut core in cores(src) {
        trace(&mut *core, 20, |_| Pins::default());
        let s = core.state();
        assert!(s.carry && s.bank && s.interrupt_enable && s.depth == 1, "{}", core.name());
        trace(&mut *core, 3, |_| Pins { reset: true, ..Pins::default() });
        let s = core.state();
        assert_eq!((s.pc, s.carry, s.zero, s.bank, s.interrupt_enable, s.depth), (0, false, false, false, false, 0));
        assert_eq!((s.registers[3], s.registers[16 + 1], s.scratch_pad[5]), (0x77, 0xFF, 0x77));
    }
}

#[test]
fn reset_in_d_still_writes_the_register_but_loses_the_flag_write() {
    // §2.4: LOAD s0, FF at 000 (D 5, write in 6); ADD s0, 01 at 001 has its D in 7 = k+1 of a
    // reset (pin high in 6). It still writes s0 = FF + 01 = 00 at the end of 8 (k+2), but its
    // flags (C = 1, Z = 1) are lost to the reset's clear.
    for mut core in cores("LOAD s0, FF\nADD s0, 01\nOUTPUT s0, 02\n") {
        trace(&mut *core, 9, reset_in(6..=6));
        let s = core.state();
        assert_eq!((s.registers[0], s.carry, s.zero), (0x00, false, false), "{}", core.name());
    }
}

// ---- §2.6: interrupts ----------------------------------------------------------------------------

#[test]
fn interrupt_example_trace() {
    // §2.6: 25 (D) interrupt rises; 27 cancels; 28 ack with the vector fetched; 29 vector's D.
    for mut core in cores("ENABLE INTERRUPT\n") {
        let t = trace(&mut *core, 34, |c| Pins { interrupt: (25..29).contains(&c), ..Pins::default() });
        assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![28], "{}", core.name());
        assert_eq!((t[28].address, t[28].bram_enable), (0x3FF, true));
        assert_eq!(t[29].address, 0x3FF);
        assert_eq!(core.state().depth, 1);
    }
}

#[test]
fn interrupt_from_an_f_cycle_acks_four_later_and_one_cycle_f_pulses_are_missed() {
    for mut core in cores("ENABLE INTERRUPT\n") {
        let t = trace(&mut *core, 40, |c| Pins { interrupt: c == 16 || (26..31).contains(&c), ..Pins::default() });
        assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![30], "{}", core.name());
    }
}

#[test]
fn enable_interrupt_with_a_pending_request() {
    // ENABLE at 000 (D 5, F 6) with the request held: 001 is cancelled, vector fetched in 8.
    for mut core in cores("ENABLE INTERRUPT\nLOAD s0, 11\n") {
        let t = trace(&mut *core, 12, |_| Pins { interrupt: true, ..Pins::default() });
        assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![8], "{}", core.name());
        assert_eq!(core.state().registers[0], 0, "the cancelled LOAD never wrote");
    }
}

#[test]
fn ack_with_sleep_in_the_entry_d_falls_in_the_first_idle_cycle_and_the_vector_is_fetched_at_wake_up() {
    // ENABLE D 5, F 6 recognises the request (pin high in 5); entry D 7 with sleep registered
    // (pin high from 6) -> 8 is idle and carries the ack (two cycles after the recognising F).
    // Sleep low first in m = 15: the vector's F in 17, its D in 18, the next F in 19.
    for mut core in cores("ENABLE INTERRUPT\nLOAD s0, 01\n") {
        let t = trace(&mut *core, 20, |c| Pins { interrupt: c == 5, sleep: (6..15).contains(&c), ..Pins::default() });
        assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![8], "{}", core.name());
        assert!(!t[8].bram_enable);
        assert_eq!(
            cycles_where(&t, |p| p.bram_enable).into_iter().filter(|&c| c > 6).collect::<Vec<_>>(),
            vec![17, 19]
        );
        assert_eq!((t[17].address, t[18].address, t[18].instruction), (0x3FF, 0x3FF, 0));
    }
}

#[test]
fn ack_pulses_in_state_00_without_a_vector_fetch_when_a_reset_starts_in_the_entry_d() {
    // §2.6: the request is recognised in ENABLE's F (6); the entry D 7 is k+1 of a reset
    // (pin high in 6). ack still pulses two cycles after the recognising F, in 8, in state 00
    // at address 000; nothing fetches the vector: the next fetch is the restart at r+3 = 10.
    for mut core in cores("ENABLE INTERRUPT\nLOAD s0, 01\n") {
        let t = trace(&mut *core, 14, |c| Pins { interrupt: c == 5, reset: c == 6, ..Pins::default() });
        assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![8], "{}", core.name());
        assert_eq!((t[8].bram_enable, t[8].address), (false, 0));
        assert_eq!(
            cycles_where(&t, |p| p.bram_enable).into_iter().filter(|&c| c > 6).collect::<Vec<_>>(),
            vec![10, 12]
        );
        let s = core.state();
        assert_eq!((s.registers[0], s.depth), (0, 0), "the pre-empted LOAD never wrote; no push in reset");
    }
}

#[test]
fn an_f_cycle_in_reset_still_recognises_the_request_and_acks_in_state_00() {
    // §2.6: ENABLE D 5 F 6; LOAD at 001 D 7 with reset high in 7: k = 7, so 8 is an F with
    // internal_reset = 1 while IE is still 1. The request (pin high in 7) is recognised there:
    // the recognition flop is never reset, so ack pulses in 10 (state 00, address 000) and no
    // vector is fetched; the restart fetches 000 in r+3 = 11 (r = 8).
    for mut core in cores("ENABLE INTERRUPT\nLOAD s0, 01\nLOAD s1, 02\n") {
        let t = trace(&mut *core, 14, |c| Pins { interrupt: c == 7, reset: c == 7, ..Pins::default() });
        assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![10], "{}", core.name());
        assert_eq!((t[10].bram_enable, t[10].address), (false, 0));
        assert_eq!(
            cycles_where(&t, |p| p.bram_enable).into_iter().filter(|&c| c > 8).collect::<Vec<_>>(),
            vec![11, 13]
        );
        assert_eq!(t[12].address, 0, "000 runs again, not the ISR");
    }
}

#[test]
fn a_preempted_regbank_still_switches_the_bank() {
    // §2.6: s0 = 11 in bank A, 22 in B. ENABLE D 9 F 10; REGBANK B at 003 (D 11) is pre-empted
    // (request pin high in 9, recognised in 10). The bank flop has no interrupt input, so the
    // ISR starts in bank B: its OUTPUT s0 (D 15) writes 22 in 16. RETURNI (D 17) restores the
    // pushed bank A and resumes at 003: REGBANK B runs (D 19), OUTPUT s0, 02 writes 22 in 22.
    let src = "
        LOAD s0, 11
        STAR s0, 22
        ENABLE INTERRUPT
        REGBANK B
        OUTPUT s0, 02
done:   JUMP done
        ADDRESS 100
isr:    OUTPUT s0, 01
        RETURNI DISABLE
        ADDRESS 3FF
        JUMP isr
";
    for mut core in cores(src) {
        let t = trace(&mut *core, 24, |c| Pins { interrupt: c == 9, ..Pins::default() });
        assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![12], "{}", core.name());
        assert_eq!(writes(&t), vec![(16, 0x01, 0x22), (22, 0x02, 0x22)], "{}", core.name());
    }
}

#[test]
fn a_preempted_returni_loads_the_saved_bank_without_popping() {
    // §2.6: main runs in bank B (s0 = 22; bank A's s0 = 11) and waits at 004. First entry
    // (pre-empting JUMP 004, D 13) pushes {004, B}; the ISR reports its bank (OUTPUT s0, D 17,
    // strobe 18: 22), switches to A, enables interrupts (D 21) and its RETURNI ENABLE (D 23)
    // is pre-empted (request still high in F 22): the bank loads the top entry's B without
    // popping, the entry pushes {103, A}, and the ISR starts again in B (strobe 28: 22). With
    // the request gone, RETURNI (D 33) pops {103, A} and RETURNI (D 35) pops {004, B}.
    let src = "
        LOAD s0, 11
        STAR s0, 22
        REGBANK B
        ENABLE INTERRUPT
wait:   JUMP wait
        ADDRESS 100
isr:    OUTPUT s0, 01
        REGBANK A
        ENABLE INTERRUPT
        RETURNI ENABLE
        ADDRESS 3FF
        JUMP isr
";
    for mut core in cores(src) {
        let t = trace(&mut *core, 34, |c| Pins { interrupt: (11..=21).contains(&c), ..Pins::default() });
        assert_eq!(writes(&t), vec![(18, 0x01, 0x22), (28, 0x01, 0x22)], "{}", core.name());
        let s = core.state();
        assert_eq!((s.pc, s.bank, s.depth), (0x103, false, 1), "{}: RETURNI popped the pushed A", core.name());
        trace(&mut *core, 2, |_| Pins::default());
        let s = core.state();
        assert_eq!((s.pc, s.bank, s.depth), (0x004, true, 0), "{}: then main's B", core.name());
    }
}

#[test]
fn interrupt_vector_and_hwbuild_parameters_reach_the_core() {
    let mut h = CpuHarness::new(ScratchPad::B128);
    let cfg = h.config();
    assert_eq!((cfg.hwbuild, cfg.interrupt_vector), (0x5A, 0x1C0));
    h.load_program(&program("HWBUILD s2\nENABLE INTERRUPT\n"));
    let t = trace(&mut h, 20, |c| Pins { interrupt: c > 8, ..Pins::default() });
    assert_eq!(h.state().registers[2], 0x5A);
    let ack = cycles_where(&t, |p| p.interrupt_ack);
    assert_eq!(t[ack[0]].address, 0x1C0);
}

// ---- §2.7: sleep ---------------------------------------------------------------------------------

#[test]
fn sleep_completes_the_instruction_and_wakes_two_cycles_after_release() {
    // §2.7: sleep high from 6: 001 (OUTPUT) decodes in 7, strobes in 8 (idle); sleep low
    // first in m = 20: fetch in 22, D in 23.
    for mut core in cores("LOAD s0, 01\nOUTPUT s0, 10\nLOAD s1, 02\n") {
        let t = trace(&mut *core, 26, |c| Pins { sleep: (6..20).contains(&c), ..Pins::default() });
        assert!(t[8].write_strobe && !t[8].bram_enable, "{}", core.name());
        assert!(t[8..22].iter().all(|p| !p.bram_enable && p.address == 2));
        assert!(t[22].bram_enable);
        assert_eq!((t[23].address, t[23].instruction), (2, 0x01102));
    }
}

// ---- §2.5: the call stack ------------------------------------------------------------------------

#[test]
fn the_stack_ram_holds_000_at_configuration_so_a_first_underflow_returns_to_001() {
    // §2.8: the stack RAM is configured to 000, and an underflow pops entry 31, which nothing
    // has written yet: the RETURN's n+2 is the D at 001 (000 + 1), in every core, the
    // four-state one included. Three programs: the RETURN first, after an OUTPUT, and a
    // LOAD&RETURN.
    for (src, d) in [("RETURN\n", 5), ("OUTPUT s0, 01\nRETURN\n", 7), ("LOAD&RETURN s1, 42\n", 5)] {
        for (name, t) in traces(src, 16, |_| Pins::default()) {
            assert_eq!(t[d + 1].address, 1, "{name} {src:?}: the F after the underflow fetches 001");
            assert_eq!(t[d + 2].address, 1, "{name} {src:?}: n+2 is the D of the popped address");
            assert!(t[d + 3..d + 5].iter().all(|p| p.address == 0 && !p.bram_enable), "{name} {src:?}: idle");
        }
    }
}

#[test]
fn stack_error_sequence_n1_to_n6_and_the_underflow_reads_entry_31() {
    // §2.5, underflow. RETURN at 001 (D 7 = n) pops entry 31, 000 at configuration: n+1 = 8 is
    // an F at 001; n+2 = 9 the D of that RETURN with internal_reset = 1, which writes entry 31
    // = {001, ...} while the depth is 31; 10, 11 idle; n+5 = 12 F at 000; n+6 = 13 D at 000.
    // The second underflow (RETURN's D 15 = n') returns to 001 + 1 = 002: its OUTPUT's D is
    // n'+2 = 17 and still strobes in 18; the restart fetches 000 in 20.
    for (name, t) in traces("OUTPUT s0, 01\nRETURN\nOUTPUT s0, 02\n", 24, |_| Pins::default()) {
        assert_eq!(
            writes(&t).iter().map(|w| (w.0, w.1)).collect::<Vec<_>>(),
            vec![(6, 1), (14, 1), (18, 2), (22, 1)],
            "{name}"
        );
        let fetches: Vec<(usize, u16)> =
            cycles_where(&t, |p| p.bram_enable).into_iter().map(|c| (c, t[c].address)).collect();
        assert_eq!(
            fetches,
            vec![(1, 0), (4, 0), (6, 1), (8, 1), (12, 0), (14, 1), (16, 2), (20, 0), (22, 1)],
            "{name}"
        );
        assert_eq!((t[9].address, t[9].instruction), (1, 0x25000), "{name}: n+2 is the D of the popped address");
        assert!(!t[10].bram_enable && !t[11].bram_enable && t[10].address == 0);
        assert_eq!((t[13].address, t[17].address), (0, 2));
    }
}

#[test]
fn stack_error_is_checked_in_f_only_so_a_call_in_n2_does_not_extend_the_reset() {
    // §2.5, overflow. `rec: CALL rec` at 000: the k-th CALL's D is 5 + 2k and leaves depth
    // k + 1; the 31st (k = 30, D 65 = n) leaves 31. n+1 = 66 is an F at 000 (the error), n+2 =
    // 67 the D of the CALL again with internal_reset = 1: not checked (it is a D), so the
    // restart fetches 000 at n+5 = 70 and decodes it at 71.
    for mut core in cores("rec: CALL rec\n") {
        let t = trace(&mut *core, 74, |_| Pins::default());
        let after: Vec<usize> = cycles_where(&t, |p| p.bram_enable).into_iter().filter(|&c| c >= 64).collect();
        assert_eq!(after, vec![64, 66, 70, 72], "{}", core.name());
        assert_eq!((t[71].address, t[71].bram_enable), (0, false));
    }
}

#[test]
fn stack_error_waits_for_the_first_f_after_sleep() {
    // §2.5: the RETURN at 001 (D 7 = n) underflows, but sleep (pin high 6-19) makes 8 an idle
    // cycle: no F, no check. The depth holds 31 and the core sleeps at the popped address 001.
    // Sleep low first in m = 20: the F of m+2 = 22 fetches 001 and sees the error; 23 is the
    // D of that RETURN in reset; 24, 25 idle; 26 fetches 000; 27 decodes it.
    for mut core in cores("LOAD s0, 00\nRETURN\n") {
        let mut t = vec![];
        for c in 0..28 {
            t.push(core.tick(Pins { sleep: (6..20).contains(&c), ..Pins::default() }));
            if (8..21).contains(&c) {
                let s = core.state();
                assert_eq!(
                    (s.depth, s.internal_reset, s.phase),
                    (31, false, Phase::Idle),
                    "{}: after {c}",
                    core.name()
                );
            }
        }
        let fetches: Vec<(usize, u16)> =
            cycles_where(&t, |p| p.bram_enable).into_iter().filter(|&c| c > 6).map(|c| (c, t[c].address)).collect();
        assert_eq!(fetches, vec![(22, 1), (26, 0)], "{}", core.name());
        assert_eq!((t[23].address, t[23].instruction, t[27].address), (1, 0x25000, 0));
    }
}

#[test]
fn stack_overflow_restarts_and_the_target_still_writes() {
    // 30 nested CALLs fit; the 31st overflows. Its target's register write still happens.
    for mut core in cores("LOAD s0, 00\nrec: ADD s0, 01\nCALL rec\n") {
        let mut restarted = None;
        for c in 0..400u64 {
            let p = core.tick(Pins::default());
            if c > 10 && p.address == 0 && p.bram_enable {
                restarted = Some(c);
                break;
            }
        }
        assert!(restarted.is_some(), "{}: no internal reset", core.name());
        // s0: 1 from the first ADD, +1 after each of the 30 CALLs that fit, +1 from the
        // overflowing CALL's target (ADD), which still writes during the reset sequence.
        assert_eq!(core.state().registers[0], 32);
    }
}

// ---- §2.8: port-level details --------------------------------------------------------------------

/// s0/s1 = A0/A1 in bank A and B0/B1 in bank B, then bank B; `last` at 005 has its D in 15.
fn two_banks_then(last: &str) -> String {
    format!("LOAD s0, A0\nLOAD s1, A1\nSTAR s0, B0\nSTAR s1, B1\nREGBANK B\n{last}\n")
}

#[test]
fn sy_follows_the_live_bank_and_sx_the_registered_xb_when_a_reset_lands_in_output_d() {
    // §2.8: OUTPUT s0, (s1) has its D in 15 with reset high in 14, so the bank is cleared at
    // the end of 15. Its strobe (16) takes port_id = sY through the live bank (A: A1) and
    // out_port = sX through xb, loaded in 15 with the old bank (B: B0). In the D itself both
    // read bank B.
    for mut core in cores(&two_banks_then("OUTPUT s0, (s1)")) {
        let t = trace(&mut *core, 18, reset_in(14..=14));
        assert_eq!((t[15].port_id, t[15].out_port, t[15].write_strobe), (0xB1, 0xB0, false), "{}", core.name());
        assert_eq!(writes(&t), vec![(16, 0xA1, 0xB0)], "{}", core.name());
    }
}

#[test]
fn store_sy_addresses_the_scratch_pad_through_the_live_bank() {
    // As above with STORE s0, (s1): the second cycle writes sX of the old bank (B0) at sY of
    // the new one (A1 mod 64 = 21), not at B1 mod 64 = 31.
    for mut core in cores(&two_banks_then("STORE s0, (s1)")) {
        trace(&mut *core, 18, reset_in(14..=14));
        let s = core.state();
        assert_eq!((s.scratch_pad[0x21], s.scratch_pad[0x31]), (0xB0, 0x00), "{}", core.name());
    }
}

#[test]
fn star_writes_the_other_bank_through_xb() {
    // §2.8: xb is loaded every cycle with F ? bank : bank ^ is_STAR; after STAR's D (7) it is
    // the other bank for the write in 8, then the bank again.
    for mut core in cores("LOAD s1, 5A\nSTAR s2, s1\n") {
        trace(&mut *core, 8, |_| Pins::default());
        let s = core.state();
        assert_eq!((s.bank, s.sx_bank), (false, true), "{}: after STAR's D", core.name());
        trace(&mut *core, 1, |_| Pins::default());
        let s = core.state();
        assert_eq!((s.sx_bank, s.registers[16 + 2], s.registers[2]), (false, 0x5A, 0x00), "{}", core.name());
    }
}

#[test]
fn out_port_follows_a_bank_switch_one_cycle_after_the_bank() {
    // s0 = 11 in bank A, 22 in bank B. CALL pushes bank A; the callee switches to B and
    // RETURNI DISABLE (D 13, F 14) restores A. RETURNI's out_port is sX (bit 13 = 0): in its F
    // the bank is already A but xb still holds B; in 15 both are A.
    for mut core in cores("LOAD s0, 11\nSTAR s0, 22\nCALL 010\nADDRESS 010\nREGBANK B\nRETURNI DISABLE\n") {
        let t = trace(&mut *core, 16, |_| Pins::default());
        assert_eq!((t[13].out_port, t[14].out_port, t[15].out_port), (0x22, 0x22, 0x11), "{}", core.name());
    }
}

#[test]
fn alu_result_is_fixed_at_the_end_of_d_when_a_reset_clears_the_carry() {
    // §2.8: C = 1 from ADD (D 7); s1 = 10 (D 9); the carry instruction at 003 has its D in 11
    // with reset high in 10: C is cleared at the end of 11, yet the write in 12 is computed
    // with C = 1 as it was in D. The flag write is lost (C = Z = 0 after the reset).
    for (instr, want) in [("ADDCY s1, 00", 0x11), ("SUBCY s1, 00", 0x0F), ("SLA s1", 0x21), ("SRA s1", 0x88)] {
        for mut core in cores(&format!("LOAD s0, FF\nADD s0, 01\nLOAD s1, 10\n{instr}\n")) {
            trace(&mut *core, 14, reset_in(10..=10));
            let s = core.state();
            assert_eq!((s.registers[1], s.carry, s.zero), (want, false, false), "{}: {instr}", core.name());
        }
    }
}

#[test]
fn scratch_pad_size_aliases_addresses() {
    for (size, addr) in [(ScratchPad::B64, 0x03usize), (ScratchPad::B128, 0x43), (ScratchPad::B256, 0xC3)] {
        for mut core in both_cores(size, &program("LOAD s1, 5A\nSTORE s1, C3\n"), [0; 256]) {
            trace(&mut *core, 12, |_| Pins::default());
            let s = core.state();
            assert_eq!(s.scratch_pad.len(), size.bytes());
            assert_eq!(s.scratch_pad[addr], 0x5A, "{size:?} {}", core.name());
        }
    }
}

#[test]
fn vcd_is_written_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cpu.vcd");
    let mut h = CpuHarness::new(ScratchPad::B64);
    h.load_program(&program("LOAD s0, 01\nOUTPUT s0, 02\n"));
    h.open_vcd(&path).unwrap();
    trace(&mut h, 20, |_| Pins::default());
    h.close_vcd();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("$timescale"));
    assert!(text.contains(" write_strobe "));
    assert!(text.contains("$scope module cpu $end"));
    assert!(h.open_vcd(&dir.path().join("no/such/dir/x.vcd")).is_err());
}
