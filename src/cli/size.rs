//! A waveform's size budget (`--vcd-max`), for `botsim run` and `botsim board` alike.

/// The largest waveform written without `--vcd-max`.
pub const VCD_MAX: u64 = 2 << 30;

/// A size in bytes from `500M`, `2G`, `4096` (K, M, G: powers of 1024).
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let (num, unit) = match t.char_indices().find(|(_, c)| c.is_ascii_alphabetic()) {
        Some((i, _)) => (&t[..i], t[i..].trim_end_matches(['B', 'b'])),
        None => (t, ""),
    };
    let scale: u64 = match unit.to_ascii_uppercase().as_str() {
        "" => 1,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        _ => return Err("expected a size such as 500M or 4G".into()),
    };
    num.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .map(|v| (v * scale as f64) as u64)
        .ok_or_else(|| "expected a size such as 500M or 4G".into())
}
