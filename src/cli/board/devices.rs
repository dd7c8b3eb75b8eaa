//! The host's side of the board's peripherals over a run: the bytes it sends (text to the
//! USB-UART, the keyboard's scan codes) fed to the design's devices as their queues take
//! them, and what the design sends back (the UART's bytes, the audio).

use std::collections::VecDeque;

use botsim::board::model::{Device, Lines, Pushed};
use botsim::PS_PER_CYCLE;
use botsim_core::board::audio::{Audio, RATE};
use botsim_core::board::stimulus::Stimulus;
use botsim_core::board::uart::{clocks_per_bit, Rate, UartLine, DEFAULT_BAUD};

/// How long a full queue waits before the host tries again (a byte to the keyboard takes
/// about 1 ms, to the UART 87 us at 115200 baud).
const FULL_RETRY_PS: u64 = 100_000_000;

/// The bytes waiting for the design's devices.
#[derive(Default)]
pub struct Feeder {
    uart: VecDeque<u8>,
    keyboard: VecDeque<u8>,
}

impl Feeder {
    /// Queue what the stimulus sends at `t`.
    pub fn queue(&mut self, s: &Stimulus, t: u64) {
        self.uart.extend(s.uart_at(t));
        self.keyboard.extend(s.keyboard_at(t));
    }

    /// Queue bytes for a device.
    pub fn send(&mut self, device: Device, bytes: &[u8]) {
        match device {
            Device::Uart => self.uart.extend(bytes),
            Device::Keyboard => self.keyboard.extend(bytes),
        }
    }

    /// Push what the devices take at `t` (`push` sends up to 8 bytes to one); the time to try
    /// again when bytes are left.
    pub fn feed(&mut self, t: u64, mut push: impl FnMut(Device, &[u8]) -> Pushed) -> Option<u64> {
        let mut retry: Option<u64> = None;
        for (device, q) in [(Device::Uart, &mut self.uart), (Device::Keyboard, &mut self.keyboard)] {
            if q.is_empty() {
                continue;
            }
            let n = q.len().min(8);
            let bytes: Vec<u8> = q.iter().take(n).copied().collect();
            let again = match push(device, &bytes) {
                Pushed::Taken => {
                    q.drain(..n);
                    // The next push waits for this one's clock edge.
                    t + PS_PER_CYCLE
                }
                Pushed::NextClock => t + PS_PER_CYCLE,
                Pushed::Full => t + FULL_RETRY_PS,
            };
            if !q.is_empty() {
                retry = Some(retry.map_or(again, |r| r.min(again)));
            }
        }
        retry
    }
}

/// What the design sends the host: the UART's bytes and, when asked for, the sound.
pub struct Heard {
    pub uart: UartLine,
    pub audio: Option<Audio>,
    /// The rate into the FPGA in clocks per bit, as last set.
    pub uart_div: u32,
}

impl Heard {
    /// `baud`: `--uart-baud` (else measured); `audio`: keep the sound.
    pub fn new(baud: Option<u32>, audio: bool) -> Heard {
        Heard {
            uart: UartLine::new(baud.map_or(Rate::Measured, Rate::Given)),
            audio: audio.then(|| Audio::new(RATE)),
            uart_div: clocks_per_bit(baud.unwrap_or(DEFAULT_BAUD)),
        }
    }

    /// The peripherals' lines from `t` on.
    pub fn lines(&mut self, t: u64, lines: Lines) {
        self.uart.level(t, lines.uart_tx());
        if let Some(a) = &mut self.audio {
            a.line(t, lines.pwm(), lines.amp_on());
        }
    }

    /// The rate into the FPGA when it should change (the design's own, measured since).
    pub fn new_uart_div(&mut self) -> Option<u32> {
        let (baud, _) = self.uart.baud()?;
        let div = clocks_per_bit(baud);
        (div != self.uart_div).then(|| {
            self.uart_div = div;
            div
        })
    }

    /// The line of the summary about the UART: its rate and what it received.
    pub fn uart_summary(&self) -> Option<String> {
        let r = &self.uart.received;
        let rate = match self.uart.baud() {
            Some((b, true)) => format!("{b} baud, measured from the design's transmissions"),
            Some((b, false)) => format!("{b} baud (--uart-baud)"),
            None if r.is_empty() => return None,
            None => "rate unknown".to_string(),
        };
        let errors = match self.uart.framing_errors() {
            0 => String::new(),
            n => format!(
                "; {n} framing errors (the design's rate looks like {} baud)",
                self.uart.suggested_baud().unwrap_or(0)
            ),
        };
        let text = self.uart.text();
        let tail: String = text.chars().rev().take(60).collect::<Vec<_>>().into_iter().rev().collect();
        let shown = if tail.len() < text.len() { format!("...{tail}") } else { tail };
        Some(format!("UART ({rate}): received {} bytes{errors}: {shown:?}", r.len()))
    }
}
