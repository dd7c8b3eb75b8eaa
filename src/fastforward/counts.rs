//! Firmware that counts, on a board's KCPSM6 models: what a model records for the
//! fast-forward since its mark (the inputs its INPUTs read, the pins it saw), and the proof
//! ([`kcpsm6::counting`]) that the period since the mark only counts, with how far it goes.
//!
//! The fast-forward (harness.cpp) repeats a period in which the whole board comes back to
//! its mark. A core in a software delay comes back but for its count: [`Watch::same`] then
//! proves the period counts, from the core at the mark and now and what it read between;
//! the board skips as many periods as the proof's room allows ([`Watch::room`]), and the core
//! jumps to where they leave it ([`Watch::skip`]). What the design sees of the core (its
//! outputs register, kcpsm6_iss.v's `botsim_iss_q`) is the model's, compared through it and
//! set from it after a skip by the harness.

use kcpsm6::counting::{same_bytes, CountingPeriod};
use kcpsm6::iss::{Cpu, Pins};

/// The most inputs kept for one mark (a period that reads more is not proven).
const MAX_INPUTS: usize = 1 << 20;

/// `read_strobe` in kcpsm6_iss.v's packed outputs, and where `in_port` and the reset,
/// sleep and interrupt pins are in its packed inputs.
const READ_STROBE: u64 = 1 << 31;
const IN_PORT_SHIFT: u32 = 18;
const PINS_SHIFT: u32 = 26;

/// What [`Watch::same`] found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Same {
    /// Not as marked.
    No,
    /// As marked.
    Yes,
    /// As marked but for a count (the period proven).
    Counting,
}

enum Proof {
    /// Not tried for this mark.
    Untried,
    /// Tried and refused: not again for this mark.
    Refused,
    Counting(Box<CountingPeriod>),
}

/// One model's records since the fast-forward's mark, and its proof.
pub(crate) struct Watch {
    /// Counting may be proven (off while the model is traced, has breakpoints, is recorded
    /// or shows its registers to a waveform).
    pub enabled: bool,
    /// The design reads `out_port` only under a write strobe (src/fastforward/strobes.rs).
    pub out_port_free: bool,
    recording: bool,
    inputs: Vec<u8>,
    too_many: bool,
    /// The combinations of reset, sleep and interrupt seen (a bit each).
    pins: u8,
    proof: Proof,
    /// Periods since the mark found not to count.
    refusals: u32,
    /// The room of the period found, when found.
    room_found: u64,
    /// Nested loops: see [`Nest`].
    nest: Nest,
}

/// Inner loops' counts that end again and again (a delay's inner loops, reloaded at every
/// turn of an outer one; a UART routine's timeout in a main loop) are taken as state: a
/// moment where one differs from the mark is not a period's end, so that the board finds the
/// outer loop's period (whose count is the outer one, or which does not count). Loops nest
/// to any depth: each inner count joins the state in turn, and stays while the outer
/// periods it shows are found. A count on trial (just taken as state) whose outer period is
/// not found and skipped within a few marks (the board's patience doubling at each) counts
/// again, and is tried again only after twice as many ends: an outer period too long to be
/// proved between the turns of the board's counters (a 1 ms delay loop beside a display
/// refreshed every 2 ms, which needs two periods' proof) is found but never skipped, and the
/// inner count's own periods skip more.
#[derive(Default)]
struct Nest {
    /// Per byte of a count: its ends since its last trial, and its trials that found nothing.
    ends: Vec<Ends>,
    /// The bytes taken as state.
    state: Vec<usize>,
    /// The bytes on trial (the last taken), and the marks since their trial began.
    trial: Vec<usize>,
    trial_marks: u32,
    /// The trial's outer period was found (not yet skipped), this many marks ago.
    found_marks: Option<u32>,
}
struct Ends {
    at: usize,
    times: u32,
    failed: u32,
}

/// The periods one mark may find not to count before it stops looking (each proof re-runs
/// its period).
const REFUSALS_PER_MARK: u32 = 4;

/// The most periods a count may have had room for, when found, for its end to count
/// towards a trial as state: a count skipped further is an outer loop doing its work.
const SHORT_ROOM: u64 = 8;

