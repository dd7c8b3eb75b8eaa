//! What a pin of the board is ([`Role`]) and the peripherals outside the FPGA that pins reach
//! ([`Peripheral`]): the words [`super::pins`] (a top's ports by their names) and
//! [`super::constraints`] (by a constraint file's package pins) both give their findings in.

/// What a top-level port is wired to in the simulated board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// The 100 MHz oscillator.
    Clock,
    /// The CPU reset button; `active_low` as on the Nexys4.
    Reset {
        active_low: bool,
    },
    /// Push button 0..4 = C, U, D, L, R.
    Button(u8),
    Switches,
    Leds,
    /// `seg[6:0]` = g..a, or `seg[7:0]` with the decimal point in bit 7 (Nexys3).
    Segments,
    /// One segment line (Nexys4 DDR: CA..CG = 0..6).
    Segment(u8),
    DecimalPoint,
    Anodes,
    VgaRed,
    VgaGreen,
    VgaBlue,
    Hsync,
    Vsync,
    /// The USB-UART's line into the FPGA (`RsRx`) and out of it (`RsTx`).
    UartRx,
    UartTx,
    /// The keyboard's PS/2 clock and data: inputs, or open-collector inouts.
    Ps2Clock,
    Ps2Data,
    /// The ADXL362's SPI pins and interrupts (`aclInt1`/`aclInt2`: 1, 2; `ACL_INT[2:1]`: 0).
    AclSck,
    AclMosi,
    AclMiso,
    AclSs,
    AclInt(u8),
    /// The audio output: the PWM line and the amplifier's enable (`ampSD`, 1 = on).
    AudioPwm,
    AudioOn,
}

/// A peripheral of the board outside the FPGA (board.md §7), as a design's pins reach it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Peripheral {
    Uart,
    Keyboard,
    Accelerometer,
    Audio,
}

impl Peripheral {
    /// Its name in botsim's messages.
    pub fn name(self) -> &'static str {
        match self {
            Peripheral::Uart => "USB-UART",
            Peripheral::Keyboard => "keyboard (PS/2)",
            Peripheral::Accelerometer => "accelerometer (ADXL362)",
            Peripheral::Audio => "audio",
        }
    }
}

impl Role {
    /// The peripheral a pin of this role reaches, if any.
    pub fn peripheral(self) -> Option<Peripheral> {
        Some(match self {
            Role::UartRx | Role::UartTx => Peripheral::Uart,
            Role::Ps2Clock | Role::Ps2Data => Peripheral::Keyboard,
            Role::AclSck | Role::AclMosi | Role::AclMiso | Role::AclSs | Role::AclInt(_) => Peripheral::Accelerometer,
            Role::AudioPwm | Role::AudioOn => Peripheral::Audio,
            _ => return None,
        })
    }
}
