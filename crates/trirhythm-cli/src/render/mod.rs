//! Pictures: the plotting toolkit ([`plot`]) and each paper figure's drawing ([`figures`]),
//! from data the paper crate computed. Depends on [`crate::io`] (atomic files) only; never on
//! the commands or the arguments.

pub mod claims_table;
pub mod figures;
pub mod legend;
pub mod paper;
pub mod plot;
pub mod report;
pub mod series;
