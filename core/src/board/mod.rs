//! What the board shows and takes, the Verilator-free half: the seven-segment display as a
//! person sees it ([`display`]), VGA frames from the pins ([`vga`]), the UART as the PC sees
//! it ([`uart`]), the keyboard behind the USB host ([`keyboard`]), the audio output as a
//! listener hears it ([`audio`]), the inputs over time ([`stimulus`], [`random_stimulus`]),
//! and GTKWave save files for a board's waveform ([`gtkw`]). Where a design comes from is
//! [`crate::frontend`]'s; the `botsim` crate builds and runs it (`botsim::board`).

pub mod audio;
pub mod display;
pub mod gtkw;
pub mod keyboard;
pub mod random_stimulus;
pub mod stimulus;
pub mod uart;
pub mod vga;