/// Ends of a count before a trial; marks a trial lasts.
const ENDS_BEFORE_TRIAL: u32 = 2;
const TRIAL_MARKS: u32 = 10;

/// Marks a trial lasts once its outer period was found, if it is not skipped.
const FOUND_MARKS: u32 = 3;

impl Watch {
    pub fn new() -> Watch {
        Watch {
            enabled: true,
            out_port_free: false,
            recording: false,
            inputs: Vec::new(),
            too_many: false,
            pins: 0,
            proof: Proof::Untried,
            refusals: 0,
            room_found: 0,
            nest: Nest::default(),
        }
    }

    /// One cycle: `pins` as the model gets them, `outputs` of the cycle (the last tick's).
    #[inline(always)]
    pub fn cycle(&mut self, pins: u64, outputs: u64) {
        if !self.recording {
            return;
        }
        self.pins |= 1 << (pins >> PINS_SHIFT & 7);
        if outputs & READ_STROBE != 0 {
            self.input((pins >> IN_PORT_SHIFT) as u8);
        }
    }

    #[cold]
    fn input(&mut self, v: u8) {
        if self.inputs.len() < MAX_INPUTS {
            self.inputs.push(v);
        } else {
            self.too_many = true;
        }
    }

    /// The fast-forward's mark: record from now on.
    pub fn mark(&mut self) {
        self.nest.mark();
        self.recording = self.enabled;
        self.inputs.clear();
        self.too_many = false;
        self.pins = 0;
        self.proof = Proof::Untried;
        self.refusals = 0;
    }

    /// Is `now` the core at `mark` again, or again but for a count? (A count proven is moved
    /// on to `now`.)
    pub fn same(&mut self, mark: &Cpu, now: &Cpu) -> Same {
        if now.same_state_as(mark) {
            // This period does not count (a proof of a shorter one since the mark is not
            // this one's); on a trial, it is the outer period found.
            self.proof = Proof::Untried;
            self.nest.repeats();
            return Same::Yes;
        }
        if !same_bytes(mark, now, &self.nest.state) {
            // An inner count taken as state differs: not an outer period's end.
            return Same::No;
        }
        match &mut self.proof {
            Proof::Counting(p) => match p.periods_to(now) {
                Some(n) if n > 0 => {
                    p.advance(n);
                    Same::Counting
                }
                _ => Same::No,
            },
            Proof::Refused => Same::No,
            Proof::Untried => {
                if !self.recording || self.too_many || self.pins.count_ones() != 1 {
                    return Same::No;
                }
                let bits = self.pins.trailing_zeros();
                let pins = Pins { interrupt: bits & 1 != 0, sleep: bits & 2 != 0, reset: bits & 4 != 0 };
                match CountingPeriod::find(mark, now, pins, &self.inputs, self.out_port_free) {
                    Ok(p) => {
                        self.nest.found();
                        if trace() {
                            eprintln!("ff: a core counts: {p:?}");
                        }
                        self.room_found = p.room();
                        self.proof = Proof::Counting(Box::new(p));
                        Same::Counting
                    }
                    Err(e) => {
                        if trace() && e.what != kcpsm6::counting::NOT_A_PERIOD {
                            eprintln!("ff: a core does not only count: {e}");
                        }
                        // A moment that is not the period's end says nothing of the mark; a
                        // period that does not count is tried a few times (a longer one may,
                        // an inner count reloaded within it), then no more for this mark.
                        if let Some(homes) = &e.count {
                            self.nest.ended(homes);
                        }
                        if e.what != kcpsm6::counting::NOT_A_PERIOD {
                            self.refusals += 1;
                            if self.refusals >= REFUSALS_PER_MARK {
                                self.proof = Proof::Refused;
                            }
                        }
                        Same::No
                    }
                }
            }
        }
    }

    /// The periods after the one found that do what it did: none known but for a count.
    pub fn room(&self) -> Option<u64> {
        match &self.proof {
            Proof::Counting(p) => Some(p.room()),
            _ => None,
        }
    }

    /// Is the model's period one that counts?
    pub fn counting(&self) -> bool {
        matches!(self.proof, Proof::Counting(_))
    }

