//! The commands, one file each.

pub mod check;
pub mod compare;
pub mod generate;
pub mod output;
pub mod solve;
