//! The board's audio output as a listener hears it (board.md §7): the low-pass filter turns
//! `ampPWM`'s duty cycle (or pulse density) into the waveform, so each sample is the line's
//! average over its sample period, silent while the amplifier is off (`ampSD` 0).
//!
//! ```
//! use botsim_core::board::audio::Audio;
//! // A line high a quarter of each 1 us: every sample averages 0.25, the amplifier on.
//! let mut a = Audio::new(48_000);
//! for k in 0..100u64 {
//!     a.line(k * 1_000_000, true, true);
//!     a.line(k * 1_000_000 + 250_000, false, true);
//! }
//! a.finish(100_000_000);
//! assert_eq!(a.samples().len(), 4);
//! assert!(a.samples().iter().all(|s| (s - 0.25).abs() < 0.01));
//! ```

/// The sample rate of `--audio` files and the page's sound.
pub const RATE: u32 = 48_000;

/// Picoseconds per second.
const PS: u128 = 1_000_000_000_000;

/// The samples of the audio output, from its lines' changes.
#[derive(Clone, Debug)]
pub struct Audio {
    rate: u32,
    /// The lines since `since`: the PWM level and the amplifier.
    high: bool,
    on: bool,
    since: u64,
    /// The sample being summed: its index and the high time in it so far (ps).
    index: u64,
    high_ps: u64,
    samples: Vec<f32>,
    /// Samples taken by [`Audio::take`] before those in `samples`.
    taken: u64,
    heard: bool,
}

impl Audio {
    pub fn new(rate: u32) -> Audio {
        Audio {
            rate,
            high: false,
            on: false,
            since: 0,
            index: 0,
            high_ps: 0,
            samples: Vec::new(),
            taken: 0,
            heard: false,
        }
    }

    /// Where sample `k` starts (ps).
    fn start(&self, k: u64) -> u64 {
        (k as u128 * PS / self.rate as u128) as u64
    }

    /// The lines are `pwm` and `amp_on` from `time_ps` on.
    pub fn line(&mut self, time_ps: u64, pwm: bool, amp_on: bool) {
        self.advance(time_ps);
        self.high = pwm;
        self.on = amp_on;
        self.heard |= amp_on;
    }

    /// Sum up to `t`: whole samples pushed, the one `t` is in kept open.
    fn advance(&mut self, t: u64) {
        while t >= self.start(self.index + 1) {
            let end = self.start(self.index + 1);
            let len = end - self.start(self.index);
            if self.high && self.on {
                self.high_ps += end - self.since.max(self.start(self.index));
            }
            let v = if self.on { self.high_ps as f32 / len as f32 } else { 0.0 };
            self.samples.push(v);
            self.index += 1;
            self.high_ps = 0;
            self.since = end;
        }
        if self.high && self.on && t > self.since {
            self.high_ps += t - self.since;
        }
        self.since = t;
    }

    /// The samples up to `time_ps`.
    pub fn finish(&mut self, time_ps: u64) {
        self.advance(time_ps);
    }

    /// Every sample so far (each the line's average, 0 to 1; 0 while the amplifier is off).
    pub fn samples(&self) -> &[f32] {
        &self.samples
    }

    /// The samples since the last take, with the index of the first.
    pub fn take(&mut self) -> (u64, Vec<f32>) {
        let first = self.taken;
        let v = std::mem::take(&mut self.samples);
        self.taken += v.len() as u64;
        (first, v)
    }

    /// Whether the amplifier was ever on.
    pub fn heard(&self) -> bool {
        self.heard
    }

    /// The samples as a mono 16-bit WAV file, AC-coupled as the board's output is (a
    /// first-order high-pass at about 20 Hz takes the line's average away), full scale at a
    /// line that swings 0 to 1.
    pub fn wav(&self) -> Vec<u8> {
        let mut pcm = Vec::with_capacity(self.samples.len() * 2);
        for x in ac_coupled(&self.samples) {
            pcm.extend_from_slice(&((x * 32767.0).round().clamp(-32768.0, 32767.0) as i16).to_le_bytes());
        }
        let mut w = Vec::with_capacity(44 + pcm.len());
        w.extend_from_slice(b"RIFF");
        w.extend_from_slice(&(36 + pcm.len() as u32).to_le_bytes());
        w.extend_from_slice(b"WAVEfmt ");
        w.extend_from_slice(&16u32.to_le_bytes());
        w.extend_from_slice(&1u16.to_le_bytes()); // PCM
        w.extend_from_slice(&1u16.to_le_bytes()); // mono
        w.extend_from_slice(&self.rate.to_le_bytes());
        w.extend_from_slice(&(self.rate * 2).to_le_bytes());
        w.extend_from_slice(&2u16.to_le_bytes());
        w.extend_from_slice(&16u16.to_le_bytes());
        w.extend_from_slice(b"data");
        w.extend_from_slice(&(pcm.len() as u32).to_le_bytes());
        w.extend_from_slice(&pcm);
        w
    }
}

/// `samples` with their slow average taken away (a one-pole DC blocker, as the board's
/// coupling capacitor does), from rest.
pub fn ac_coupled(samples: &[f32]) -> Vec<f32> {
    const POLE: f32 = 0.9974; // about 20 Hz at 48 kHz
    let (mut last_in, mut last_out) = (samples.first().copied().unwrap_or(0.0), 0.0f32);
    samples
        .iter()
        .map(|&x| {
            last_out = x - last_in + POLE * last_out;
            last_in = x;
            last_out
        })
        .collect()
}

/// The strongest frequency of `samples` at `rate` between `lo` and `hi` Hz (1 Hz steps, the
/// Goertzel power of each): for checking a tone.
pub fn pitch(samples: &[f32], rate: u32, lo: u32, hi: u32) -> u32 {
    let mean = samples.iter().sum::<f32>() / samples.len().max(1) as f32;
    let mut best = (lo, 0.0f64);
    for f in lo..=hi {
        let w = 2.0 * std::f64::consts::PI * f as f64 / rate as f64;
        let c = 2.0 * w.cos();
        let (mut s1, mut s2) = (0.0f64, 0.0f64);
        for &x in samples {
            let s0 = (x - mean) as f64 + c * s1 - s2;
            s2 = s1;
            s1 = s0;
        }
        let p = s1 * s1 + s2 * s2 - c * s1 * s2;
        if p > best.1 {
            best = (f, p);
        }
    }
    best.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_tone_has_its_pitch_and_silence_when_off() {
        // 440 Hz square wave for 0.1 s, then the amplifier off.
        let mut a = Audio::new(RATE);
        let half = PS as u64 / 880;
        for k in 0..88u64 {
            a.line(k * half, k % 2 == 0, true);
        }
        a.line(88 * half, false, false);
        a.finish(PS as u64 / 5);
        let s = a.samples();
        assert_eq!(s.len(), RATE as usize / 5);
        assert_eq!(pitch(&s[..RATE as usize / 10], RATE, 200, 2000), 440);
        assert!(s[RATE as usize / 10 + 10..].iter().all(|&v| v == 0.0));
        let w = a.wav();
        assert_eq!(&w[..4], b"RIFF");
        assert_eq!(w.len(), 44 + 2 * s.len());
    }
}
