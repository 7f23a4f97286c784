//! The commands, one file each.

pub mod check;
pub mod generate;
pub mod solve;
