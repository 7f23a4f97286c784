//! The commands, one file each.

pub mod check;
pub mod compare;
pub mod generate;
pub mod output;
pub mod solve;

/// `n` and the noun, in the plural unless `n` is 1: "1 pair", "9 pairs".
pub fn counted(n: u64, noun: &str) -> String {
    format!("{n} {noun}{}", if n == 1 { "" } else { "s" })
}
