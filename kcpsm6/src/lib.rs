//! KCPSM6 (PicoBlaze-6) toolchain: assembler, disassembler, program images, output formats
//! and a cycle-exact instruction-set simulator. No Verilator and no Xilinx code: usable from a
//! build script and on its own.
//!
//! ```
//! use kcpsm6::asm::assemble_str;
//! use kcpsm6::iss::{Config, Cpu, NullBus};
//! let p = assemble_str("LOAD s0, 05\nloop: SUB s0, 01\nJUMP NZ, loop\nOUTPUT s0, 01\n").unwrap();
//! let mut cpu = Cpu::new(Config::default(), &p.image.words[..]);
//! let mut bus = NullBus::default();
//! // LOAD, then five SUB/JUMP pairs, then OUTPUT.
//! let out = cpu.run_instructions(12, &mut bus).unwrap();
//! assert_eq!(out.port.map(|e| e.value), Some(0));
//! ```

pub mod asm;
pub mod counting;
pub mod diag;
pub mod disasm;
pub mod image;
pub mod isa;
pub mod iss;
pub mod loader;
pub mod output;
pub mod readmemh;
pub mod source;
pub mod time;
pub mod trace;

pub use diag::{Diagnostic, Diagnostics, Loc};
pub use image::Image;
