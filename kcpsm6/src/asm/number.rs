//! Number forms (spec §4.1): hex with exactly the field's digit count, `nn'd` decimal,
//! `bbbb'b` binary with the full digit count.

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Num {
    Hex,
    Dec,
    Bin,
}

/// Parse `text` as a number for a field of `hex_digits` hex digits and `bits` bits.
/// `None` if it is not written as a number (it may be a name); `Some(Err)` if it is a
/// malformed or out-of-range number.
pub fn parse_num(text: &str, hex_digits: usize, bits: u32) -> Option<Result<u32, String>> {
    let max = (1u64 << bits) - 1;
    let lower = text.to_ascii_lowercase();
    if let Some(d) = lower.strip_suffix("'d") {
        if d.is_empty() || !d.chars().all(|c| c.is_ascii_digit()) {
            return Some(Err(format!("'{text}' is not a decimal number")));
        }
        return Some(match d.parse::<u64>() {
            Ok(v) if v <= max => Ok(v as u32),
            _ => Err(format!("decimal value '{text}' is out of range 0'd-{max}'d")),
        });
    }
    if let Some(b) = lower.strip_suffix("'b") {
        if b.is_empty() || !b.chars().all(|c| c == '0' || c == '1') {
            return Some(Err(format!("'{text}' is not a binary number")));
        }
        if b.len() != bits as usize {
            return Some(Err(format!("binary value '{text}' must have exactly {bits} digits")));
        }
        return Some(Ok(u32::from_str_radix(b, 2).unwrap_or(0)));
    }
    if !text.is_empty() && text.chars().all(|c| c.is_ascii_hexdigit()) {
        if text.len() != hex_digits {
            let s = if hex_digits == 1 { "" } else { "s" };
            return Some(Err(format!("hex value '{text}' must have exactly {hex_digits} digit{s}")));
        }
        return Some(Ok(u32::from_str_radix(text, 16).unwrap_or(0)));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms() {
        assert_eq!(parse_num("7B", 2, 8), Some(Ok(0x7B)));
        assert_eq!(parse_num("7e4", 3, 12), Some(Ok(0x7E4)));
        assert_eq!(parse_num("255'd", 2, 8), Some(Ok(255)));
        assert!(parse_num("256'd", 2, 8).unwrap().is_err());
        assert_eq!(parse_num("4095'd", 3, 12), Some(Ok(4095)));
        assert_eq!(parse_num("10100011'b", 2, 8), Some(Ok(0xA3)));
        assert!(parse_num("1010'b", 2, 8).unwrap().is_err());
        assert!(parse_num("7", 2, 8).unwrap().is_err());
        assert!(parse_num("123", 2, 8).unwrap().is_err());
        assert_eq!(parse_num("loop", 3, 12), None);
        assert!(parse_num("'d", 2, 8).unwrap().is_err());
    }
}
