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
    Counting(CountingPeriod),
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
}

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
        self.recording = self.enabled;
        self.inputs.clear();
        self.too_many = false;
        self.pins = 0;
        self.proof = Proof::Untried;
    }

    /// Is `now` the core at `mark` again, or again but for a count? (A count proven is moved
    /// on to `now`.)
    pub fn same(&mut self, mark: &Cpu, now: &Cpu) -> Same {
        if now.same_state_as(mark) {
            // This period does not count (a proof of a shorter one since the mark is not
            // this one's).
            self.proof = Proof::Untried;
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
                    Ok(p) => {
                        if trace() {
                            eprintln!("ff: a core counts: {p:?}");
                        }
                        self.proof = Proof::Counting(p);
                        Same::Counting
                    }
                    Err(e) => {
                        if trace() && e.what != kcpsm6::counting::NOT_A_PERIOD {
                            eprintln!("ff: a core does not only count: {e}");
                        }
                        // A moment that is not the period's end says nothing of the mark.
                        if e.what != kcpsm6::counting::NOT_A_PERIOD {
                            self.proof = Proof::Refused;
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
        p.advance(periods);
        Some(p.state_after(0))
    }
}

/// The fast-forward's trace for botsim's developers (`BOTSIM_FF_TRACE`, as harness.cpp's).
fn trace() -> bool {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ON.get_or_init(|| std::env::var_os("BOTSIM_FF_TRACE").is_some())
}
