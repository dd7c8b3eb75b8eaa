//! Name rules (spec §4.1): `[A-Za-z0-9_]`, not readable as a hex value, not a register name,
//! not a word the syntax reserves.

/// Condition names that would make `JUMP NZ, x` and `JUMP NZ` read differently.
/// (`C` cannot be a name anyway: it reads as hex.) Mnemonics are allowed as user names:
/// names are case-sensitive and only appear where a value or target is expected.
const RESERVED: &[&str] = &["Z", "NZ", "NC"];

/// `s0`..`sF` in any case.
pub fn is_default_reg(w: &str) -> bool {
    let b = w.as_bytes();
    b.len() == 2 && (b[0] == b's' || b[0] == b'S') && b[1].is_ascii_hexdigit()
}

/// Ok if `name` may be defined as a label, constant, register name, or a STRING/TABLE stem.
pub fn check_name(name: &str) -> Result<(), String> {
    if name.is_empty() {
        return Err("missing name".into());
    }
    if let Some(c) = name.chars().find(|c| !(c.is_ascii_alphanumeric() || *c == '_')) {
        return Err(format!(
            "'{name}' is not a valid name ('{}' is not allowed; use letters, digits and _)",
            c.escape_default()
        ));
    }
    if name.chars().all(|c| c.is_ascii_hexdigit()) {
        return Err(format!("'{name}' is not a valid name: it reads as a hex value"));
    }
    if is_default_reg(name) {
        return Err(format!("'{name}' is not a valid name: it is a register name"));
    }
    if RESERVED.iter().any(|r| r.eq_ignore_ascii_case(name)) {
        return Err(format!("'{name}' is not a valid name: it is a reserved word"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules() {
        assert!(check_name("loop_1").is_ok());
        assert!(check_name("BAD").is_err());
        assert!(check_name("cafe").is_err());
        assert!(check_name("S4").is_err());
        assert!(check_name("sub").is_ok());
        assert!(check_name("nz").is_err());
        assert!(check_name("a-b").is_err());
        assert!(check_name("s10").is_ok());
    }
}
