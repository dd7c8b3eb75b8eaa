//! The keyboard behind the Nexys4's USB host, as the FPGA sees it (board.md §7): a key pressed
//! sends its scan-code set 2 make code, released `F0` and the make code, extended keys with
//! `E0` first. Keys are named as the browser's `KeyboardEvent.code` names them (`KeyA`,
//! `Digit1`, `Enter`, `ArrowUp`, ...), in the page and in stimulus files alike.
//!
//! ```
//! use botsim_core::board::keyboard::{codes, Key};
//! let up = Key::named("ArrowUp").unwrap();
//! assert_eq!(codes(up, true), [0xE0, 0x75]);
//! assert_eq!(codes(up, false), [0xE0, 0xF0, 0x75]);
//! assert_eq!(codes(Key::named("keya").unwrap(), false), [0xF0, 0x1C]);
//! ```

/// A key of the keyboard: its name and set 2 make code, `E0`-prefixed when `extended`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Key {
    pub name: &'static str,
    pub code: u8,
    pub extended: bool,
}

/// The keys (the standard IBM scan-code set 2): (name, make code, extended).
const KEYS: &[(&str, u8, bool)] = &[
    ("KeyA", 0x1C, false),
    ("KeyB", 0x32, false),
    ("KeyC", 0x21, false),
    ("KeyD", 0x23, false),
    ("KeyE", 0x24, false),
    ("KeyF", 0x2B, false),
    ("KeyG", 0x34, false),
    ("KeyH", 0x33, false),
    ("KeyI", 0x43, false),
    ("KeyJ", 0x3B, false),
    ("KeyK", 0x42, false),
    ("KeyL", 0x4B, false),
    ("KeyM", 0x3A, false),
    ("KeyN", 0x31, false),
    ("KeyO", 0x44, false),
    ("KeyP", 0x4D, false),
    ("KeyQ", 0x15, false),
    ("KeyR", 0x2D, false),
    ("KeyS", 0x1B, false),
    ("KeyT", 0x2C, false),
    ("KeyU", 0x3C, false),
    ("KeyV", 0x2A, false),
    ("KeyW", 0x1D, false),
    ("KeyX", 0x22, false),
    ("KeyY", 0x35, false),
    ("KeyZ", 0x1A, false),
    ("Digit0", 0x45, false),
    ("Digit1", 0x16, false),
    ("Digit2", 0x1E, false),
    ("Digit3", 0x26, false),
    ("Digit4", 0x25, false),
    ("Digit5", 0x2E, false),
    ("Digit6", 0x36, false),
    ("Digit7", 0x3D, false),
    ("Digit8", 0x3E, false),
    ("Digit9", 0x46, false),
    ("Backquote", 0x0E, false),
    ("Minus", 0x4E, false),
    ("Equal", 0x55, false),
    ("Backslash", 0x5D, false),
    ("Backspace", 0x66, false),
    ("Space", 0x29, false),
    ("Tab", 0x0D, false),
    ("CapsLock", 0x58, false),
    ("ShiftLeft", 0x12, false),
    ("ShiftRight", 0x59, false),
    ("ControlLeft", 0x14, false),
    ("AltLeft", 0x11, false),
    ("Enter", 0x5A, false),
    ("Escape", 0x76, false),
    ("BracketLeft", 0x54, false),
    ("BracketRight", 0x5B, false),
    ("Semicolon", 0x4C, false),
    ("Quote", 0x52, false),
    ("Comma", 0x41, false),
    ("Period", 0x49, false),
    ("Slash", 0x4A, false),
    ("NumLock", 0x77, false),
    ("ScrollLock", 0x7E, false),
    ("F1", 0x05, false),
    ("F2", 0x06, false),
    ("F3", 0x04, false),
    ("F4", 0x0C, false),
    ("F5", 0x03, false),
    ("F6", 0x0B, false),
    ("F7", 0x83, false),
    ("F8", 0x0A, false),
    ("F9", 0x01, false),
    ("F10", 0x09, false),
    ("F11", 0x78, false),
    ("F12", 0x07, false),
    ("Numpad0", 0x70, false),
    ("Numpad1", 0x69, false),
    ("Numpad2", 0x72, false),
    ("Numpad3", 0x7A, false),
    ("Numpad4", 0x6B, false),
    ("Numpad5", 0x73, false),
    ("Numpad6", 0x74, false),
    ("Numpad7", 0x6C, false),
    ("Numpad8", 0x75, false),
    ("Numpad9", 0x7D, false),
    ("NumpadDecimal", 0x71, false),
    ("NumpadAdd", 0x79, false),
    ("NumpadSubtract", 0x7B, false),
    ("NumpadMultiply", 0x7C, false),
    ("ControlRight", 0x14, true),
    ("AltRight", 0x11, true),
    ("MetaLeft", 0x1F, true),
    ("MetaRight", 0x27, true),
    ("ContextMenu", 0x2F, true),
    ("Insert", 0x70, true),
    ("Home", 0x6C, true),
    ("PageUp", 0x7D, true),
    ("Delete", 0x71, true),
    ("End", 0x69, true),
    ("PageDown", 0x7A, true),
    ("ArrowUp", 0x75, true),
    ("ArrowLeft", 0x6B, true),
    ("ArrowDown", 0x72, true),
    ("ArrowRight", 0x74, true),
    ("NumpadDivide", 0x4A, true),
    ("NumpadEnter", 0x5A, true),
];

impl Key {
    /// The key named `name` (in any case), if the keyboard has it.
    pub fn named(name: &str) -> Option<Key> {
        KEYS.iter().find(|(n, _, _)| n.eq_ignore_ascii_case(name)).map(|&(name, code, extended)| Key {
            name,
            code,
            extended,
        })
    }
}

/// The scan codes a key sends when pressed (`down`) or released.
pub fn codes(key: Key, down: bool) -> Vec<u8> {
    let mut v = Vec::with_capacity(3);
    if key.extended {
        v.push(0xE0);
    }
    if !down {
        v.push(0xF0);
    }
    v.push(key.code);
    v
}

/// An unknown key's message: what names look like.
pub fn unknown(name: &str) -> String {
    format!("unknown key `{name}` (keys as the browser names them: KeyA, Digit1, Enter, Space, ArrowUp, F1, ...)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_has_one_name_and_one_code() {
        let mut names: Vec<String> = KEYS.iter().map(|k| k.0.to_ascii_lowercase()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), KEYS.len());
        let mut codes: Vec<(u8, bool)> = KEYS.iter().map(|k| (k.1, k.2)).collect();
        codes.sort();
        codes.dedup();
        assert_eq!(codes.len(), KEYS.len());
        // board.md §7's examples.
        for (n, c) in [("KeyA", 0x1C), ("Enter", 0x5A), ("Space", 0x29), ("Escape", 0x76)] {
            assert_eq!(Key::named(n).map(|k| (k.code, k.extended)), Some((c, false)));
        }
        for (n, c) in [("ArrowUp", 0x75), ("ArrowDown", 0x72), ("ArrowLeft", 0x6B), ("ArrowRight", 0x74)] {
            assert_eq!(Key::named(n).map(|k| (k.code, k.extended)), Some((c, true)));
        }
        assert!(Key::named("Hyper").is_none());
    }
}