    /// The core `periods` periods on from the one found (its end moves there): none if the
    /// period did not count.
    pub fn skip(&mut self, periods: u64) -> Option<Cpu> {
        let Proof::Counting(p) = &mut self.proof else { return None };
        self.nest.skipped(periods);
        if periods >= p.room() && self.room_found <= SHORT_ROOM {
            // The count ends in the next period, having been skipped little.
            self.nest.ended(&p.homes());
        }
        p.advance(periods);
        Some(p.state_after(0))
    }
}

impl Nest {
    /// A count at `homes` ended (its room used up, or set to something else within a
    /// period): enough ends take it as state, on trial.
    fn ended(&mut self, homes: &[usize]) {
        for &at in homes {
            if self.state.contains(&at) {
                continue;
            }
            let i = match self.ends.iter().position(|e| e.at == at) {
                Some(i) => i,
                None => {
                    self.ends.push(Ends { at, times: 0, failed: 0 });
                    self.ends.len() - 1
                }
            };
            let e = &mut self.ends[i];
            e.times += 1;
            if e.times >= ENDS_BEFORE_TRIAL << e.failed.min(8) {
                if trace() {
                    eprintln!("ff: a core's inner count at byte {at} is state (a trial)");
                }
                self.state.push(at);
                self.trial.push(at);
                self.trial_marks = self.trial_marks.max(1);
            }
        }
    }

    /// A period that counts found (its count is not the state's): the trial's outer period,
    /// which pays once it is skipped (`skipped`).
    fn found(&mut self) {
        if self.trial.is_empty() {
            self.trial_marks = 0;
        } else {
            self.found_marks.get_or_insert(0);
        }
    }

    /// Periods of a count skipped: a trial's outer period paid.
    fn skipped(&mut self, periods: u64) {
        if periods == 0 {
            return;
        }
        for at in self.trial.drain(..) {
            if let Some(e) = self.ends.iter_mut().find(|e| e.at == at) {
                e.failed = 0;
            }
        }
        self.trial_marks = 0;
        self.found_marks = None;
    }

    /// A period that does not count found: a trial holds while it repeats.
    fn repeats(&mut self) {
        self.trial_marks = self.trial_marks.min(1);
    }

    /// The fast-forward's mark: a trial that found nothing within its marks ends, and its
    /// counts count again.
    fn mark(&mut self) {
        if self.trial_marks == 0 {
            return;
        }
        self.trial_marks += 1;
        if let Some(m) = &mut self.found_marks {
            *m += 1;
        }
        if self.trial_marks > TRIAL_MARKS || self.found_marks.is_some_and(|m| m > FOUND_MARKS) {
            for at in self.trial.drain(..) {
                self.state.retain(|&s| s != at);
                if let Some(e) = self.ends.iter_mut().find(|e| e.at == at) {
                    e.times = 0;
                    e.failed += 1;
                }
            }
            self.trial_marks = 0;
            self.found_marks = None;
        }
    }
}

/// The fast-forward's trace for botsim's developers (`BOTSIM_FF_TRACE`, as harness.cpp's).
fn trace() -> bool {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ON.get_or_init(|| std::env::var_os("BOTSIM_FF_TRACE").is_some())
}

#[cfg(test)]
mod tests {
    use super::*;
    use kcpsm6::asm::assemble_str;
    use kcpsm6::iss::{Config, NullBus};

    /// A delay of three loops (s2 in s1 in s0), placed at 0F0 so that its JUMPs show sF on
    /// port_id; one inner turn is 4 cycles, one middle turn 2 (1 + 2 x 3 + 2) = 18, one
    /// outer turn 2 (1 + 3 x 9 + 2) = 60.
    const NEST: &str = "JUMP start\nADDRESS 0F0\nstart: LOAD s0, 60\nouter: LOAD s1, 03\nmiddle: LOAD s2, 03\ninner: SUB s2, 01\nJUMP NZ, inner\nSUB s1, 01\nJUMP NZ, middle\nSUB s0, 01\nJUMP NZ, outer\nhalt: JUMP halt\n";

