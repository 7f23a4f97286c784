//! The commands, one file each.

pub mod check;
pub mod compare;
pub mod generate;
pub mod output;
pub mod solve;
pub mod trace;

/// `n` and the noun, in the plural unless `n` is 1: "1 pair", "9 pairs".
pub fn counted(n: u64, noun: &str) -> String {
    format!("{n} {noun}{}", if n == 1 { "" } else { "s" })
}

/// A positive finite number.
pub fn positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a positive number, got `{s}`")),
    }
}

/// A count of at least 1 (clap's own range check would print `1..18446744073709551615`).
pub fn at_least_one(s: &str) -> Result<u64, String> {
    match s.parse::<u64>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!("expected a whole number of at least 1, got `{s}`")),
    }
}
