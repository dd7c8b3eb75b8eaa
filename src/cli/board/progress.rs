//! The progress line of a long run.

use std::time::Instant;

/// The progress line of a long run on a terminal: board time (or samples) against the end,
/// the rate against real time and the expected end; shown once a run has taken 2 s.
pub struct Progress {
    on: bool,
    end_ps: u64,
    samples: u64,
    start: Instant,
    bar: Option<indicatif::ProgressBar>,
}

impl Progress {
    pub fn new(wanted: bool, end_ps: u64, samples: u64) -> Progress {
        use std::io::IsTerminal;
        let on = wanted && std::io::stderr().is_terminal();
        Progress { on, end_ps, samples, start: Instant::now(), bar: None }
    }

    pub fn show(&mut self, now_ps: u64, samples: u64) {
        if !self.on || self.start.elapsed() < std::time::Duration::from_secs(2) {
            return;
        }
        let by_time = self.end_ps != u64::MAX;
        let bar = self.bar.get_or_insert_with(|| {
            let len = if by_time { self.end_ps / 1_000_000_000 } else { self.samples };
            let b = indicatif::ProgressBar::new(len);
            let unit = if by_time { "ms of board time" } else { "samples" };
            b.set_style(
                indicatif::ProgressStyle::with_template(&format!(
                    "{{bar:30}} {{pos}}/{{len}} {unit}, {{msg}}, ends in {{eta}}"
                ))
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            b
        });
        bar.set_position(if by_time { now_ps / 1_000_000_000 } else { samples });
        let real = now_ps as f64 / 1e12 / self.start.elapsed().as_secs_f64();
        bar.set_message(format!("{real:.2} x real time"));
    }

    pub fn done(&mut self) {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
    }
}