    fn core(warm: u64) -> Cpu {
        let p = assemble_str(NEST).unwrap();
        let mut cpu = Cpu::new(Config::default(), &p.image.words[..]);
        cpu.run_instructions(warm, &mut NullBus::default()).unwrap();
        cpu
    }

    fn on(cpu: &Cpu, cycles: u64) -> Cpu {
        let mut c = cpu.clone();
        for _ in 0..cycles {
            c.tick(Pins::default(), &mut NullBus::default());
        }
        c
    }

    /// What the harness does: a mark, then the moments a board of period `board` cycles is
    /// as marked, until the core is (or is but for a count).
    fn look(w: &mut Watch, mark: &Cpu, board: u64, looks: u64) -> Option<(u64, Same)> {
        w.mark();
        for k in 1..=looks {
            let now = on(mark, board * k);
            for _ in 0..board {
                w.cycle(0, 0);
            }
            match w.same(mark, &now) {
                Same::No => continue,
                s => return Some((board * k, s)),
            }
        }
        None
    }

    #[test]
    fn inner_counts_become_state_and_the_outer_period_counts() {
        let mut w = Watch::new();
        w.out_port_free = true;
        // Marked in the inner loop (after its first JUMP): a board whose period is 4 cycles
        // finds the inner count's short period, whose room is a turn or two.
        let mark = core(6);
        assert_eq!(look(&mut w, &mark, 4, 1), Some((4, Same::Counting)));
        // Periods of 22 cycles (a middle turn and an inner turn) span s2's reload: refused,
        // and twice makes s2 state, on trial.
        for _ in 0..3 {
            assert_eq!(look(&mut w, &mark, 22, 3), None);
        }
        assert!(w.nest.state.contains(&2), "{:?}", w.nest.state);
        // With s2 as state, the inner loop's short period is no period any more (it was one
        // above), and a board of 18 cycles finds the middle loop's: s1 counts.
        assert_eq!(look(&mut w, &mark, 4, 1), None);
        assert_eq!(look(&mut w, &mark, 18, 3), Some((18, Same::Counting)));
        assert_eq!(w.nest.trial, vec![2], "found, not yet skipped");
        assert_eq!(w.room(), Some(1), "s1 is 2 now: one more middle turn before it ends");
        w.skip(1).unwrap();
        assert!(w.nest.trial.is_empty(), "the trial's outer period skipped: it paid");
        assert!(w.nest.state.contains(&2), "{:?}", w.nest.state);
    }

    #[test]
    fn a_trial_whose_outer_period_is_found_but_never_skipped_ends() {
        let mut n = Nest::default();
        n.ended(&[7]);
        n.ended(&[7]);
        n.found();
        n.skipped(0);
        for _ in 0..FOUND_MARKS {
            n.mark();
        }
        assert_eq!(n.state, vec![7], "still on trial");
        n.mark();
        assert!(n.state.is_empty() && n.trial.is_empty(), "the trial ended: {:?}", n.state);
    }

    #[test]
    fn a_trial_that_finds_nothing_ends_and_waits_twice_as_long() {
        let mut n = Nest::default();
        n.ended(&[7]);
        assert!(n.state.is_empty());
        n.ended(&[7]);
        assert_eq!((n.state.clone(), n.trial.clone()), (vec![7], vec![7]));
        // The trial began within a mark: it lasts that one and TRIAL_MARKS - 1 more.
        for _ in 1..TRIAL_MARKS {
            n.mark();
        }
        assert_eq!(n.state, vec![7], "still on trial");
        n.mark();
        assert!(n.state.is_empty() && n.trial.is_empty(), "the trial ended");
        for _ in 0..3 {
            n.ended(&[7]);
        }
        assert!(n.state.is_empty(), "four ends now");
        n.ended(&[7]);
        assert_eq!(n.state, vec![7]);
        // Found and skipped: it stays state, and a later trial of another count leaves it.
        n.found();
        n.skipped(1);
        n.ended(&[9]);
        n.ended(&[9]);
        for _ in 0..=TRIAL_MARKS {
            n.mark();
        }
        assert_eq!(n.state, vec![7]);
    }
}
