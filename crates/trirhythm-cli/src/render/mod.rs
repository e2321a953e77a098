//! Pictures: the plotting toolkit ([`plot`]) and each paper figure's drawing ([`figures`]),
//! from data the paper crate computed. Depends on [`crate::io`] (atomic files, CSV) and
//! [`crate::error`]; never on the commands.

pub mod figures;
pub mod plot;
