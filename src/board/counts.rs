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

use kcpsm6::counting::CountingPeriod;
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
    /// The design reads `out_port` only under a write strobe (src/board/strobes.rs).
    pub out_port_free: bool,
    recording: bool,
    inputs: Vec<u8>,
    too_many: bool,
    /// The combinations of reset, sleep and interrupt seen (a bit each).
    pins: u8,
    proof: Proof,
    /// Periods since the mark found not to count.
    refusals: u32,
    /// Nested loops: see [`Nest`].
    nest: Nest,
}

/// An inner loop's count that ends again and again (a delay's inner loop, reloaded at every
/// turn of an outer one; a UART routine's timeout in a main loop) is tried as state: its
/// periods are refused so that the board finds the outer loop's period (whose count is the
/// outer one, or which does not count). A trial that finds neither within a few marks (the
/// board's patience doubling at each) ends, and the next waits for twice as many ends.
#[derive(Default)]
struct Nest {
    /// The homes of the count whose room the last skips used up, and how many times in a row.
    ended: Vec<usize>,
    times: u32,
    /// Marks since the trial began (0: none on).
    trial_marks: u32,
    /// Trials that found nothing.
    failed: u32,
}

/// The periods one mark may find not to count before it stops looking (each proof re-runs
/// its period).
const REFUSALS_PER_MARK: u32 = 4;

/// Ends of the same count in a row before a trial; marks a trial lasts.
const ENDS_BEFORE_TRIAL: u32 = 2;
const TRIAL_MARKS: u32 = 10;

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
        if self.nest.trial_marks > 0 {
            self.nest.trial_marks += 1;
            if self.nest.trial_marks > TRIAL_MARKS {
                // No outer count found: the inner one counts again.
                self.nest.trial_marks = 0;
                self.nest.times = 0;
                self.nest.failed += 1;
            }
        }
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
            self.nest.trial_marks = self.nest.trial_marks.min(1);
            return Same::Yes;
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
                    Ok(p) if self.nest.tried_as_state(&p.homes()) => {
                        if trace() {
                            eprintln!("ff: a core's inner count is state (a trial): {p:?}");
                        }
                        self.proof = Proof::Refused;
                        Same::No
                    }
                    Ok(p) => {
                        if self.nest.trial_marks > 0 && p.homes() != self.nest.ended {
                            // Another count on trial: an outer one, found.
                            self.nest.trial_marks = 0;
                            self.nest.failed = 0;
                        }
                        if trace() {
                            eprintln!("ff: a core counts: {p:?}");
                        }
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
        if periods >= p.room() {
            // The count ends in the next period.
            let homes = p.homes();
            if homes == self.nest.ended {
                self.nest.times += 1;
            } else {
                self.nest.ended = homes;
                self.nest.times = 1;
            }
        }
        p.advance(periods);
        Some(p.state_after(0))
    }
}

impl Nest {
    /// Is a count at `homes` the inner one on trial as state? (Starts the trial when its
    /// ends are enough.)
    fn tried_as_state(&mut self, homes: &[usize]) -> bool {
        if homes != self.ended || self.times < ENDS_BEFORE_TRIAL << self.failed.min(8) {
            return false;
        }
        if self.trial_marks == 0 {
            self.trial_marks = 1;
        }
        true
    }
}

/// The fast-forward's trace for botsim's developers (`BOTSIM_FF_TRACE`, as harness.cpp's).
fn trace() -> bool {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ON.get_or_init(|| std::env::var_os("BOTSIM_FF_TRACE").is_some())
}
